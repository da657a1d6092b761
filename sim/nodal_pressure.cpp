#include "nodal_pressure.h"

#include <algorithm>
#include <stdexcept>

namespace palpation::sim {

int NodalPressurePattern::pair_of(int n, int j) const {
  const auto first = col.begin() + row_ptr[std::size_t(n)], last = col.begin() + row_ptr[std::size_t(n) + 1];
  const auto at = std::lower_bound(first, last, j);
  return at == last || *at != j ? -1 : static_cast<int>(at - col.begin());
}

NodalPressurePattern build_nodal_pressure_pattern(const Model& m) {
  const int nn = m.num_nodes(), nf = m.num_free(), ne = m.num_tets();
  NodalPressurePattern p;
  // Free neighbours of each node (itself included when free), sorted.
  std::vector<std::vector<int>> adj(nn);
  for (const auto& t : m.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        if (m.dof[t[b]] >= 0) adj[t[a]].push_back(m.dof[t[b]]);
  p.row_ptr.assign(nn + 1, 0);
  for (int n = 0; n < nn; ++n) {
    auto& r = adj[n];
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    p.row_ptr[n + 1] = p.row_ptr[n] + static_cast<int>(r.size());
  }
  p.col.reserve(p.row_ptr[nn]);
  for (const auto& r : adj) p.col.insert(p.col.end(), r.begin(), r.end());
  p.tet_pair.resize(ne);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        const int j = m.dof[m.tets[e][b]];
        p.tet_pair[e][4 * a + b] = j < 0 ? -1 : p.pair_of(m.tets[e][a], j);
      }
  // Transpose: by free node j, its pressure nodes n in increasing order.
  p.t_row_ptr.assign(nf + 1, 0);
  for (int j : p.col) ++p.t_row_ptr[j + 1];
  for (int j = 0; j < nf; ++j) p.t_row_ptr[j + 1] += p.t_row_ptr[j];
  p.t_node.resize(p.col.size());
  p.t_pair.resize(p.col.size());
  std::vector<int> fill(p.t_row_ptr.begin(), p.t_row_ptr.end() - 1);
  for (int n = 0; n < nn; ++n)
    for (int k = p.row_ptr[n]; k < p.row_ptr[n + 1]; ++k) {
      const int slot = fill[p.col[k]]++;
      p.t_node[slot] = n;
      p.t_pair[slot] = k;
    }
  // The block order. Pair (n, j) exists where n and j share an element, as block
  // (dof n, j) does: a free n's pairs are blocks of its row (checked here: the product by
  // block rows relies on it).
  std::vector<std::vector<std::pair<int, int>>> fixed_of(nf);  // per free j: (n, pair)
  for (int n = 0; n < nn; ++n) {
    const int i = m.dof[n];
    if (i < 0 && p.row_ptr[n + 1] > p.row_ptr[n]) p.fixed_rows.push_back(n);
    for (int k = p.row_ptr[n]; k < p.row_ptr[n + 1]; ++k) {
      if (i < 0) {
        fixed_of[p.col[k]].emplace_back(n, k);
        continue;
      }
      const int j = p.col[k];
      const int blk = m.block_of(i, j), tblk = m.block_of(j, i);
      if (blk >= m.row_ptr[i + 1] || m.col[blk] != j || tblk >= m.row_ptr[j + 1] || m.col[tblk] != i)
        throw std::logic_error("nodal pressure: a pair of free nodes without its stiffness block");
    }
  }
  p.ft_row_ptr.assign(nf + 1, 0);
  for (int j = 0; j < nf; ++j) {
    p.ft_row_ptr[j + 1] = p.ft_row_ptr[j] + static_cast<int>(fixed_of[j].size());
    for (const auto& [n, k] : fixed_of[j]) {
      p.ft_node.push_back(n);
      p.ft_pair.push_back(k);
    }
  }
  p.node_volume.assign(nn, 0.0);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < 4; ++a) p.node_volume[m.tets[e][a]] += 0.25 * m.volume[e];
  return p;
}

std::vector<double> nodal_pressure_weights(const Model& m, const NodalPressurePattern& p,
                                           const std::vector<double>& lambda) {
  std::vector<double> w(m.num_nodes(), 0.0);
  for (int e = 0; e < m.num_tets(); ++e)
    for (int a = 0; a < 4; ++a) w[m.tets[e][a]] += 0.25 * m.volume[e] * lambda[e];
  // sum (V_e / 4) lambda_e = lambda_n V_n, so w_n = lambda_n / V_n = that / V_n^2.
  for (int n = 0; n < m.num_nodes(); ++n) {
    const double vn = p.node_volume[n];
    w[n] = vn > 0 ? w[n] / (vn * vn) : 0.0;
  }
  return w;
}

}  // namespace palpation::sim
