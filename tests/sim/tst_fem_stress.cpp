// sim/fem_stress.h: the display stress against closed forms. Invariants, not stored
// numbers: zero at rest and under a rigid rotation (the corotational model feels no
// stress there either); uniaxial strain eps along x gives sigma_xx = (lambda + 2 mu) E,
// sigma_yy = sigma_zz = lambda E with Green strain E = eps + eps^2 / 2, so von Mises
// = 2 mu E; a pure shear gamma gives sqrt(3) mu gamma to first order; the nodal average
// of a uniform field is that field; a stiffer element shows a larger stress.
#include <QtTest>

#include <cmath>

#include <Eigen/Geometry>

#include "fem_stress.h"
#include "mesh.h"
#include "model.h"

using namespace palpation::sim;
using V3 = Eigen::Vector3d;

namespace {
constexpr double kE = 19000, kNu = 0.45;

Model box() { return build_model(make_box_mesh(V3(0.03, 0.03, 0.03), 3, 3, 3), Material{kE, kNu, 1000}, {}); }

std::vector<double> mapped(const Model& m, const std::function<V3(const V3&)>& f) {
  std::vector<double> xyz;
  for (const auto& p : m.rest) {
    const V3 q = f(p);
    xyz.insert(xyz.end(), {q.x(), q.y(), q.z()});
  }
  return xyz;
}
}  // namespace

class TstFemStress : public QObject {
  Q_OBJECT

 private slots:
  void zero_at_rest_and_under_rotation() {
    const Model m = box();
    std::vector<double> vm;
    element_von_mises(m, m.materials, mapped(m, [](const V3& p) { return p; }).data(), vm);
    for (double v : vm) QVERIFY(std::abs(v) < 1e-9);
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, V3(1, 2, 3).normalized()).toRotationMatrix();
    element_von_mises(m, m.materials, mapped(m, [&](const V3& p) { return V3(R * p + V3(0.1, -0.2, 0.05)); }).data(), vm);
    for (double v : vm) QVERIFY(std::abs(v) < 1e-6 * kE);
  }

  void uniaxial_strain_and_shear() {
    const Model m = box();
    double lambda, mu;
    lame(kE, kNu, lambda, mu);
    std::vector<double> vm;
    const double eps = 0.05;
    element_von_mises(m, m.materials, mapped(m, [&](const V3& p) { return V3(p.x() * (1 + eps), p.y(), p.z()); }).data(), vm);
    const double green = eps + 0.5 * eps * eps;
    for (double v : vm) QVERIFY(std::abs(v - 2 * mu * green) < 1e-9 * kE);
    const double gamma = 1e-3;
    element_von_mises(m, m.materials, mapped(m, [&](const V3& p) { return V3(p.x() + gamma * p.y(), p.y(), p.z()); }).data(), vm);
    for (double v : vm) QVERIFY(std::abs(v - std::sqrt(3.0) * mu * gamma) < 1e-3 * std::sqrt(3.0) * mu * gamma);
  }

  void nodal_average() {
    Model m = box();
    const double eps = 0.02;
    const auto xyz = mapped(m, [&](const V3& p) { return V3(p.x() * (1 + eps), p.y(), p.z()); });
    std::vector<float> node;
    StressScratch scratch;
    nodal_von_mises(m, m.materials, xyz.data(), node, scratch);
    QCOMPARE(node.size(), m.rest.size());
    double lambda, mu;
    lame(kE, kNu, lambda, mu);
    const double want = 2 * mu * (eps + 0.5 * eps * eps);
    for (float v : node) QVERIFY(std::abs(v - want) < 1e-4 * want);
    // A tumour element (10x stiffer) raises the stress at its nodes, not elsewhere.
    m.set_element_material(0, 10 * kE, kNu);
    std::vector<float> stiff;
    nodal_von_mises(m, m.materials, xyz.data(), stiff, scratch);
    for (int a = 0; a < 4; ++a) QVERIFY(stiff[m.tets[0][a]] > node[m.tets[0][a]] * 1.01f);
    int changed = 0;
    for (std::size_t i = 0; i < node.size(); ++i) changed += std::abs(stiff[i] - node[i]) > 1e-6f * want;
    QCOMPARE(changed, 4);
  }
};

QTEST_GUILESS_MAIN(TstFemStress)
#include "tst_fem_stress.moc"
