// The preconditioned CG against Eigen's sparse Cholesky on the same system.
#include <QtTest>

#include <algorithm>
#include <random>

#include <Eigen/SparseCholesky>

#include "model.h"
#include "nodal_pressure.h"
#include "solve_cg.h"
#include "static_solve.h"

using namespace palpation::sim;

namespace {

// The implicit-Euler system of a box at rest: (1 + h alpha) M + (h^2 + h beta) K, in
// block CSR (as the backends build it) and as an Eigen sparse matrix.
struct System {
  Model m;
  std::vector<double> blocks;
  Eigen::SparseMatrix<double> A;
};

System make_system(double h) {
  System s;
  s.m = build_model(make_box_mesh(Eigen::Vector3d(0.06, 0.04, 0.03), 12, 8, 6), Material{19000, 0.45, 1000}, fix_base());
  Eigen::SparseMatrix<double> K = assemble_stiffness(s.m);
  const double ks = h * h + h * 0.002, ms = 1.0 + h * 1.0;
  s.A = ks * K;
  for (int i = 0; i < s.m.num_free(); ++i)
    for (int k = 0; k < 3; ++k) s.A.coeffRef(3 * i + k, 3 * i + k) += ms * s.m.mass[s.m.free_nodes[i]];
  s.blocks.assign(9 * std::size_t(s.m.num_blocks()) + 1, 0.0);  // + 1: cg::multiply reads one past a block
  for (int i = 0; i < s.m.num_free(); ++i)
    for (int k = s.m.row_ptr[i]; k < s.m.row_ptr[i + 1]; ++k) {
      const int j = s.m.col[k];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) s.blocks[9 * std::size_t(k) + r + 3 * c] = s.A.coeff(3 * i + r, 3 * j + c);  // column-major
    }
  return s;
}

}  // namespace

class TestSolveCg : public QObject {
  Q_OBJECT
 private slots:
  // Relative residual 1e-12 bounds the relative error by cond(A) * 1e-12; cond(A) of this
  // system is below 1e4 (mass-dominated at h = 1 ms), so 1e-7 is a safe bound.
  void matchesSparseCholesky() {
    const System s = make_system(0.001);
    const int n = 3 * s.m.num_free();
    std::mt19937 rng(3);
    std::normal_distribution<double> nd;
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) b[i] = nd(rng);
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(s.A);
    QCOMPARE(ldlt.info(), Eigen::Success);
    const Eigen::VectorXd x_ref = ldlt.solve(b);

    std::vector<double> x(n, 0.0);
    cg::BlockSystem<double> sys{s.m.num_free(), s.m.row_ptr.data(), s.m.col.data(), s.blocks.data()};
    cg::Workspace<double> w;
    const auto res = cg::solve(sys, b.data(), x.data(), 1e-12, 10000, w, false);
    QVERIFY(res.converged);
    const double err = (Eigen::Map<Eigen::VectorXd>(x.data(), n) - x_ref).norm() / x_ref.norm();
    qInfo("CG: %d iterations, relative error %.2e vs LDLT", res.iterations, err);
    QVERIFY2(err < 1e-7, qPrintable(QString::number(err)));

    // Warm start from the solution: nothing left to do.
    const auto again = cg::solve(sys, b.data(), x.data(), 1e-10, 10000, w, false);
    QCOMPARE(again.iterations, 0);

    // The parallel path gives the same answer (reductions in another order: round-off).
    std::vector<double> xp(n, 0.0);
    const auto rp = cg::solve(sys, b.data(), xp.data(), 1e-12, 10000, w, true);
    QVERIFY(rp.converged);
    const double errp = (Eigen::Map<Eigen::VectorXd>(xp.data(), n) - x_ref).norm() / x_ref.norm();
    QVERIFY2(errp < 1e-7, qPrintable(QString::number(errp)));
  }

  // A stiffness-dominated system (h = 0.1 s, static-like) still converges, in more
  // iterations: the iteration cap is honoured and reported.
  void capIsHonoured() {
    const System s = make_system(0.1);
    const int n = 3 * s.m.num_free();
    std::vector<double> b(n, 1.0), x(n, 0.0);
    cg::BlockSystem<double> sys{s.m.num_free(), s.m.row_ptr.data(), s.m.col.data(), s.blocks.data()};
    cg::Workspace<double> w;
    const auto capped = cg::solve(sys, b.data(), x.data(), 1e-14, 7, w, false);
    QCOMPARE(capped.iterations, 7);
    QVERIFY(!capped.converged);
    std::fill(x.begin(), x.end(), 0.0);
    const auto full = cg::solve(sys, b.data(), x.data(), 1e-10, 100000, w, false);
    QVERIFY(full.converged);
    QVERIFY(full.iterations > 7);
  }

  // Float precision: the same system to 1e-5 relative residual; the error against the
  // double solution is bounded by cond * 1e-5.
  void floatSolves() {
    const System s = make_system(0.001);
    const int n = 3 * s.m.num_free();
    Eigen::VectorXd b = Eigen::VectorXd::Ones(n);
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(s.A);
    const Eigen::VectorXd x_ref = ldlt.solve(b);
    std::vector<float> bf(n, 1.0f), xf(n, 0.0f), blocks(s.blocks.begin(), s.blocks.end());
    cg::BlockSystem<float> sys{s.m.num_free(), s.m.row_ptr.data(), s.m.col.data(), blocks.data()};
    cg::Workspace<float> w;
    const auto res = cg::solve(sys, bf.data(), xf.data(), 1e-5f, 10000, w, false);
    QVERIFY(res.converged);
    double num = 0;
    for (int i = 0; i < n; ++i) num += (xf[i] - x_ref[i]) * (xf[i] - x_ref[i]);
    const double err = std::sqrt(num) / x_ref.norm();
    QVERIFY2(err < 1e-3, qPrintable(QString::number(err)));
  }

  // The product with the nodal-pressure term B^T W B three ways: by block rows with the
  // couplings laid out in the blocks' order (what the CPU backend runs), on one thread and
  // on several, and by the pressures and a gather through the pairs' by-free-row index (a
  // term without the layout), all against the same term as an Eigen sparse matrix. Only
  // the order of the sums differs: about 30 terms of order 1 a row, so 1e-12 of the
  // largest entry is a thousand times their rounding; a lost or doubled pair moves an
  // entry by order 1. The chest wall's pressure rows (fixed nodes acting on their free
  // neighbours) take their own path in the block layout: the mesh has them.
  void pressureProductMatchesSparse() {
    const System s = make_system(0.001);
    const int nf = s.m.num_free(), nn = s.m.num_nodes(), n = 3 * nf;
    const NodalPressurePattern pat = build_nodal_pressure_pattern(s.m);
    QVERIFY(!pat.fixed_rows.empty() && !pat.ft_pair.empty());
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<double> b(3 * std::size_t(pat.num_pairs())), w(nn), pi(nn), pif(nf), x(n);
    for (double& v : b) v = u(rng);
    for (double& v : w) v = 1.0 + u(rng) * 0.5;
    for (double& v : x) v = u(rng);
    std::vector<double> bb(3 * std::size_t(s.m.num_blocks()) + 1, 0.0), bt(bb.size(), 0.0);
    couplings_to_block_order(s.m, pat, b.data(), bb.data(), bt.data());
    cg::PressureTerm<double> P{nn, pat.row_ptr.data(), pat.col.data(), pat.t_row_ptr.data(), pat.t_node.data(),
                               pat.t_pair.data(), b.data(), w.data(), pi.data()};
    cg::BlockSystem<double> sys{nf, s.m.row_ptr.data(), s.m.col.data(), s.blocks.data()};
    sys.scale = 0.5;
    sys.pressure = &P;
    const amg::SpMat M = cg::to_sparse(sys) + cg::pressure_to_sparse(sys);
    const Eigen::VectorXd ref = M * Eigen::Map<const Eigen::VectorXd>(x.data(), n);
    QVERIFY(ref.norm() > 0);
    auto error_of = [&](bool parallel) {
      std::vector<double> y(n);
      double xy = 0;
      cg::multiply(sys, x.data(), y.data(), parallel, &xy);
      const Eigen::Map<const Eigen::VectorXd> xv(x.data(), n);
      const double e = (Eigen::Map<const Eigen::VectorXd>(y.data(), n) - ref).cwiseAbs().maxCoeff();
      const double exy = std::abs(xy - xv.dot(ref));  // the fused x . y with it
      return std::max(e / ref.cwiseAbs().maxCoeff(), exy / (xv.norm() * ref.norm()));
    };
    const double gathered = error_of(false);
    cg::set_block_layout(P, pat, s.m.free_nodes.data(), bb.data(), bt.data(), pif.data());
    const double blocks = error_of(false), threads = error_of(true);
    qInfo("largest error against the sparse product: by blocks %.2e, threads %.2e, gathered %.2e", blocks, threads,
          gathered);
    QVERIFY2(blocks <= 1e-12, qPrintable(QString::number(blocks)));
    QVERIFY2(threads <= 1e-12, qPrintable(QString::number(threads)));
    QVERIFY2(gathered <= 1e-12, qPrintable(QString::number(gathered)));
  }

  // The product through the upper triangle (cg::UpperBlocks, one thread) is the same
  // product: entry (i, c), c >= i, holds A_ci and the couplings at block (i, c), and each
  // serves both (i, c) and (c, i). Against the sparse matrix of the full blocks and the
  // pressure term (with the chest wall's fixed rows), with a mass diagonal, with and without
  // the term, twice in a row (the scratch must be left clear). The same 1e-12 as above: only
  // the order of the sums differs. A block served to the wrong side (A_ic for A_ci) breaks
  // it, as the blocks here are not symmetric one by one.
  void upperTriangleProductMatchesSparse() {
    const System s = make_system(0.001);
    const int nf = s.m.num_free(), nn = s.m.num_nodes(), n = 3 * nf;
    const NodalPressurePattern pat = build_nodal_pressure_pattern(s.m);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<double> b(3 * std::size_t(pat.num_pairs())), w(nn), pi(nn), pif(nf), x(n + 1), diag(9 * std::size_t(nf) + 1);
    for (double& v : b) v = u(rng);
    for (double& v : w) v = 1.0 + u(rng) * 0.5;
    for (double& v : x) v = u(rng);  // x[n]: the padding an upper product may read, not used
    for (double& v : diag) v = u(rng);
    // A symmetric matrix whose blocks are not: A_ci = A_ic^T, random.
    std::vector<double> blocks(9 * std::size_t(s.m.num_blocks()) + 1, 0.0);
    for (int i = 0; i < nf; ++i)
      for (int k = s.m.row_ptr[i]; k < s.m.row_ptr[i + 1]; ++k) {
        const int c = s.m.col[k];
        if (c < i) continue;
        const std::size_t kt = std::size_t(s.m.block_of(c, i));
        for (int r = 0; r < 3; ++r)
          for (int q = 0; q < 3; ++q) {
            const double v = c == i && q < r ? blocks[9 * std::size_t(k) + 3 * r + q] : u(rng);  // the diagonal symmetric
            blocks[9 * std::size_t(k) + r + 3 * q] = v;
            blocks[9 * kt + q + 3 * r] = v;
          }
      }
    std::vector<double> bb(3 * std::size_t(s.m.num_blocks()) + 1, 0.0), bt(bb.size(), 0.0);
    couplings_to_block_order(s.m, pat, b.data(), bb.data(), bt.data());
    // The upper triangle as the layout says.
    std::vector<int> urow{0}, ucol;
    std::vector<double> ublocks, ubb, ubt;
    for (int i = 0; i < nf; ++i) {
      for (int k = s.m.row_ptr[i]; k < s.m.row_ptr[i + 1]; ++k) {
        const int c = s.m.col[k];
        if (c < i) continue;
        ucol.push_back(c);
        const std::size_t kt = std::size_t(s.m.block_of(c, i));
        for (int q = 0; q < 9; ++q) ublocks.push_back(blocks[9 * kt + q]);
        for (int q = 0; q < 3; ++q) {
          ubb.push_back(bb[3 * std::size_t(k) + q]);
          ubt.push_back(bt[3 * std::size_t(k) + q]);
        }
      }
      urow.push_back(int(ucol.size()));
    }
    ublocks.push_back(0.0);
    ubb.push_back(0.0);
    ubt.push_back(0.0);
    std::vector<double> scatter(4 * std::size_t(nf), 0.0);
    const cg::UpperBlocks<double> U{urow.data(), ucol.data(), ublocks.data(), ubb.data(), ubt.data(), scatter.data()};
    cg::PressureTerm<double> P{nn, pat.row_ptr.data(), pat.col.data(), pat.t_row_ptr.data(), pat.t_node.data(),
                               pat.t_pair.data(), b.data(), w.data(), pi.data()};
    cg::set_block_layout(P, pat, s.m.free_nodes.data(), bb.data(), bt.data(), pif.data());
    for (const bool with_pressure : {false, true}) {
      cg::BlockSystem<double> sys{nf, s.m.row_ptr.data(), s.m.col.data(), blocks.data()};
      sys.scale = 0.5;
      sys.diag = diag.data();
      if (with_pressure) sys.pressure = &P;
      amg::SpMat M = cg::to_sparse(sys) + cg::pressure_to_sparse(sys);
      const Eigen::Map<const Eigen::VectorXd> xv(x.data(), n);
      const Eigen::VectorXd ref = M * xv;
      QVERIFY(ref.norm() > 0);
      sys.upper = &U;
      for (int rep = 0; rep < 2; ++rep) {
        std::vector<double> y(n);
        double xy = 0;
        cg::multiply(sys, x.data(), y.data(), false, &xy);
        const double e = (Eigen::Map<const Eigen::VectorXd>(y.data(), n) - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
        const double exy = std::abs(xy - xv.dot(ref)) / (xv.norm() * ref.norm());
        qInfo("pressure term %d, product %d: largest error %.2e, x . y %.2e", int(with_pressure), rep + 1, e, exy);
        QVERIFY2(e <= 1e-12, qPrintable(QString::number(e)));
        QVERIFY2(exy <= 1e-12, qPrintable(QString::number(exy)));
      }
      QVERIFY(std::all_of(scatter.begin(), scatter.end(), [](double v) { return v == 0.0; }));
    }
  }
};

QTEST_APPLESS_MAIN(TestSolveCg)
#include "tst_solve_cg.moc"
