#include "static_solve.h"

#include <stdexcept>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>

#include "amg.h"

#include "fem_corotational.h"

namespace palpation::sim {

namespace {

/// The stiffness in two parts: K (for the nodal-pressure element without its volumetric
/// term) and, for that element, the volumetric term B^T W B (else empty).
void assemble_parts(const Model& m, const std::vector<Eigen::Matrix3d>* rotations, Element element,
                    Eigen::SparseMatrix<double>& K, Eigen::SparseMatrix<double>& Kv) {
  const int n = 3 * m.num_free(), nn = m.num_nodes();
  const bool nodal = resolve_element(element, m.tissue.poisson_ratio) == Element::NodalPressure;
  std::vector<Eigen::Triplet<double>> trip, btrip;
  std::vector<double> node_volume(nn, 0.0), node_lambda(nn, 0.0);
  trip.reserve(std::size_t(m.num_tets()) * 144);
  for (int e = 0; e < m.num_tets(); ++e) {
    const Eigen::Matrix3d R = rotations ? (*rotations)[e] : Eigen::Matrix3d::Identity();
    Eigen::Vector3d r[4];
    for (int a = 0; a < 4; ++a) r[a] = R * m.grad[e][a];
    const double lambda = nodal ? 0.0 : m.materials.lambda[e];
    if (nodal)
      for (int a = 0; a < 4; ++a) {
        const int node = m.tets[e][a];
        node_volume[node] += m.volume[e] / 4;
        node_lambda[node] += m.volume[e] / 4 * m.materials.lambda[e];
        for (int b = 0; b < 4; ++b) {
          const int ib = m.dof[m.tets[e][b]];
          if (ib < 0) continue;
          for (int k = 0; k < 3; ++k) btrip.emplace_back(node, 3 * ib + k, m.volume[e] / 4 * r[b][k]);
        }
      }
    for (int a = 0; a < 4; ++a) {
      const int ia = m.dof[m.tets[e][a]];
      if (ia < 0) continue;
      for (int b = 0; b < 4; ++b) {
        const int ib = m.dof[m.tets[e][b]];
        if (ib < 0) continue;
        const Eigen::Matrix3d Kab =
            fem::stiffness_block<double>(r[a], r[b], m.grad[e][a].dot(m.grad[e][b]), m.volume[e], lambda, m.materials.mu[e]);
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) trip.emplace_back(3 * ia + i, 3 * ib + j, Kab(i, j));
      }
    }
  }
  K = Eigen::SparseMatrix<double>(n, n);
  K.setFromTriplets(trip.begin(), trip.end());
  Kv = Eigen::SparseMatrix<double>(n, n);
  if (!nodal) return;
  // B (nnode x 3 nfree), W = diag(lambda_n / V_n), lambda_n the volume-weighted mean.
  Eigen::SparseMatrix<double> B(nn, n);
  B.setFromTriplets(btrip.begin(), btrip.end());
  Eigen::VectorXd w(nn);
  for (int i = 0; i < nn; ++i) w[i] = node_volume[i] > 0 ? node_lambda[i] / (node_volume[i] * node_volume[i]) : 0.0;
  const Eigen::SparseMatrix<double> WB = w.asDiagonal() * B;
  Kv = Eigen::SparseMatrix<double>(B.transpose()) * WB;
}

Eigen::VectorXd free_loads(const Model& m, const std::vector<Eigen::Vector3d>& loads) {
  Eigen::VectorXd f(3 * m.num_free());
  for (int i = 0; i < m.num_free(); ++i) f.segment<3>(3 * i) = loads[m.free_nodes[i]];
  return f;
}

std::vector<Eigen::Vector3d> node_displacements(const Model& m, const Eigen::VectorXd& u) {
  std::vector<Eigen::Vector3d> out(m.num_nodes(), Eigen::Vector3d::Zero());
  for (int i = 0; i < m.num_free(); ++i) out[m.free_nodes[i]] = u.segment<3>(3 * i);
  return out;
}

}  // namespace

Eigen::SparseMatrix<double> assemble_stiffness(const Model& m, const std::vector<Eigen::Matrix3d>* rotations,
                                               Element element) {
  Eigen::SparseMatrix<double> K, Kv;
  assemble_parts(m, rotations, element, K, Kv);
  return Kv.nonZeros() ? Eigen::SparseMatrix<double>(K + Kv) : K;
}

std::vector<Eigen::Vector3d> solve_linear_static(const Model& m, const std::vector<Eigen::Vector3d>& loads,
                                                 Element element) {
  const Eigen::SparseMatrix<double> K = assemble_stiffness(m, nullptr, element);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(K);
  if (ldlt.info() != Eigen::Success) throw std::runtime_error("static solve: factorisation failed (unconstrained body?)");
  return node_displacements(m, ldlt.solve(free_loads(m, loads)));
}

std::vector<Eigen::Vector3d> solve_linear_static_multigrid(const Model& m, const std::vector<Eigen::Vector3d>& loads,
                                                           Element element, double tolerance, int* iterations) {
  Eigen::SparseMatrix<double> K, Kv;
  assemble_parts(m, nullptr, element, K, Kv);
  const amg::SpMat A = Kv.nonZeros() ? amg::SpMat(K + Kv) : amg::SpMat(K);
  const amg::SpMat sparser = K;
  std::vector<Eigen::Vector3d> nodes;
  for (int node : m.free_nodes) nodes.push_back(m.rest[node]);
  amg::Options opt;
  opt.keep_finest = true;
  amg::Hierarchy levels;
  levels.build(A, nodes, opt, Kv.nonZeros() ? &sparser : nullptr);
  Eigen::ConjugateGradient<amg::SpMat, Eigen::Lower | Eigen::Upper, amg::EigenPreconditioner> cg;
  cg.setTolerance(tolerance);
  cg.setMaxIterations(5000);
  cg.preconditioner().attach(&levels);
  cg.compute(A);
  const Eigen::VectorXd u = cg.solve(free_loads(m, loads));
  if (iterations) *iterations = int(cg.iterations());
  if (cg.info() != Eigen::Success || !(cg.error() <= tolerance))
    throw std::runtime_error("static solve (multigrid CG): relative residual " + std::to_string(cg.error()) + " after " +
                             std::to_string(cg.iterations()) + " iterations, not " + std::to_string(tolerance));
  return node_displacements(m, u);
}

std::vector<Eigen::Vector3d> body_force_loads(const Model& m, const Eigen::Vector3d& b) {
  std::vector<Eigen::Vector3d> f(m.num_nodes(), Eigen::Vector3d::Zero());
  for (int e = 0; e < m.num_tets(); ++e)
    for (int a = 0; a < 4; ++a) f[m.tets[e][a]] += b * (m.volume[e] / 4.0);
  return f;
}

}  // namespace palpation::sim
