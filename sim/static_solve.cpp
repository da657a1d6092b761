#include "static_solve.h"

#include <stdexcept>

#include <Eigen/SparseCholesky>

#include "fem_corotational.h"

namespace palpation::sim {

Eigen::SparseMatrix<double> assemble_stiffness(const Model& m, const std::vector<Eigen::Matrix3d>* rotations,
                                               Element element) {
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
        const Eigen::Matrix3d K =
            fem::stiffness_block<double>(r[a], r[b], m.grad[e][a].dot(m.grad[e][b]), m.volume[e], lambda, m.materials.mu[e]);
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) trip.emplace_back(3 * ia + i, 3 * ib + j, K(i, j));
      }
    }
  }
  Eigen::SparseMatrix<double> K(n, n);
  K.setFromTriplets(trip.begin(), trip.end());
  if (!nodal) return K;
  // B (nnode x 3 nfree), W = diag(lambda_n / V_n), lambda_n the volume-weighted mean.
  Eigen::SparseMatrix<double> B(nn, n);
  B.setFromTriplets(btrip.begin(), btrip.end());
  Eigen::VectorXd w(nn);
  for (int i = 0; i < nn; ++i) w[i] = node_volume[i] > 0 ? node_lambda[i] / (node_volume[i] * node_volume[i]) : 0.0;
  const Eigen::SparseMatrix<double> WB = w.asDiagonal() * B;
  const Eigen::SparseMatrix<double> Kv = Eigen::SparseMatrix<double>(B.transpose()) * WB;
  return K + Kv;
}

std::vector<Eigen::Vector3d> solve_linear_static(const Model& m, const std::vector<Eigen::Vector3d>& loads,
                                                 Element element) {
  const Eigen::SparseMatrix<double> K = assemble_stiffness(m, nullptr, element);
  Eigen::VectorXd f(3 * m.num_free());
  for (int i = 0; i < m.num_free(); ++i) f.segment<3>(3 * i) = loads[m.free_nodes[i]];
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(K);
  if (ldlt.info() != Eigen::Success) throw std::runtime_error("static solve: factorisation failed (unconstrained body?)");
  const Eigen::VectorXd u = ldlt.solve(f);
  std::vector<Eigen::Vector3d> out(m.num_nodes(), Eigen::Vector3d::Zero());
  for (int i = 0; i < m.num_free(); ++i) out[m.free_nodes[i]] = u.segment<3>(3 * i);
  return out;
}

std::vector<Eigen::Vector3d> body_force_loads(const Model& m, const Eigen::Vector3d& b) {
  std::vector<Eigen::Vector3d> f(m.num_nodes(), Eigen::Vector3d::Zero());
  for (int e = 0; e < m.num_tets(); ++e)
    for (int a = 0; a < 4; ++a) f[m.tets[e][a]] += b * (m.volume[e] / 4.0);
  return f;
}

}  // namespace palpation::sim
