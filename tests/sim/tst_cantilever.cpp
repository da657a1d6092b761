// Cantilever under its own weight: linear tetrahedra against beam theory, converging as
// the mesh is refined; and the dynamic solver settling to the same static deflection.
#include <QtTest>

#include <Eigen/Dense>

#include "backend.h"
#include "model.h"
#include "static_solve.h"

using namespace palpation::sim;
using V3 = Eigen::Vector3d;

namespace {

constexpr double kL = 0.2, kH = 0.02;  // length and square side, m (L/h = 10)
constexpr double kE = 19000, kB = 10;  // Pa, body force N/m^3 (down): tip ~1.6% of L
constexpr double kNu = 0.3;

// Beam along x with the face x = -L/2 clamped, `across` cells through the bending
// direction z (and the length in proportion); the y direction, which does not bend,
// gets a quarter of that.
Model beam(int across, double nu = kNu) {
  TetMesh m = make_box_mesh(V3(kL, kH, kH), 10 * across, std::max(2, across / 4), across);
  return build_model(m, Material{kE, nu, 1000}, [](const V3& p) { return p.x() <= -kL / 2 + 1e-9; });
}

double tip_deflection(const Model& m, const std::vector<V3>& u) {
  double sum = 0;
  int n = 0;
  for (int i = 0; i < m.num_nodes(); ++i)
    if (m.rest[i].x() >= kL / 2 - 1e-9) {
      sum += -u[i].z();
      ++n;
    }
  return sum / n;
}

// Timoshenko beam under a uniform load q: q L^4 / (8 E I) + q L^2 / (2 kappa G A),
// kappa = 5/6 for a square section. The shear term is ~1% here (L/h = 10).
double timoshenko(double nu = kNu) {
  const double A = kH * kH, I = kH * kH * kH * kH / 12, q = kB * A, G = kE / (2 * (1 + nu));
  return q * std::pow(kL, 4) / (8 * kE * I) + q * kL * kL / (2 * (5.0 / 6.0) * G * A);
}

// Tip deflection once the implicit integrator has settled under gravity (dt 20 ms, mass
// damping 5/s: 400 steps leave ~e^-40 of the initial transient).
double settled_tip(const Model& m, Element element, double corotation_tolerance = SolverParams{}.corotation_tolerance) {
  SimParams p;
  p.element = element;
  p.solver.corotation_tolerance = corotation_tolerance;
  p.solver.dt = 0.02;
  p.solver.cg_tolerance = 1e-10;
  p.solver.cg_max_iterations = 20000;
  p.damping.mass = 5.0;
  p.damping.stiffness = 0.0;
  p.gravity = V3(0, 0, -kB / 1000.0);  // body force / density (1000 kg/m^3)
  auto b = make_backend(BackendKind::Cpu, m, p);
  std::vector<FingerInput> none;
  std::vector<FingerOutput> out;
  for (int k = 0; k < 400; ++k)
    if (!b->step(none, out).finite) return NAN;
  std::vector<double> x;
  b->positions(x);
  std::vector<V3> u(m.num_nodes());
  for (int i = 0; i < m.num_nodes(); ++i) u[i] = V3(x[3 * i], x[3 * i + 1], x[3 * i + 2]) - m.rest[i];
  return tip_deflection(m, u);
}

}  // namespace

class TestCantilever : public QObject {
  Q_OBJECT
 private slots:
  // Linear tetrahedra are too stiff in bending (shear locking) and converge from below.
  // Tolerance at 24 elements across: 3% (the clamped face's 3-D constraint and the
  // beam theory's own approximations are ~1%; the remainder is discretisation, and it
  // must shrink with every refinement).
  void convergesToBeamTheory() {
    const double ref = timoshenko();
    // PALPATION_LIGHT_TESTS=1 (the sanitizer build in CI, .ci/run): up to 16 across;
    // convergence is still asserted, the 3% bound needs 24.
    const bool light = qEnvironmentVariableIntValue("PALPATION_LIGHT_TESTS") != 0;
    const std::vector<int> sizes = light ? std::vector<int>{4, 8, 16} : std::vector<int>{4, 8, 16, 24};
    double previous_error = 1e9;
    for (int across : sizes) {
      const Model m = beam(across);
      const auto u = solve_linear_static(m, body_force_loads(m, V3(0, 0, -kB)));
      const double d = tip_deflection(m, u);
      const double err = std::abs(d - ref) / ref;
      qInfo("cantilever %d across: %d tets, tip %.4f mm vs %.4f mm (error %.2f%%)", across, m.num_tets(), d * 1e3,
            ref * 1e3, 100 * err);
      QVERIFY2(err < previous_error, "error must shrink with refinement");
      previous_error = err;
    }
    if (light)
      QSKIP(qPrintable(QString("PALPATION_LIGHT_TESTS: convergence checked up to 16 across; the 3% bound against "
                               "beam theory is NOT checked (it needs 24 across; the finest here is %1% off)")
                           .arg(100 * previous_error, 0, 'f', 2)));
    QVERIFY2(previous_error < 0.03, qPrintable(QString("finest error %1").arg(previous_error)));
  }

  // The implicit integrator with gravity settles to the linear static answer on the same
  // mesh (corotation changes it by O(deflection/L)^2 ~ 1e-4 at 1.5% deflection). 0.5%.
  // Nearly incompressible tissue (nu = 0.49) in bending. The linear element locks: its
  // one volumetric strain per element holds each element's volume on its own, on top of
  // the shear locking above (measured: -70 / -40 / -17 % at 4 / 8 / 16 across). The
  // nodal-pressure element averages that strain over each node's elements and converges
  // like the linear element at nu = 0.3 (-22 / -12 / -5.5 / -4.0 % at 4 / 8 / 16 / 24
  // across). The nodal error must be under half the linear one at every size and shrink
  // with h; at 24 across it must be within 5% of beam theory. That mesh (42,175 nodes) is
  // solved by CG with the multigrid preconditioner (527 iterations to 1e-8, 35 s, 1.7 GB
  // here): its two-ring direct factorisation takes minutes. The two solvers are held to
  // each other at 8 across first, to 1e-4 of the tip: the residual bound alone (1e-8 times
  // a condition number near 1e6) would allow 1e-2, but the tip is a smooth, bending-
  // dominated quantity that CG resolves first (measured: equal to six digits).
  void nodalPressureDoesNotLockInBending() {
    constexpr double nu = 0.49;
    const double ref = timoshenko(nu);
    const bool light = qEnvironmentVariableIntValue("PALPATION_LIGHT_TESTS") != 0;
    const std::vector<int> sizes = light ? std::vector<int>{4, 8} : std::vector<int>{4, 8, 16};
    double previous = 1e9;
    for (int across : sizes) {
      const Model m = beam(across, nu);
      const auto loads = body_force_loads(m, V3(0, 0, -kB));
      const double lin = std::abs(tip_deflection(m, solve_linear_static(m, loads)) - ref) / ref;
      const double direct = tip_deflection(m, solve_linear_static(m, loads, Element::NodalPressure));
      const double np = std::abs(direct - ref) / ref;
      qInfo("nu 0.49, %d across: linear %.1f%%, nodal pressure %.1f%% off beam theory", across, 100 * lin, 100 * np);
      QVERIFY2(np < 0.5 * lin, "the nodal-pressure element must not lock");
      QVERIFY2(np < previous, "error must shrink with refinement");
      previous = np;
      if (across == 8) {
        int its = 0;
        const double mg = tip_deflection(m, solve_linear_static_multigrid(m, loads, Element::NodalPressure, 1e-8, &its));
        qInfo("8 across: multigrid CG %d iterations, tip %.6g against the direct %.6g", its, mg, direct);
        QVERIFY2(std::abs(mg - direct) <= 1e-4 * std::abs(direct), "multigrid CG and the direct solve disagree");
      }
    }
    if (light) QSKIP("PALPATION_LIGHT_TESTS: locking and convergence checked up to 8 across; the 5% bound needs 24");
    const Model m = beam(24, nu);
    int its = 0;
    const double tip =
        tip_deflection(m, solve_linear_static_multigrid(m, body_force_loads(m, V3(0, 0, -kB)), Element::NodalPressure, 1e-8, &its));
    const double np = std::abs(tip - ref) / ref;
    qInfo("nu 0.49, 24 across (%d nodes): nodal pressure %.2f%% off beam theory (multigrid CG, %d iterations)", m.num_nodes(),
          100 * np, its);
    QVERIFY2(np < previous, "error must shrink with refinement");
    QVERIFY2(np < 0.05, qPrintable(QString("24 across: error %1").arg(np)));
  }

  // The CPU backend keeps the nodal-pressure term factored (B^T W B, updated element by
  // element); the static solve assembles it independently with Eigen's sparse products.
  // Settled under gravity the two agree to the dynamic test's 0.5% (measured 0.03%), with
  // the kept rotations (the default) and with every element re-rotated every step
  // (tolerance 0, the arithmetic of the GPU backends).
  void backendNodalPressureMatchesAssembled() {
    const Model m = beam(4, 0.49);
    const double d_static =
        tip_deflection(m, solve_linear_static(m, body_force_loads(m, V3(0, 0, -kB)), Element::NodalPressure));
    for (double tol : {SolverParams{}.corotation_tolerance, 0.0}) {
      const double d_dyn = settled_tip(m, Element::NodalPressure, tol);
      qInfo("nodal pressure, nu 0.49, corotation tolerance %g: settled tip %.5f mm, static %.5f mm", tol, d_dyn * 1e3,
            d_static * 1e3);
      QVERIFY2(std::abs(d_dyn - d_static) < 5e-3 * d_static, qPrintable(QString::number(d_dyn / d_static)));
    }
  }

  void dynamicSolverSettlesToStaticDeflection() {
    const Model m = beam(2);
    const auto u_static = solve_linear_static(m, body_force_loads(m, V3(0, 0, -kB)));
    const double d_dyn = settled_tip(m, Element::Linear), d_st = tip_deflection(m, u_static);
    QVERIFY(std::isfinite(d_dyn));
    qInfo("settled tip %.5f mm, static %.5f mm", d_dyn * 1e3, d_st * 1e3);
    QVERIFY2(std::abs(d_dyn - d_st) < 5e-3 * d_st, qPrintable(QString::number(d_dyn / d_st)));
  }
};

QTEST_APPLESS_MAIN(TestCantilever)
#include "tst_cantilever.moc"
