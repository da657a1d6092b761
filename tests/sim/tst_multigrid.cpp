// The smoothed-aggregation multigrid preconditioner (sim/amg.h): the aggregation covers
// every node, the V-cycle is a symmetric positive definite operator (what CG needs), CG
// with it reaches the same solution as a sparse Cholesky, its iteration count does not
// grow with the mesh the way block-Jacobi's does, its Chebyshev smoother keeps them from
// growing more than 2x from Poisson's ratio 0.40 to 0.49, and a whole simulation with it
// (the nodal-pressure element, contact) gives block-Jacobi's forces.
#include <QtTest>

#include "relative_error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/SparseCholesky>

#include "amg.h"
#include "backend_cpu.h"
#include "model.h"
#include "multigrid_keeper.h"
#include "scenario.h"
#include "simulation.h"
#include "solve_cg.h"
#include "static_solve.h"

using namespace palpation::sim;

namespace {

// The implicit-Euler system of a box of n x (2n/3) x (n/2) cells, fixed at its base, at a
// step of 50 ms: stiffness-dominated, so block-Jacobi's iterations grow with the mesh
// (at the haptic step of 1 ms the mass makes every preconditioner look good).
struct System {
  Model m;
  std::vector<double> blocks;
  amg::SpMat A;
  std::vector<Eigen::Vector3d> nodes;  // rest positions of the free nodes
  cg::BlockSystem<double> block_system() const {
    return cg::BlockSystem<double>{m.num_free(), m.row_ptr.data(), m.col.data(), blocks.data()};
  }
};

System make_system(int n) {
  const double h = 0.05;
  System s;
  s.m = build_model(make_box_mesh(Eigen::Vector3d(0.06, 0.04, 0.03), n, 2 * n / 3, n / 2), Material{19000, 0.45, 1000},
                    fix_base());
  Eigen::SparseMatrix<double> A = (h * h + h * 0.01) * assemble_stiffness(s.m);
  for (int i = 0; i < s.m.num_free(); ++i)
    for (int k = 0; k < 3; ++k) A.coeffRef(3 * i + k, 3 * i + k) += (1.0 + h) * s.m.mass[s.m.free_nodes[i]];
  s.A = A;
  s.blocks.assign(9 * std::size_t(s.m.num_blocks()) + 1, 0.0);  // + 1: cg::multiply reads one past a block
  for (int i = 0; i < s.m.num_free(); ++i)
    for (int k = s.m.row_ptr[i]; k < s.m.row_ptr[i + 1]; ++k)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) s.blocks[9 * std::size_t(k) + r + 3 * c] = A.coeff(3 * i + r, 3 * s.m.col[k] + c);
  for (int node : s.m.free_nodes) s.nodes.push_back(s.m.rest[node]);
  return s;
}

Eigen::VectorXd random_vector(Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> nd;
  Eigen::VectorXd v(n);
  for (auto& x : v) x = nd(rng);
  return v;
}

// CG iterations to a relative residual of 1e-8 from zero, with or without the levels.
int iterations(const System& s, const amg::Hierarchy* levels) {
  const int n = 3 * s.m.num_free();
  const Eigen::VectorXd b = random_vector(n, 5);
  std::vector<double> x(n, 0.0);
  cg::Workspace<double> w;
  w.multigrid = levels;
  const auto res = cg::solve(s.block_system(), b.data(), x.data(), 1e-8, 20000, w, false);
  return res.converged ? res.iterations : -1;
}

// Any scalar system with 3 unknowns per node as cg's block CSR (every 3x3 block with an
// entry; column-major blocks, one value of padding).
struct Blocks {
  std::vector<int> row_ptr{0}, col;
  std::vector<double> values;
  cg::BlockSystem<double> system() const {
    return cg::BlockSystem<double>{int(row_ptr.size()) - 1, row_ptr.data(), col.data(), values.data()};
  }
};

Blocks to_blocks(const amg::SpMat& A) {
  Blocks b;
  for (Eigen::Index i = 0; i < A.rows() / 3; ++i) {
    std::vector<int> cols;
    for (int r = 0; r < 3; ++r)
      for (amg::SpMat::InnerIterator it(A, 3 * i + r); it; ++it) cols.push_back(int(it.col()) / 3);
    std::sort(cols.begin(), cols.end());
    cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
    for (int j : cols) {
      b.col.push_back(j);
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) b.values.push_back(A.coeff(3 * i + r, 3 * j + c));
    }
    b.row_ptr.push_back(int(b.col.size()));
  }
  b.values.push_back(0.0);
  return b;
}

// The implicit-Euler system of the nodal-pressure element (the volumetric term averaged
// over each node's elements) on a box of n x (2n/3) x (n/2) cells fixed at its base, at
// Poisson's ratio nu and a step of 50 ms; and its stiffness without the volumetric term,
// what the backend aggregates with (amg.h).
struct NodalSystem {
  amg::SpMat A, shear;
  amg::SpMat stiffness;  // A less the volumetric term: shear and mass, as the backends split it (multigrid_keeper.h)
  std::vector<Eigen::Vector3d> nodes;
};

NodalSystem make_nodal_system(int n, double nu) {
  const double h = 0.05;
  Model m = build_model(make_box_mesh(Eigen::Vector3d(0.06, 0.04, 0.03), n, 2 * n / 3, n / 2), Material{19000, nu, 1000},
                        fix_base());
  NodalSystem s;
  Eigen::SparseMatrix<double> A = (h * h + h * 0.01) * assemble_stiffness(m, nullptr, Element::NodalPressure);
  for (int i = 0; i < m.num_free(); ++i)
    for (int k = 0; k < 3; ++k) A.coeffRef(3 * i + k, 3 * i + k) += (1.0 + h) * m.mass[m.free_nodes[i]];
  s.A = A;
  Model shear = m;
  for (auto& l : shear.materials.lambda) l = 0;  // the linear element at lambda 0: the nodal element's shear part
  s.shear = amg::SpMat((h * h + h * 0.01) * assemble_stiffness(shear, nullptr, Element::Linear));
  s.stiffness = s.shear;
  for (int i = 0; i < m.num_free(); ++i)
    for (int k = 0; k < 3; ++k) s.stiffness.coeffRef(3 * i + k, 3 * i + k) += (1.0 + h) * m.mass[m.free_nodes[i]];
  for (int node : m.free_nodes) s.nodes.push_back(m.rest[node]);
  return s;
}

amg::Options chebyshev_options() {
  amg::Options o;
  o.smoother = amg::Smoother::Chebyshev;
  o.degree = 2;
  return o;
}

// A 6 x 6 x 3 cm box of nodal-pressure tissue (Poisson's ratio 0.45: the pressure term is
// in the system) in 4 mm cells, CG to 1e-6, one thread.
Scenario press_box() {
  Scenario s;
  s.source = "tst_multigrid";
  s.patient.phantom = "box";
  s.patient.resolution.clear();
  s.patient.edge = 0.004;
  s.patient.size = Eigen::Vector3d(0.06, 0.06, 0.03);
  s.young_modulus = 19000;
  s.poisson_ratio = 0.45;
  s.backend = "cpu";
  s.params.solver.cg_tolerance = 1e-6;
  s.params.solver.threads = 1;
  return s;
}

// A finger of 8 mm radius pressed into press_box() from its top at x = 5 mm, 0.1 mm a step
// of 1 ms, for `steps` steps: the raw forces (three a step) and the CG iterations in all.
struct Press {
  std::vector<double> f;
  int iterations = 0;
};
Press press(Simulation& sim, int steps) {
  std::vector<FingerInput> in(1);
  std::vector<FingerOutput> out(1);
  in[0].radius = 0.008;
  Press r;
  for (int k = 1; k <= steps; ++k) {
    in[0].position = Eigen::Vector3d(0.005, 0, 0.03 + 0.008 - 1e-4 * k);
    const auto o = sim.advance(in, out, 0.001);
    if (!o.ok) throw std::runtime_error("step " + std::to_string(k) + " diverged");
    r.iterations += o.stats.cg_iterations;
    r.f.insert(r.f.end(), out[0].force_raw.data(), out[0].force_raw.data() + 3);
  }
  return r;
}

}  // namespace

class TestMultigrid : public QObject {
  Q_OBJECT
 private slots:
  void aggregationCoversEveryNode() {
    const System s = make_system(12);
    int count = 0;
    const std::vector<int> agg = amg::aggregate(s.A, 3, amg::Options{}.strength, count);
    QCOMPARE(int(agg.size()), s.m.num_free());
    std::vector<int> size(count, 0);
    for (int a : agg) {
      QVERIFY(a >= 0 && a < count);
      ++size[a];
    }
    for (int k : size) QVERIFY(k > 0);
    // A coarser level at all: at least four nodes per aggregate on average.
    QVERIFY2(4 * count <= s.m.num_free(), qPrintable(QString("%1 aggregates of %2 nodes").arg(count).arg(s.m.num_free())));
  }

  // CG's theory needs a symmetric positive definite preconditioner; the V-cycle is one when
  // its smoothing before and after the coarse correction is the same and convergent.
  // Symmetric to round-off (1e-10 relative to |x| |M y|).
  void cycleIsSymmetricPositiveDefinite_data() {
    QTest::addColumn<int>("smoother");
    QTest::addColumn<int>("degree");
    QTest::addColumn<int>("coarse_smoother");
    QTest::newRow("one Jacobi sweep") << int(amg::Smoother::Jacobi) << 1 << int(amg::Smoother::Jacobi);
    QTest::newRow("two Jacobi sweeps") << int(amg::Smoother::Jacobi) << 2 << int(amg::Smoother::Jacobi);
    QTest::newRow("Chebyshev, degree 2") << int(amg::Smoother::Chebyshev) << 2 << int(amg::Smoother::Jacobi);
    QTest::newRow("Chebyshev, degree 3, on every level") << int(amg::Smoother::Chebyshev) << 3 << int(amg::Smoother::Chebyshev);
  }
  void cycleIsSymmetricPositiveDefinite() {
    QFETCH(int, smoother);
    QFETCH(int, degree);
    QFETCH(int, coarse_smoother);
    const System s = make_system(12);
    amg::Options o;
    o.smoother = amg::Smoother(smoother);
    o.degree = degree;
    o.coarse_smoother = amg::Smoother(coarse_smoother);
    o.coarse_degree = degree;
    o.coarse_unknowns = 120;  // three levels or more: the coarse levels' smoothing is in the cycle
    amg::Hierarchy levels;
    levels.build(s.A, s.nodes, o);
    QVERIFY(levels.stats().levels() >= 3);
    QCOMPARE(levels.fine_smoothing().steps(), degree);
    const int n = 3 * s.m.num_free();
    cg::Workspace<double> w;
    w.multigrid = &levels;
    w.resize(n);
    const auto sys = s.block_system();
    cg::build_block_jacobi(sys, w.precond.data());
    auto apply = [&](const Eigen::VectorXd& r) {
      Eigen::VectorXd z(n);
      cg::multigrid_cycle(sys, w, r.data(), z.data(), false);
      return z;
    };
    for (unsigned seed = 1; seed <= 3; ++seed) {
      const Eigen::VectorXd x = random_vector(n, seed), y = random_vector(n, seed + 10);
      const Eigen::VectorXd Mx = apply(x), My = apply(y);
      const double asym = std::abs(x.dot(My) - y.dot(Mx)) / (x.norm() * My.norm());
      QVERIFY2(asym < 1e-10, qPrintable(QString("asymmetry %1").arg(asym)));
      QVERIFY(x.dot(Mx) > 0);
    }
  }

  // Relative residual 1e-12 bounds the relative error by cond(A) 1e-12 (cond < 1e5 here).
  void solvesLikeCholesky() {
    const System s = make_system(12);
    amg::Hierarchy levels;
    levels.build(s.A, s.nodes);
    const int n = 3 * s.m.num_free();
    const Eigen::VectorXd b = random_vector(n, 7);
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(Eigen::SparseMatrix<double>(s.A));
    QCOMPARE(ldlt.info(), Eigen::Success);
    const Eigen::VectorXd x_ref = ldlt.solve(b);
    std::vector<double> x(n, 0.0);
    cg::Workspace<double> w;
    w.multigrid = &levels;
    const auto res = cg::solve(s.block_system(), b.data(), x.data(), 1e-12, 1000, w, false);
    QVERIFY(res.converged);
    const double err = (Eigen::Map<Eigen::VectorXd>(x.data(), n) - x_ref).norm() / x_ref.norm();
    qInfo("multigrid CG: %d iterations to 1e-12, error %.2e against LDLT", res.iterations, err);
    QVERIFY2(err < 1e-7, qPrintable(QString::number(err)));
  }

  // Twice the cells along each side (8x the nodes): block-Jacobi's iterations grow about
  // with the nodes across (2x); the multigrid's grow far less, and are several times
  // fewer on the finer box. The bound is on the ratio of two counts that each move with
  // where the aggregates fall: in the box's structured numbering 38 and 48 iterations
  // (1.26x), in the order build_model gives the mesh (TetMesh::order_for_locality) 35 and
  // 51 (1.46x), so 1.5x, against block-Jacobi's 2x.
  void iterationsDoNotGrowWithTheMesh() {
    int jacobi[2], multigrid[2];
    const int cells[2] = {12, 24};
    for (int k = 0; k < 2; ++k) {
      const System s = make_system(cells[k]);
      amg::Hierarchy levels;
      levels.build(s.A, s.nodes);
      jacobi[k] = iterations(s, nullptr);
      multigrid[k] = iterations(s, &levels);
      const auto st = levels.stats();
      qInfo("%d cells across, %d unknowns: block-Jacobi %d iterations, multigrid %d (%d levels, operator complexity %.2f)",
            cells[k], 3 * s.m.num_free(), jacobi[k], multigrid[k], st.levels(), st.operator_complexity);
      QVERIFY(jacobi[k] > 0 && multigrid[k] > 0);
    }
    QVERIFY2(multigrid[1] * 4 < jacobi[1], "multigrid not 4x fewer iterations than block-Jacobi on the fine box");
    const double growth_mg = double(multigrid[1]) / multigrid[0], growth_j = double(jacobi[1]) / jacobi[0];
    QVERIFY2(growth_mg < 1.5 && growth_mg < growth_j,
             qPrintable(QString("iterations grew %1x (block-Jacobi %2x)").arg(growth_mg).arg(growth_j)));
  }

  // Nearly incompressible tissue (the nodal-pressure element, stiffness-dominated):
  // from Poisson's ratio 0.40 to 0.49 (lambda / mu from 4 to 49) one Jacobi sweep before
  // and after the coarse correction leaves the error that is nearly free of volume change
  // (small eigenvalues of D^-1 A, which lambda dominates) to CG, and its iterations grow
  // about 2x; the Chebyshev polynomial of degree 2 over [rho / 27, 1.1 rho] damps it too.
  // Measured on this 12-cell box: Jacobi 20 -> 52 (2.6x), Chebyshev 18 -> 31 (1.72x); on
  // the Hertz scene at 20 across 103 -> 219 against 61 -> 93 (docs/simulation.md). The
  // bound is the 2x asked of the multigrid, 12 % above what the box gives.
  //
  // The multigrid preconditioner's own options (MultigridKeeper::options(Multigrid)) pick
  // between the two by the volumetric term's share of the system's trace, with the
  // stiffness split as the backends split it: one Jacobi sweep at 0.40, where that share is
  // small, Chebyshev at 0.49, where it is large; so its iterations stay within the 2x too.
  void chebyshevHoldsNearIncompressibleIterations() {
    const double nus[2] = {0.40, 0.49};
    int jacobi[2], chebyshev[2], keeper[2], forced_jacobi[2];
    double share[2];
    bool keeper_chebyshev[2], forced_jacobi_chebyshev[2];
    for (int k = 0; k < 2; ++k) {
      const NodalSystem s = make_nodal_system(12, nus[k]);
      const Blocks b = to_blocks(s.A);
      const int n = int(s.A.rows());
      const Eigen::VectorXd rhs = random_vector(n, 11);
      auto solve = [&](const amg::Options& o, const amg::SpMat& sparser, amg::Stats* stats = nullptr) {
        amg::Hierarchy levels;
        levels.build(s.A, s.nodes, o, &sparser);
        if (stats) *stats = levels.stats();
        std::vector<double> x(n, 0.0);
        cg::Workspace<double> w;
        w.multigrid = &levels;
        const auto res = cg::solve(b.system(), rhs.data(), x.data(), 1e-8, 20000, w, false);
        return res.converged ? res.iterations : -1;
      };
      jacobi[k] = solve(amg::Options{}, s.shear);
      chebyshev[k] = solve(chebyshev_options(), s.shear);
      amg::Stats st;
      keeper[k] = solve(MultigridKeeper::options(Preconditioner::Multigrid), s.stiffness, &st);
      share[k] = st.sparser_share;
      keeper_chebyshev[k] = st.finest_chebyshev;
      // "multigrid-jacobi": the same levels with one sweep whatever the share.
      amg::Stats stj;
      forced_jacobi[k] = solve(MultigridKeeper::options(Preconditioner::MultigridJacobi), s.stiffness, &stj);
      forced_jacobi_chebyshev[k] = stj.finest_chebyshev;
      qInfo("nu %.2f, %d unknowns: CG iterations to 1e-8 with one Jacobi sweep %d, Chebyshev of degree 2 %d; "
            "the multigrid's own choice %d (%s at a volumetric share of %.2f); multigrid-jacobi %d",
            nus[k], n, jacobi[k], chebyshev[k], keeper[k], keeper_chebyshev[k] ? "Chebyshev" : "Jacobi", share[k],
            forced_jacobi[k]);
      QVERIFY(jacobi[k] > 0 && chebyshev[k] > 0 && keeper[k] > 0 && forced_jacobi[k] > 0);
    }
    const double rj = double(jacobi[1]) / jacobi[0], rc = double(chebyshev[1]) / chebyshev[0];
    const double rk = double(keeper[1]) / keeper[0];
    qInfo("0.49 over 0.40: Jacobi %.2fx, Chebyshev %.2fx, the multigrid's choice %.2fx", rj, rc, rk);
    QVERIFY2(rc <= 2.0, qPrintable(QString("Chebyshev: %1x").arg(rc)));
    QVERIFY2(chebyshev[1] < jacobi[1] && rc < rj, "Chebyshev did not take fewer iterations at 0.49, or grew as much");
    // The share grows with lambda / mu and crosses the switch between the two ratios.
    QVERIFY2(share[0] < MultigridKeeper::kChebyshevShare && share[1] >= MultigridKeeper::kChebyshevShare && share[1] > share[0],
             qPrintable(QString("shares %1 and %2").arg(share[0]).arg(share[1])));
    QVERIFY(!keeper_chebyshev[0] && keeper_chebyshev[1]);
    QVERIFY2(rk <= 2.0, qPrintable(QString("the multigrid's choice: %1x").arg(rk)));
    // Forced to one sweep, the levels keep it above the share too: below it the same solve
    // as the multigrid's own, above it more iterations than its Chebyshev.
    QVERIFY(!forced_jacobi_chebyshev[0] && !forced_jacobi_chebyshev[1]);
    QCOMPARE(forced_jacobi[0], keeper[0]);
    QVERIFY2(forced_jacobi[1] > keeper[1], qPrintable(QString("%1 against %2").arg(forced_jacobi[1]).arg(keeper[1])));
  }

  // The Chebyshev smoother's interval ends at 1.1 times the estimate of D^-1 A's largest
  // eigenvalue: an estimate more than 10 % low lets the polynomial amplify the top modes.
  // On three diagonal blocks of the 1D Laplacian tridiag(-1, 2, -1) (n = 3,000, its top
  // eigenvalues clustered as a fine mesh's are) D^-1 A = A / 2 has the largest eigenvalue
  // 1 + cos(pi / (n/3 + 1)) exactly. 20 Lanczos steps come within 1 % from below (measured
  // 0.6 %); the power iteration's 20 steps, what the smoother had before, are 3.8 % low on
  // this spectrum (16-20 % on the 28-across Hertz block).
  void largestEigenvalueIsCloseFromBelow() {
    const int m = 1000, n = 3 * m;
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i < m; ++i)
      for (int c = 0; c < 3; ++c) {
        const int r = 3 * i + c;
        t.emplace_back(r, r, 2.0);
        if (i > 0) t.emplace_back(r, r - 3, -1.0);
        if (i + 1 < m) t.emplace_back(r, r + 3, -1.0);
      }
    amg::SpMat A(n, n), Dinv(n, n);
    A.setFromTriplets(t.begin(), t.end());
    std::vector<Eigen::Triplet<double>> d;
    for (int r = 0; r < n; ++r) d.emplace_back(r, r, 0.5);
    Dinv.setFromTriplets(d.begin(), d.end());
    const double exact = 1.0 + std::cos(M_PI / (m + 1));
    const double lanczos = amg::largest_eigenvalue(Dinv, A);
    Eigen::VectorXd v = Eigen::VectorXd::Ones(n);
    double power = 0;
    for (int k = 0; k < 20; ++k) {
      const Eigen::VectorXd y = Dinv * (A * v);
      power = y.norm() / v.norm();
      v = y / y.norm();
    }
    qInfo("largest eigenvalue %.6f: Lanczos (20 steps) %.6f, power iteration (20 steps) %.6f", exact, lanczos, power);
    QVERIFY2(lanczos <= exact * (1 + 1e-12) && lanczos >= 0.99 * exact, qPrintable(QString::number(lanczos)));
    QVERIFY(lanczos > power);
  }

  void badInputIsNamed() {
    const System s = make_system(6);
    amg::Hierarchy levels;
    std::vector<Eigen::Vector3d> fewer(s.nodes.begin(), s.nodes.end() - 1);
    try {
      levels.build(s.A, fewer);
      QFAIL("a matrix for other nodes was accepted");
    } catch (const std::runtime_error& e) {
      QVERIFY2(QString(e.what()).contains("rows for"), e.what());
    }
    QVERIFY(!levels.built());
  }

  // The levels are built once for a press and hold; not again for the small dt changes of
  // the real-time loop (10 %); for a large one (more than 2x the stiffness's weight) again,
  // but not within 100 steps of the last build (a rebuild's slow step must not set off the
  // next); and again for new materials.
  void levelsAreRebuiltOnlyWhenNeeded() {
    Scenario s = press_box();
    s.params.solver.preconditioner = Preconditioner::Multigrid;
    const Model m = build_scenario_model(s, patient_mesh(s));
    auto b = make_cpu_backend(m, s.params);
    std::vector<FingerInput> in(1);
    std::vector<FingerOutput> out(1);
    in[0].radius = 0.008;
    auto steps = [&](int from, int to) {
      for (int k = from; k < to; ++k) {
        in[0].position = Eigen::Vector3d(0.005, 0, 0.03 + 0.008 - 1e-4 * std::min(k, 30));  // 3 mm, then held
        const auto st = b->step(in, out);
        QVERIFY(st.finite);
      }
    };
    auto builds = [&] { return b->multigrid_counts().builds; };
    steps(1, 30);
    QCOMPARE(builds(), 1L);
    SimParams p = b->params();
    p.solver.dt *= 1.1;
    b->set_params(p);
    steps(30, 40);
    QCOMPARE(builds(), 1L);
    p.solver.dt *= 2;  // the stiffness's weight 2.4x the build's
    b->set_params(p);
    steps(40, 60);
    QCOMPARE(builds(), 1L);
    steps(60, 140);
    QCOMPARE(builds(), 2L);
    Materials mat = m.materials;
    for (auto& e : mat.mu) e *= 2;
    b->set_materials(mat);
    steps(140, 145);
    QCOMPARE(builds(), 3L);
    QCOMPARE(b->multigrid_counts().failures, 0L);
  }

  // A patient's levels are built when it loads (Simulation::reset(), the body at rest), not
  // in the first touch's step, which would stall the simulation for the build (0.3-1 s on
  // the paper mesh). On every backend this machine has; the press that follows builds
  // nothing more and feels what block-Jacobi's press feels: the rest system differs from
  // the first touch's only by the contact penalty on a few nodes' diagonal, so the levels
  // precondition as well, and any preconditioner converged to 1e-6 gives the same forces
  // (1e-4, as simulationMatchesBlockJacobi) in no more iterations than the touch-built
  // levels need plus a tenth (measured: equal or within one iteration a step).
  void levelsAreBuiltWhenThePatientLoads_data() {
    QTest::addColumn<QString>("backend");
    for (const auto& name : available_backends())
      if (name == "cpu" || name == "cuda") QTest::newRow(name.c_str()) << QString::fromStdString(name);
  }
  void levelsAreBuiltWhenThePatientLoads() {
    QFETCH(QString, backend);
    Scenario s = press_box();
    s.backend = backend.toStdString();
    const Model m = build_scenario_model(s, patient_mesh(s));
    // 30 steps of a 3 mm press, and the builds before the first and after the last.
    struct Pressed : Press {
      long built_before = 0, built_after = 0;
    };
    auto pressed = [&](Preconditioner pc, bool at_load) {
      Scenario t = s;
      t.params.solver.preconditioner = pc;
      Simulation sim(t, m);
      if (at_load) sim.reset();
      Pressed r;
      r.built_before = sim.backend().multigrid_counts().builds;
      static_cast<Press&>(r) = press(sim, 30);
      r.built_after = sim.backend().multigrid_counts().builds;
      return r;
    };
    const Pressed loaded = pressed(Preconditioner::Multigrid, true);
    QCOMPARE(loaded.built_before, 1L);
    QCOMPARE(loaded.built_after, 1L);
    const Pressed touched = pressed(Preconditioner::Multigrid, false);  // no reset(): built at the first touch
    QCOMPARE(touched.built_before, 0L);
    QCOMPARE(touched.built_after, 1L);
    const Pressed jacobi = pressed(Preconditioner::BlockJacobi, true);
    QCOMPARE(jacobi.built_after, 0L);  // nothing for a preconditioner without levels
    const double err = relative_error(loaded.f, jacobi.f);
    qInfo("%s: levels at load %d CG iterations, at the first touch %d; force difference from block-Jacobi %.2e",
          qPrintable(backend), loaded.iterations, touched.iterations, err);
    QVERIFY(std::abs(jacobi.f.back()) > 0.1);  // it pressed
    QVERIFY2(err < 1e-4, qPrintable(QString::number(err)));
    QVERIFY2(loaded.iterations <= touched.iterations + touched.iterations / 10,
             qPrintable(QString("%1 against %2").arg(loaded.iterations).arg(touched.iterations)));
  }

  // A deferred rebuild through the backend, on every backend this machine has: new
  // materials (the box's upper half twice as stiff) make the levels due; the step that
  // finds them due keeps the present ones and hands the build out as a job; the job runs
  // on a thread of its own (on CUDA it reads the device's copy of the system back there)
  // and its levels go in use between two steps. The press after it feels what
  // block-Jacobi's press of the same materials feels (1e-4, as simulationMatchesBlockJacobi)
  // in under half its CG iterations: the installed levels are the ones solving.
  void deferredRebuildRunsOnAnotherThread_data() { levelsAreBuiltWhenThePatientLoads_data(); }
  void deferredRebuildRunsOnAnotherThread() {
    QFETCH(QString, backend);
    Scenario s = press_box();
    s.backend = backend.toStdString();
    const Model m = build_scenario_model(s, patient_mesh(s));
    std::vector<std::pair<int, double>> stiffer;
    for (int e = 0; e < m.num_tets(); ++e) {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (int a = 0; a < 4; ++a) c += m.rest[std::size_t(m.tets[std::size_t(e)][a])] / 4.0;
      if (c.z() > 0.015) stiffer.emplace_back(e, 2.0 * m.materials.young[std::size_t(e)]);
    }
    QVERIFY(!stiffer.empty());
    auto painted = [&](Simulation& sim) {
      sim.reset();
      QCOMPARE(sim.set_element_young(stiffer), int(stiffer.size()));
    };

    Scenario t = s;
    t.params.solver.preconditioner = Preconditioner::BlockJacobi;
    Simulation jacobi(t, m);
    painted(jacobi);
    press(jacobi, 1);
    const Press fj = press(jacobi, 30);

    t.params.solver.preconditioner = Preconditioner::Multigrid;
    Simulation sim(t, m);
    sim.set_deferred_levels(true);
    painted(sim);
    QCOMPARE(sim.backend().multigrid_counts().builds, 1L);  // the load's, of the old materials
    press(sim, 1);                                          // finds the levels due
    QCOMPARE(sim.backend().multigrid_counts().builds, 1L);
    const std::shared_ptr<LevelsJob> job = sim.backend().take_levels_job();
    QVERIFY(job);
    QVERIFY(!sim.backend().take_levels_job());
    std::thread builder([job] { job->run(); });
    builder.join();
    QVERIFY(job->done());
    QVERIFY(sim.backend().install_levels(job));
    QCOMPARE(sim.backend().multigrid_counts().builds, 2L);
    QCOMPARE(sim.backend().multigrid_counts().failures, 0L);
    const Press fmg = press(sim, 30);
    QCOMPARE(sim.backend().multigrid_counts().builds, 2L);  // nothing more due
    const double err = relative_error(fmg.f, fj.f);
    qInfo("%s: block-Jacobi %d CG iterations, the levels built on another thread %d; force difference %.2e",
          qPrintable(backend), fj.iterations, fmg.iterations, err);
    QVERIFY(std::abs(fj.f.back()) > 0.1);  // it pressed
    QVERIFY2(err < 1e-4, qPrintable(QString::number(err)));
    QVERIFY2(fmg.iterations * 2 < fj.iterations, qPrintable(QString("%1 against %2").arg(fmg.iterations).arg(fj.iterations)));
  }

  // The real-time loop sets dt from the wall clock: a step that overran (a build's own) is
  // followed by one step at the loop's largest dt, ten times the usual and a hundred times
  // the stiffness's weight. That one solve, however poor, does not mark the levels stale
  // (neither beyond the rescue tolerance nor by its iteration count); a weight that stays
  // moved for MultigridKeeper::kMovedSteps steps rebuilds them once; and the drift rules
  // still hold at the levels' own weight. A rebuild for the long step would overrun in
  // turn and set off the next one.
  void anOverrunsLongStepDoesNotRebuild() {
    const System s = make_system(6);
    MultigridKeeper keeper;
    long builds = 0, failures = 0;
    const auto prepare = [&](double weight) {
      return keeper.prepare(
          Preconditioner::Multigrid, weight, s.m,
          [&]() -> LevelsSystem { return [&](amg::SpMat& stiffness, amg::SpMat&) { stiffness = s.A; }; },
          [](const amg::Hierarchy&) {}, builds, failures);
    };
    const double tol = 1e-3;
    // One step's solve at `weight`, of `iterations`, within the tolerance or not.
    const auto solve = [&](double weight, int iterations, bool solved) {
      QVERIFY(prepare(weight));
      keeper.note(iterations, solved, tol);
    };
    const auto usual = [&](int n, double weight) {
      for (int k = 0; k < n; ++k) solve(weight, 6, true);
    };
    usual(150, 1.0);
    QCOMPARE(builds, 1L);
    // The overrun's long step, beyond the rescue tolerance at the cap; then the usual one.
    solve(100.0, 200, false);
    usual(1, 1.0);
    QCOMPARE(builds, 1L);
    // Nor one that converged in many iterations, straight after a build (its solve the
    // reference); while twice the reference and ten more at the levels' weight is drift.
    keeper.invalidate();
    usual(1, 1.0);
    QCOMPARE(builds, 2L);
    solve(100.0, 200, true);
    solve(1.0, 6, true);
    QCOMPARE(builds, 2L);
    solve(1.0, 2 * 6 + 11, true);
    usual(1, 1.0);
    QCOMPARE(builds, 3L);
    // A weight that stays moved: rebuilt once, at the kMovedSteps-th step in a row (and 100
    // after the last build), then held.
    usual(100, 1.0);
    QCOMPARE(builds, 3L);
    usual(MultigridKeeper::kMovedSteps - 1, 100.0);
    QCOMPARE(builds, 3L);
    usual(1, 100.0);
    QCOMPARE(builds, 4L);
    usual(200, 100.0);
    QCOMPARE(builds, 4L);
    QCOMPARE(failures, 0L);
  }

  // Deferred builds: with levels built, a rebuild that falls due is handed out once as a
  // job and the solves keep the present levels until it is installed; a job of a system
  // changed since (invalidate()) is refused and a new one handed out; a job whose build
  // threw counts as a failed build (block-Jacobi for the next 1,000 steps); a build with
  // no levels yet, or one that may not be deferred (the reset's), is done at once.
  void deferredRebuildKeepsTheLevelsUntilInstalled() {
    const System s = make_system(6);
    MultigridKeeper keeper;
    keeper.set_deferred(true);
    long builds = 0, failures = 0, uploads = 0;
    amg::SpMat system = s.A;
    const auto upload = [&](const amg::Hierarchy&) { ++uploads; };
    const auto prepare = [&](bool may_defer = true) {
      return keeper.prepare(
          Preconditioner::Multigrid, 1.0, s.m,
          [&]() -> LevelsSystem { return [A = system](amg::SpMat& stiffness, amg::SpMat&) { stiffness = A; }; }, upload,
          builds, failures, may_defer);
    };
    QVERIFY(prepare());  // no levels yet: built at once
    QCOMPARE(builds, 1L);
    QVERIFY(!keeper.take_job());
    keeper.note(6, false, 1e-3);  // a solve beyond its tolerance: a rebuild is due
    QVERIFY(prepare());
    QCOMPARE(builds, 1L);
    const auto job = keeper.take_job();
    QVERIFY(job);
    QVERIFY(!keeper.take_job());  // handed out once
    QVERIFY(!keeper.install(job, upload, builds, failures));  // not run yet
    for (int k = 0; k < 5; ++k) QVERIFY(prepare());  // the present levels meanwhile, no second job
    QVERIFY(!keeper.take_job());
    job->run();
    QVERIFY(job->done());
    QVERIFY(keeper.install(job, upload, builds, failures));
    QCOMPARE(builds, 2L);
    QCOMPARE(uploads, 2L);
    QVERIFY(!keeper.install(job, upload, builds, failures));  // once
    // The levels of the job solve as the ones built in a step do (the same system).
    amg::Hierarchy direct;
    MultigridKeeper::build(direct, s.m, s.A, amg::SpMat(), MultigridKeeper::options(Preconditioner::Multigrid));
    QVERIFY(keeper.levels().stats().unknowns == direct.stats().unknowns);

    // A system changed while the job ran: refused, and a new job of the new system.
    keeper.note(6, false, 1e-3);
    QVERIFY(prepare());
    const auto old_job = keeper.take_job();
    QVERIFY(old_job);
    keeper.invalidate();
    QVERIFY(prepare());
    const auto new_job = keeper.take_job();
    QVERIFY(new_job && new_job != old_job);
    old_job->run();
    QVERIFY(!keeper.install(old_job, upload, builds, failures));
    QCOMPARE(builds, 2L);
    new_job->run();
    QVERIFY(keeper.install(new_job, upload, builds, failures));
    QCOMPARE(builds, 3L);

    // Not deferred: built in the call.
    keeper.invalidate();
    QVERIFY(prepare(false));
    QCOMPARE(builds, 4L);
    QVERIFY(!keeper.take_job());

    // A build that throws (a system that is not finite) on the job's thread.
    system.coeffRef(0, 0) = std::numeric_limits<double>::quiet_NaN();
    keeper.invalidate();
    QVERIFY(prepare());
    const auto bad = keeper.take_job();
    QVERIFY(bad);
    bad->run();
    QVERIFY(!keeper.install(bad, upload, builds, failures));
    QCOMPARE(failures, 1L);
    QCOMPARE(builds, 4L);
    QVERIFY(!prepare());  // block-Jacobi after a failed build
  }

  // solver.preconditioner "auto" (the default) is resolved where a backend is made, in its
  // constructor and in set_params: the multigrid on the GPU's persistent solver from
  // kGpuMultigridFromNodes nodes (where it measured as quick or quicker than block-Jacobi),
  // block-Jacobi below it, on the CPU at any size, and for the library baselines, which
  // have no multigrid. A named preconditioner is never changed. The CUDA cases run where
  // a GPU is usable (tools/gpu-check.sh tests).
  void autoPreconditionerResolves() {
    const int at = kGpuMultigridFromNodes;
    QVERIFY(resolve_preconditioner(Preconditioner::Auto, true, at) == Preconditioner::Multigrid);
    QVERIFY(resolve_preconditioner(Preconditioner::Auto, true, at - 1) == Preconditioner::BlockJacobi);
    QVERIFY(resolve_preconditioner(Preconditioner::Auto, false, 100 * at) == Preconditioner::BlockJacobi);
    for (Preconditioner p : kPreconditioners)
      if (p != Preconditioner::Auto)
        for (bool gpu : {false, true})
          for (int n : {1, at, 100 * at}) QVERIFY(resolve_preconditioner(p, gpu, n) == p);
    QVERIFY(!is_multigrid(Preconditioner::Auto));

    Scenario small = press_box();  // 15 x 15 x 8 cells: 2,304 nodes
    Scenario large = press_box();  // 38 x 38 x 19 cells: 30,420 nodes
    large.patient.edge = 0.0016;
    const Model ms = build_scenario_model(small, patient_mesh(small));
    const Model ml = build_scenario_model(large, patient_mesh(large));
    qInfo("boxes of %d and %d nodes; the multigrid from %d on the GPU", ms.num_nodes(), ml.num_nodes(), at);
    QVERIFY(ms.num_nodes() < at && ml.num_nodes() >= at);
    SimParams p;  // the defaults: preconditioner auto
    QVERIFY(p.solver.preconditioner == Preconditioner::Auto);
    // What the backend runs after its constructor, or Auto (never a resolution) where
    // set_params, given what the live loop hands back, resolved it otherwise.
    auto resolved = [&](const std::string& backend, const Model& m, SimParams q) {
      const auto b = make_named_backend(backend, m, q);
      const Preconditioner made = b->params().solver.preconditioner;
      b->set_params(q);
      return b->params().solver.preconditioner == made ? made : Preconditioner::Auto;
    };
    QVERIFY(resolved("cpu", ms, p) == Preconditioner::BlockJacobi);
    QVERIFY(resolved("cpu", ml, p) == Preconditioner::BlockJacobi);
    SimParams named = p;
    named.solver.preconditioner = Preconditioner::Multigrid;
    QVERIFY(resolved("cpu", ms, named) == Preconditioner::Multigrid);
    std::string why;
    if (!cuda_available(&why)) QSKIP(("no usable GPU (" + why + "): the CUDA backend's choice is not checked").c_str());
    QVERIFY(resolved("cuda", ms, p) == Preconditioner::BlockJacobi);
    QVERIFY(resolved("cuda", ml, p) == Preconditioner::Multigrid);
    named.solver.preconditioner = Preconditioner::BlockJacobi;
    QVERIFY(resolved("cuda", ml, named) == Preconditioner::BlockJacobi);
    SimParams linear = p;  // the baselines have the linear element only
    linear.element = Element::Linear;
    QVERIFY(resolved("cuda-bsr", ml, linear) == Preconditioner::BlockJacobi);
  }

  // The whole step with it: a finger presses a box of nodal-pressure tissue
  // (Poisson's ratio 0.45: the pressure term is in the system) at the haptic step. The
  // forces match block-Jacobi's within what a relative residual of 1e-6 allows (1e-4),
  // with fewer iterations.
  void simulationMatchesBlockJacobi() {
    const Scenario s = press_box();
    const Model m = build_scenario_model(s, patient_mesh(s));
    auto press_with = [&](Preconditioner pc, int& iterations) {  // 6 mm in 60 ms
      Scenario t = s;
      t.params.solver.preconditioner = pc;
      Simulation sim(t, m);
      Press r = press(sim, 60);
      iterations = r.iterations;
      return r.f;
    };
    int it_j = 0, it_mg = 0;
    const auto fj = press_with(Preconditioner::BlockJacobi, it_j);
    const auto fmg = press_with(Preconditioner::Multigrid, it_mg);
    const double err = relative_error(fmg, fj);
    qInfo("60 steps: block-Jacobi %d CG iterations, multigrid %d; force difference %.2e (final %.3f N)", it_j, it_mg, err,
          fj[fj.size() - 1]);
    QVERIFY(std::abs(fj[fj.size() - 1]) > 0.1);  // it pressed
    QVERIFY2(err < 1e-4, qPrintable(QString::number(err)));
    QVERIFY2(it_mg * 2 < it_j, "multigrid did not halve the iterations");
    // The Chebyshev-smoothed levels (solver.preconditioner "multigrid-chebyshev") in the
    // same simulation: the same forces, and no more iterations than the Jacobi-smoothed
    // ones (a degree-2 polynomial smooths at least as much as one sweep).
    int it_cheb = 0;
    const auto fcheb = press_with(Preconditioner::MultigridChebyshev, it_cheb);
    const double err_cheb = relative_error(fcheb, fj);
    qInfo("multigrid-chebyshev %d CG iterations; force difference %.2e", it_cheb, err_cheb);
    QVERIFY2(err_cheb < 1e-4, qPrintable(QString::number(err_cheb)));
    QVERIFY2(it_cheb <= it_mg, qPrintable(QString("%1 against %2").arg(it_cheb).arg(it_mg)));
  }
};

QTEST_APPLESS_MAIN(TestMultigrid)
#include "tst_multigrid.moc"
