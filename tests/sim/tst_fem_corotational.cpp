// Invariants of the corotational element (Drake style: check properties, not numbers).
#include <QtTest>

#include <random>

#include <Eigen/Dense>

#include "fem_corotational.h"
#include "model.h"

using namespace palpation::sim;
using V3 = Eigen::Vector3d;
using M3 = Eigen::Matrix3d;

namespace {

// A generic (not regular) tetrahedron and its shape gradients.
struct Tet {
  V3 X[4] = {V3(0, 0, 0), V3(0.011, 0.001, 0.002), V3(0.002, 0.012, -0.001), V3(0.001, 0.002, 0.010)};
  V3 g[4];
  double vol;
  Tet() {
    M3 dm;
    for (int k = 0; k < 3; ++k) dm.col(k) = X[k + 1] - X[0];
    vol = dm.determinant() / 6;
    const M3 inv = dm.inverse();
    for (int k = 0; k < 3; ++k) g[k + 1] = inv.row(k).transpose();
    g[0] = -(g[1] + g[2] + g[3]);
  }
};

constexpr double kE = 19000, kNu = 0.45;

void forces(const Tet& t, const V3 x[4], Eigen::Quaterniond& q, V3 f[4], int iterations = 50) {
  double lambda, mu;
  lame(kE, kNu, lambda, mu);
  const M3 F = fem::deformation_gradient<double>(x, t.g);
  fem::extract_rotation<double>(F, q, iterations);
  fem::element_forces<double>(F, q.toRotationMatrix(), t.g, t.vol, lambda, mu, f);
}

double max_norm(const V3 f[4]) {
  double m = 0;
  for (int a = 0; a < 4; ++a) m = std::max(m, f[a].norm());
  return m;
}

}  // namespace

class TestFemCorotational : public QObject {
  Q_OBJECT
 private slots:
  // Force scale for comparisons: E * area ~ 19000 * 1e-4 = ~2 N for 1 cm elements.
  // Rigid motions must give forces at round-off level: 1e-9 N (9 orders below).
  void rigidTranslationGivesZeroForce() {
    Tet t;
    V3 x[4], f[4];
    for (int a = 0; a < 4; ++a) x[a] = t.X[a] + V3(0.3, -0.2, 0.05);
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
    forces(t, x, q, f);
    QVERIFY2(max_norm(f) < 1e-9, qPrintable(QString::number(max_norm(f))));
  }

  void rigidRotation90GivesZeroForce() {
    Tet t;
    for (const V3& axis : {V3(0, 0, 1), V3(1, 0, 0), V3(1, 1, 1).normalized()}) {
      const M3 R = Eigen::AngleAxisd(M_PI / 2, axis).toRotationMatrix();
      V3 x[4], f[4];
      for (int a = 0; a < 4; ++a) x[a] = R * t.X[a] + V3(0.01, 0.02, 0.03);
      Eigen::Quaterniond q = Eigen::Quaterniond::Identity();  // cold start: 90 degrees away
      forces(t, x, q, f);
      QVERIFY2(max_norm(f) < 1e-9, qPrintable(QString::number(max_norm(f))));
      // The iteration stops when the update angle is below 1e-9 rad: R within ~1e-8.
      QVERIFY((q.toRotationMatrix() - R).norm() < 1e-7);
    }
  }

  // Without corotation a linear element under a 90-degree rotation produces large
  // spurious forces: the property the paper relies on (no "inflation").
  void linearElementWouldNotBeInvariant() {
    Tet t;
    const M3 R = Eigen::AngleAxisd(M_PI / 2, V3::UnitZ()).toRotationMatrix();
    V3 x[4], f[4];
    for (int a = 0; a < 4; ++a) x[a] = R * t.X[a];
    double lambda, mu;
    lame(kE, kNu, lambda, mu);
    const M3 F = fem::deformation_gradient<double>(x, t.g);
    fem::element_forces<double>(F, M3::Identity(), t.g, t.vol, lambda, mu, f);
    QVERIFY(max_norm(f) > 1e-2);
  }

  // Patch test: a linear displacement field u = G X gives F = I + G everywhere; the
  // strain is uniform, so on a mesh the interior nodes carry no net force and the stress
  // equals the analytic one.
  void patchTestUniformStrain() {
    Eigen::Matrix3d G;
    G << 1e-3, 2e-4, 0, 2e-4, -5e-4, 1e-4, 0, 1e-4, 2e-3;  // small symmetric strain
    TetMesh mesh = make_box_mesh(V3(0.03, 0.03, 0.03), 3, 3, 3);
    Model m = build_model(mesh, Material{kE, kNu, 1000}, {});
    std::vector<V3> fsum(m.num_nodes(), V3::Zero());
    double lambda, mu;
    lame(kE, kNu, lambda, mu);
    const M3 eps = G;  // symmetric
    const M3 sigma_exact = 2 * mu * eps + lambda * eps.trace() * M3::Identity();
    for (int e = 0; e < m.num_tets(); ++e) {
      V3 x[4], g[4], f[4];
      for (int a = 0; a < 4; ++a) {
        x[a] = m.rest[m.tets[e][a]] + G * m.rest[m.tets[e][a]];
        g[a] = m.grad[e][a];
      }
      const M3 F = fem::deformation_gradient<double>(x, g);
      QVERIFY((F - (M3::Identity() + G)).norm() < 1e-12);  // uniform gradient, exactly
      Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
      fem::extract_rotation<double>(F, q, 50);
      // Symmetric G: no rotation part.
      QVERIFY((q.toRotationMatrix() - M3::Identity()).norm() < 1e-12);
      const M3 S = fem::linear_stress<double>(F - M3::Identity(), lambda, mu);
      QVERIFY((S - sigma_exact).norm() < 1e-9 * sigma_exact.norm());
      fem::element_forces<double>(F, q.toRotationMatrix(), g, m.volume[e], lambda, mu, f);
      for (int a = 0; a < 4; ++a) fsum[m.tets[e][a]] += f[a];
    }
    // Interior nodes: net force zero (to round-off relative to element forces ~1e-3 N).
    for (int i = 0; i < m.num_nodes(); ++i) {
      const V3& p = m.rest[i];
      const bool interior = (p.array().abs() < 0.0149).all() && p.z() > 1e-4 && p.z() < 0.0299;
      if (interior) QVERIFY2(fsum[i].norm() < 1e-12, qPrintable(QString::number(fsum[i].norm())));
    }
  }

  // K_ab = -d f_a / d x_b at small deformation, by central differences. Step 1e-7 m on
  // 1 cm elements: truncation O(h^2) and round-off O(eps f / h) both ~1e-9 relative; the
  // corotational K drops dR/dx terms, which are O(strain) relative: with strains ~1e-4
  // the tolerance is 1e-3 of ||K||.
  void stiffnessMatchesFiniteDifferences() {
    Tet t;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1e-6, 1e-6);
    V3 x[4];
    for (int a = 0; a < 4; ++a) x[a] = t.X[a] + V3(u(rng), u(rng), u(rng));
    double lambda, mu;
    lame(kE, kNu, lambda, mu);
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
    const M3 F = fem::deformation_gradient<double>(x, t.g);
    fem::extract_rotation<double>(F, q, 50);
    const M3 R = q.toRotationMatrix();
    V3 r[4];
    for (int a = 0; a < 4; ++a) r[a] = R * t.g[a];
    Eigen::Matrix<double, 12, 12> K, Kfd;
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        K.block<3, 3>(3 * a, 3 * b) = fem::stiffness_block<double>(r[a], r[b], t.g[a].dot(t.g[b]), t.vol, lambda, mu);
    const double h = 1e-7;
    for (int b = 0; b < 4; ++b)
      for (int c = 0; c < 3; ++c) {
        V3 xp[4], xm[4], fp[4], fm[4];
        for (int a = 0; a < 4; ++a) xp[a] = xm[a] = x[a];
        xp[b][c] += h;
        xm[b][c] -= h;
        Eigen::Quaterniond qp = q, qm = q;
        forces(t, xp, qp, fp);
        forces(t, xm, qm, fm);
        for (int a = 0; a < 4; ++a) Kfd.block<3, 1>(3 * a, 3 * b + c) = -(fp[a] - fm[a]) / (2 * h);
      }
    const double rel = (K - Kfd).norm() / K.norm();
    QVERIFY2(rel < 1e-3, qPrintable(QString::number(rel)));
    // Symmetric positive semi-definite with exactly 6 zero modes (rigid motions).
    QVERIFY((K - K.transpose()).norm() < 1e-12 * K.norm());
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 12, 12>> es(K);
    int zero = 0;
    for (int i = 0; i < 12; ++i) {
      QVERIFY(es.eigenvalues()[i] > -1e-9 * es.eigenvalues().maxCoeff());
      if (es.eigenvalues()[i] < 1e-9 * es.eigenvalues().maxCoeff()) ++zero;
    }
    QCOMPARE(zero, 6);
  }

  // The matrix-free product equals the assembled blocks.
  void matrixFreeApplyMatchesBlocks() {
    Tet t;
    const M3 R = Eigen::AngleAxisd(0.7, V3(1, 2, 3).normalized()).toRotationMatrix();
    double lambda, mu;
    lame(kE, kNu, lambda, mu);
    V3 r[4], p[4], y[4];
    for (int a = 0; a < 4; ++a) {
      r[a] = R * t.g[a];
      p[a] = V3(0.1 * a, -0.2, 0.3 + a);
    }
    fem::stiffness_apply<double>(r, t.vol, lambda, mu, p, y);
    for (int a = 0; a < 4; ++a) {
      V3 ref = V3::Zero();
      for (int b = 0; b < 4; ++b) ref += fem::stiffness_block<double>(r[a], r[b], t.g[a].dot(t.g[b]), t.vol, lambda, mu) * p[b];
      QVERIFY((ref - y[a]).norm() < 1e-12 * (1 + ref.norm()));
    }
  }

  // Inverted element (one node pushed through the opposite face): the rotation is still
  // a proper rotation (det +1, orthonormal), and the elastic force pushes the node back.
  void invertedElementHasProperRotationAndRestoringForce() {
    Tet t;
    V3 x[4], f[4];
    for (int a = 0; a < 4; ++a) x[a] = t.X[a];
    x[3] = V3(0.004, 0.004, -0.004);  // below the base face (z ~ 0): inverted
    const M3 F = fem::deformation_gradient<double>(x, t.g);
    QVERIFY(F.determinant() < 0);
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
    forces(t, x, q, f);
    const M3 R = q.toRotationMatrix();
    QVERIFY(std::abs(R.determinant() - 1) < 1e-12);
    QVERIFY((R.transpose() * R - M3::Identity()).norm() < 1e-12);
    QVERIFY(f[3].z() > 0);  // pushed back up through the face
    for (int a = 0; a < 4; ++a) QVERIFY(f[a].allFinite());
  }

  // The four-lane extraction (the CPU backend's) is the scalar one lane by lane: the same
  // warm start and iteration count give the same rotation to round-off (1e-12 in double,
  // 1e-5 in float: a few ulps of the iteration's divisions and roots), for mildly
  // deformed, strongly rotated (past the series' 1e-2 rad, cos/sin lane by lane) and
  // inverted elements, with lanes stopping at different iterations. And a NaN lane
  // gives NaN like the scalar loop, without touching the others.
  void fourLaneExtractionMatchesScalar() {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    auto check = [&](auto zero, double tol) {
      using T = decltype(zero);
      using V4 = palpation::sim::lanes::V4<T>;
      for (int trial = 0; trial < 200; ++trial) {
        V4 A[9], q[4];
        Eigen::Quaternion<T> qs[4];
        fem::Mat3<T> F[4];
        for (int l = 0; l < 4; ++l) {
          // Lane kinds: near identity, rotated by up to 1.5 rad, inverted, already converged.
          const int kind = (trial + l) % 4;
          const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
          const double angle = kind == 1 ? 1.5 * u(rng) : 0.01 * u(rng);
          M3 Fd = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) Fd(i, j) += (kind == 3 ? 0.0 : 0.05) * u(rng);
          if (kind == 2) Fd.col(2) *= -0.5;  // det < 0
          F[l] = Fd.cast<T>();
          qs[l] = kind == 3 ? Eigen::Quaternion<T>(Eigen::AngleAxis<T>(T(angle), axis.cast<T>()))
                            : Eigen::Quaternion<T>::Identity();
          for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) A[3 * j + i][l] = F[l](i, j);
          q[0][l] = qs[l].w();
          q[1][l] = qs[l].x();
          q[2][l] = qs[l].y();
          q[3][l] = qs[l].z();
        }
        fem::extract_rotation4<T>(A, q);
        for (int l = 0; l < 4; ++l) {
          fem::extract_rotation<T>(F[l], qs[l]);
          const Eigen::Quaternion<T> ql(q[0][l], q[1][l], q[2][l], q[3][l]);
          const double d = double((ql.toRotationMatrix() - qs[l].toRotationMatrix()).cwiseAbs().maxCoeff());
          if (!(d <= tol)) qWarning("trial %d lane %d: differs by %g", trial, l, d);
          QVERIFY(d <= tol);
        }
      }
      // NaN in lane 1 only.
      V4 A[9] = {}, q[4] = {{1, 1, 1, 1}, {}, {}, {}};
      for (int j = 0; j < 3; ++j) A[4 * j] = V4{1, 1, 1, 1};  // identity in every lane
      A[0][1] = std::numeric_limits<T>::quiet_NaN();
      fem::extract_rotation4<T>(A, q);
      QVERIFY(std::isnan(q[0][1]));
      for (int l : {0, 2, 3}) QCOMPARE(double(q[0][l]), 1.0);
    };
    check(double(0), 1e-12);
    check(float(0), 1e-5);
  }
};

QTEST_APPLESS_MAIN(TestFemCorotational)
#include "tst_fem_corotational.moc"
