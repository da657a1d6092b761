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
constexpr double kE = 19000, kNu = 0.3, kB = 10;  // Pa, -, body force N/m^3 (down): tip ~1.6% of L

// Beam along x with the face x = -L/2 clamped, `across` cells through the bending
// direction z (and the length in proportion); the y direction, which does not bend,
// gets a quarter of that.
Model beam(int across) {
  TetMesh m = make_box_mesh(V3(kL, kH, kH), 10 * across, std::max(2, across / 4), across);
  return build_model(m, Material{kE, kNu, 1000}, [](const V3& p) { return p.x() <= -kL / 2 + 1e-9; });
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
double timoshenko() {
  const double A = kH * kH, I = kH * kH * kH * kH / 12, q = kB * A, G = kE / (2 * (1 + kNu));
  return q * std::pow(kL, 4) / (8 * kE * I) + q * kL * kL / (2 * (5.0 / 6.0) * G * A);
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
  void dynamicSolverSettlesToStaticDeflection() {
    const Model m = beam(2);
    const auto u_static = solve_linear_static(m, body_force_loads(m, V3(0, 0, -kB)));
    SimParams p;
    p.solver.dt = 0.02;
    p.solver.cg_tolerance = 1e-10;
    p.solver.cg_max_iterations = 5000;
    p.damping.mass = 5.0;
    p.damping.stiffness = 0.0;
    p.gravity = V3(0, 0, -kB / 1000.0);  // body force / density (1000 kg/m^3)
    auto b = make_backend(BackendKind::Cpu, m, p);
    std::vector<FingerInput> none;
    std::vector<FingerOutput> out;
    for (int k = 0; k < 400; ++k) QVERIFY(b->step(none, out).finite);
    std::vector<double> x;
    b->positions(x);
    std::vector<V3> u(m.num_nodes());
    for (int i = 0; i < m.num_nodes(); ++i) u[i] = V3(x[3 * i], x[3 * i + 1], x[3 * i + 2]) - m.rest[i];
    const double d_dyn = tip_deflection(m, u), d_st = tip_deflection(m, u_static);
    qInfo("settled tip %.5f mm, static %.5f mm", d_dyn * 1e3, d_st * 1e3);
    QVERIFY2(std::abs(d_dyn - d_st) < 5e-3 * d_st, qPrintable(QString::number(d_dyn / d_st)));
  }
};

QTEST_APPLESS_MAIN(TestCantilever)
#include "tst_cantilever.moc"
