#include "model.h"

#include <algorithm>
#include <stdexcept>

#include <Eigen/Dense>

namespace palpation::sim {

FixedPredicate fix_base(double height) {
  return [height](const Eigen::Vector3d& p) { return p.z() <= height; };
}

void Materials::set(int e, double E, double nu) {
  young[e] = E;
  poisson[e] = nu;
  lame(E, nu, lambda[e], mu[e]);
}

int Model::block_of(int ia, int ib) const {
  if (ia < 0 || ib < 0) return -1;
  const auto begin = col.begin() + row_ptr[std::size_t(ia)];
  const auto end = col.begin() + row_ptr[std::size_t(ia) + 1];
  return static_cast<int>(std::lower_bound(begin, end, ib) - col.begin());
}

Model build_model(TetMesh mesh, const Material& tissue, const FixedPredicate& is_fixed) {
  if (std::string why = mesh.validate(); !why.empty()) throw std::invalid_argument(why);
  mesh.orient();
  Model m;
  m.mesh_tet = mesh.order_for_locality();
  m.tissue = tissue;
  m.density = tissue.density;
  const int nn = mesh.num_nodes();
  const int ne = mesh.num_tets();
  m.rest = mesh.nodes;
  m.tets = mesh.tets;
  m.region = mesh.region.empty() ? std::vector<int>(ne, 0) : mesh.region;
  m.surface = mesh.boundary_faces();
  {
    std::vector<unsigned char> on(nn, 0);
    for (const auto& f : m.surface)
      for (int v : f) on[v] = 1;
    for (int i = 0; i < nn; ++i)
      if (on[i]) m.surface_nodes.push_back(i);
  }

  m.materials.young.assign(ne, tissue.young_modulus);
  m.materials.poisson.assign(ne, tissue.poisson_ratio);
  m.tissue_young.assign(ne, tissue.young_modulus);
  m.materials.lambda.resize(ne);
  m.materials.mu.resize(ne);
  m.volume.resize(ne);
  m.grad.resize(ne);
  m.dm_inv.resize(ne);
  m.mass.assign(nn, 0.0);
  for (int e = 0; e < ne; ++e) {
    const auto& t = m.tets[e];
    Eigen::Matrix3d dm;
    for (int k = 0; k < 3; ++k) dm.col(k) = m.rest[t[k + 1]] - m.rest[t[0]];
    const double vol = dm.determinant() / 6.0;
    m.volume[e] = vol;
    m.dm_inv[e] = dm.inverse();
    // Rows of Dm^-1 are the gradients of shape functions 1..3; g0 = -(g1 + g2 + g3).
    for (int k = 0; k < 3; ++k) m.grad[e][k + 1] = m.dm_inv[e].row(k).transpose();
    m.grad[e][0] = -(m.grad[e][1] + m.grad[e][2] + m.grad[e][3]);
    lame(tissue.young_modulus, tissue.poisson_ratio, m.materials.lambda[e], m.materials.mu[e]);
    for (int k = 0; k < 4; ++k) m.mass[t[k]] += tissue.density * vol / 4.0;
  }

  m.fixed.assign(nn, 0);
  m.dof.assign(nn, -1);
  for (int i = 0; i < nn; ++i) {
    if (is_fixed && is_fixed(m.rest[i])) {
      m.fixed[i] = 1;
    } else {
      m.dof[i] = static_cast<int>(m.free_nodes.size());
      m.free_nodes.push_back(i);
    }
  }
  if (m.free_nodes.empty()) throw std::invalid_argument("every node is fixed");

  // Block sparsity over free nodes.
  const int nf = m.num_free();
  std::vector<std::vector<int>> adj(nf);
  for (const auto& t : m.tets)
    for (int a = 0; a < 4; ++a) {
      const int ia = m.dof[t[a]];
      if (ia < 0) continue;
      for (int b = 0; b < 4; ++b) {
        const int ib = m.dof[t[b]];
        if (ib >= 0) adj[ia].push_back(ib);
      }
    }
  m.row_ptr.assign(nf + 1, 0);
  for (int i = 0; i < nf; ++i) {
    auto& r = adj[i];
    r.push_back(i);
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    m.row_ptr[i + 1] = m.row_ptr[i] + static_cast<int>(r.size());
  }
  m.col.resize(m.row_ptr[nf]);
  m.diag_block.resize(nf);
  for (int i = 0; i < nf; ++i) {
    std::copy(adj[i].begin(), adj[i].end(), m.col.begin() + m.row_ptr[i]);
    m.diag_block[i] =
        m.row_ptr[i] + static_cast<int>(std::lower_bound(adj[i].begin(), adj[i].end(), i) - adj[i].begin());
  }
  m.tet_block.resize(ne);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) m.tet_block[e][a * 4 + b] = m.block_of(m.dof[m.tets[e][a]], m.dof[m.tets[e][b]]);

  // Greedy element colouring over shared nodes.
  std::vector<std::vector<int>> node_colours(nn);
  for (int e = 0; e < ne; ++e) {
    int c = 0;
    for (;; ++c) {
      bool clash = false;
      for (int v : m.tets[e]) {
        const auto& used = node_colours[v];
        if (std::find(used.begin(), used.end(), c) != used.end()) {
          clash = true;
          break;
        }
      }
      if (!clash) break;
    }
    if (c >= static_cast<int>(m.colours.size())) m.colours.resize(c + 1);
    m.colours[c].push_back(e);
    for (int v : m.tets[e]) node_colours[v].push_back(c);
  }
  return m;
}

}  // namespace palpation::sim
