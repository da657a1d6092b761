#include "multigrid_keeper.h"

#include <stdexcept>

#include "solve_cg.h"

namespace palpation::sim {

amg::SpMat block_rows_to_sparse(int n, const std::vector<int>& row_ptr, const std::vector<int>& col,
                                const std::vector<double>& vals) {
  if (int(row_ptr.size()) != n + 1 || vals.size() != 9 * col.size())
    throw std::runtime_error("multigrid: the block rows' sizes do not match");
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(vals.size());
  for (int i = 0; i < n; ++i) {
    const int k0 = row_ptr[std::size_t(i)], len = row_ptr[std::size_t(i) + 1] - k0;
    const double* v = vals.data() + 9 * std::size_t(k0);
    for (int r = 0; r < 3; ++r)
      for (int kk = 0; kk < len; ++kk)
        for (int c = 0; c < 3; ++c)
          t.emplace_back(3 * i + r, 3 * col[std::size_t(k0 + kk)] + c, v[3 * std::size_t(r) * std::size_t(len) + 3 * std::size_t(kk) + std::size_t(c)]);
  }
  amg::SpMat M(3 * n, 3 * n);
  M.setFromTriplets(t.begin(), t.end());
  return M;
}

amg::SpMat nodal_pressure_to_sparse(const NodalPressurePattern& pattern, int nfree, const std::vector<double>& b,
                                    const std::vector<double>& w, double scale) {
  if (b.size() != 3 * pattern.col.size() || w.size() + 1 != pattern.row_ptr.size())
    throw std::runtime_error("multigrid: the nodal-pressure term's sizes do not match its pattern");
  cg::PressureTerm<double> term;
  term.nnode = int(w.size());
  term.row_ptr = pattern.row_ptr.data();
  term.col = pattern.col.data();
  term.b = b.data();
  term.w = w.data();
  cg::BlockSystem<double> sys{};
  sys.n = nfree;
  sys.scale = scale;
  sys.pressure = &term;
  return cg::pressure_to_sparse(sys);
}

}  // namespace palpation::sim
