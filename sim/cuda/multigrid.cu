// The multigrid levels copied to the device (see multigrid.cuh).
#include "cuda/multigrid.cuh"

#include <stdexcept>
#include <string>
#include <vector>

namespace palpation::sim::cuda {

int csr_lanes(long rows, long nonzeros, long threads) {
  if (rows <= 0) return kGroup;
  const double mean = double(nonzeros) / double(rows);
  if (mean >= 128 && rows <= 4096) return kBlockPerRow;
  return mean < 12 && rows * kGroup > threads ? 2 : kGroup;
}

CsrDev MultigridDevice::csr(const amg::SpMat& M, cudaStream_t s, long threads, int lanes, bool single) {
  CsrDev d;
  d.rows = int(M.rows());
  auto& ptr = mats_->ints.emplace_back();
  ptr.upload(M.outerIndexPtr(), std::size_t(M.rows()) + 1, s);
  auto& col = mats_->ints.emplace_back();
  col.upload(M.innerIndexPtr(), std::size_t(M.nonZeros()), s);
  d.ptr = ptr.get();
  d.col = col.get();
  if (single) {
    auto& val = mats_->flts.emplace_back();
    val.upload(std::vector<float>(M.valuePtr(), M.valuePtr() + M.nonZeros()), s);  // waits for the copy
    d.val32 = val.get();
  } else {
    auto& val = mats_->dbls.emplace_back();
    val.upload(M.valuePtr(), std::size_t(M.nonZeros()), s);
    d.val = val.get();
  }
  d.lanes = lanes >= 0 ? lanes : csr_lanes(M.rows(), M.nonZeros(), threads);
  return d;
}

double* MultigridDevice::vec(int n) {
  auto& v = vecs_.emplace_back();
  v.alloc(std::size_t(n));
  return v.get();
}

void MultigridDevice::own_vectors(cudaStream_t s) {
  vecs_.clear();
  for (int k = 1; k < host_.levels; ++k) {
    MgLevelDev& l = host_.lv[k];
    l.b = vec(l.n);
    l.x = vec(l.n);
    l.r = vec(l.n);
    l.d = vec(l.n);
  }
  desc_.upload(&host_, 1, s);
}

void MultigridDevice::borrow(const MultigridDevice& owner, cudaStream_t s, bool single) {
  if (!owner.mats_) throw std::logic_error("cuda multigrid: no levels to borrow");
  if (owner.single_ != single)
    throw std::logic_error(std::string("cuda multigrid: levels uploaded in ") + (owner.single_ ? "float" : "double") +
                           " borrowed by a solve in " + (single ? "float" : "double"));
  if (mats_ == owner.mats_) return;  // these levels already, with vectors of this one's own
  CU(cudaStreamSynchronize(s));      // this one's earlier solves may still read its old vectors
  mats_ = owner.mats_;
  host_ = owner.host_;
  single_ = owner.single_;
  own_vectors(s);
}

void MultigridDevice::upload(const amg::Hierarchy& h, cudaStream_t s, long threads, int lanes, bool single) {
  const auto& levels = h.levels();
  const int L = int(levels.size());
  if (L < 2 || L > kMgMaxLevels)
    throw std::runtime_error("cuda multigrid: " + std::to_string(L) + " levels (2 to " + std::to_string(kMgMaxLevels) +
                             " run on the GPU)");
  for (const auto& lv : levels)
    if (lv.smoothing.steps() > kMgMaxSteps)
      throw std::runtime_error("cuda multigrid: a smoothing of degree " + std::to_string(lv.smoothing.steps()) +
                               " (at most " + std::to_string(kMgMaxSteps) + " on the GPU)");
  CU(cudaStreamSynchronize(s));  // the kernels of earlier steps may still read the old levels
  mats_ = std::make_shared<Matrices>();  // the old ones stay while another backend borrows them
  MgDev m;
  m.levels = L;
  for (int k = 0; k < L; ++k) {
    const auto& src = levels[std::size_t(k)];
    MgLevelDev& dst = m.lv[k];
    dst.n = k == 0 ? int(src.P.rows()) : int(src.A.rows());
    if (k > 0) dst.A = csr(src.A, s, threads, lanes, single);
    if (k + 1 < L) {
      if (k > 0) dst.Dinv = csr(src.Dinv, s, threads, lanes, single);
      dst.P = csr(src.P, s, threads, lanes, single);
      dst.R = csr(src.R, s, threads, lanes, single);
      dst.steps = src.smoothing.steps();
      for (int j = 0; j < dst.steps; ++j) {
        dst.a[j] = src.smoothing.a[std::size_t(j)];
        dst.c[j] = src.smoothing.c[std::size_t(j)];
      }
    }
  }
  // The coarsest solve as one more matrix: its inverse, every row full.
  const Eigen::MatrixXd inv = h.coarsest_inverse();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(std::size_t(inv.size()));
  for (Eigen::Index i = 0; i < inv.rows(); ++i)
    for (Eigen::Index j = 0; j < inv.cols(); ++j) t.emplace_back(int(i), int(j), inv(i, j));
  amg::SpMat dense(inv.rows(), inv.cols());
  dense.setFromTriplets(t.begin(), t.end());
  dense.makeCompressed();
  m.coarsest_inverse = csr(dense, s, threads, lanes, single);
  host_ = m;
  single_ = single;
  own_vectors(s);
}

}  // namespace palpation::sim::cuda
