// Sparsity and weights of the average-nodal-pressure volumetric term (Bonet & Burton 1998,
// "A simple average nodal pressure tetrahedral element for incompressible and nearly
// incompressible dynamic explicit applications", Commun. Numer. Meth. Engng 14:437).
//
// The linear tetrahedron has one volumetric strain per element, so as Poisson's ratio
// approaches 0.5 each element's volume is held on its own and the mesh locks (too stiff,
// and CG needs many more iterations). Averaging the volumetric strain over the elements
// around each node spreads the constraint over the patch instead:
//   theta_e = tr(R_e^T F_e) - 3                          element volumetric strain
//   theta_n = sum_{e at n} (V_e / 4) theta_e / V_n        V_n = sum_{e at n} V_e / 4
//   energy  = sum_n lambda_n V_n theta_n^2 / 2            lambda_n: mean of lambda_e by volume
// while the shear part (2 mu eps) stays per element. With b_nj = sum_{e at n and j}
// (V_e / 4) R_e g_{e,j} (the pair's coupling vector) the term's stiffness is B^T W B,
// (B u)_n = sum_j b_nj . u_j, W = diag(lambda_n / V_n): rows over every node (the chest
// wall's pressures act on their free neighbours), columns over the free nodes. B has the
// node-adjacency pattern of K, while B^T W B reaches two rings of nodes, so it is kept
// factored and applied as two sparse products (solve_cg.h) rather than assembled.
#pragma once

#include <array>
#include <vector>

#include "model.h"

namespace palpation::sim {

struct NodalPressurePattern {
  // Pressure rows: every node n; entries: the free nodes j that share an element with n.
  std::vector<int> row_ptr;  // (nnode + 1)
  std::vector<int> col;      // (npair) free index of j
  // The same pairs by free node j: the pressure node n and the pair's index.
  std::vector<int> t_row_ptr;  // (nfree + 1)
  std::vector<int> t_node;     // (npair) n
  std::vector<int> t_pair;     // (npair) index of the pair (n, j)
  // Pair of element e's nodes (a, b) at 4 a + b, -1 when node b is fixed.
  std::vector<std::array<int, 4 * 4>> tet_pair;  // (ntet)
  std::vector<double> node_volume;               // (nnode) V_n, m^3
  // For a product by block rows (solve_cg.h): pair (n, j) of a free n is block (dof n, j)
  // of the block matrix (Model::col) and its transpose block (j, dof n) (the two patterns
  // are the same: checked when the pattern is built); the fixed nodes' rows stay in the
  // pair order.
  std::vector<int> fixed_rows;        // the fixed nodes with pairs
  std::vector<int> ft_row_ptr;        // (nfree + 1) free node j's pairs (n fixed, j):
  std::vector<int> ft_node, ft_pair;  // n and the pair
  int num_pairs() const { return static_cast<int>(col.size()); }
  /// The index of pair (n, j) (j a free index), -1 when n and j share no element.
  int pair_of(int n, int j) const;
};

NodalPressurePattern build_nodal_pressure_pattern(const Model& m);

/// The free rows' couplings b (pair order, 3 per pair) in the block order: bb at block
/// (i, c) b_{n(i) c}, bt at block (i, c) b_{n(c) i} (solve_cg.h's PressureTerm; bb and bt
/// hold 3 x the model's blocks and are overwritten there). The CPU backend keeps them in
/// that order as it updates them (through each element's block offsets); this is for
/// whoever holds them in the pair order (tests).
template <class T>
void couplings_to_block_order(const Model& m, const NodalPressurePattern& p, const T* b, T* bb, T* bt) {
  for (int n = 0; n < m.num_nodes(); ++n) {
    const int i = m.dof[n];
    if (i < 0) continue;
    for (int k = p.row_ptr[n]; k < p.row_ptr[n + 1]; ++k) {
      const int j = p.col[k];
      const std::size_t blk = std::size_t(m.block_of(i, j)), tblk = std::size_t(m.block_of(j, i));
      for (int c = 0; c < 3; ++c) {
        bb[3 * blk + c] = b[3 * std::size_t(k) + c];
        bt[3 * tblk + c] = b[3 * std::size_t(k) + c];
      }
    }
  }
}

/// W's diagonal, lambda_n / V_n, for per-element lambda (Pa): lambda_n is the mean of the
/// elements' lambda around n weighted by volume.
std::vector<double> nodal_pressure_weights(const Model& m, const NodalPressurePattern& p,
                                           const std::vector<double>& lambda);

}  // namespace palpation::sim
