// Tissue layers (sim/tissue_layers.h): the depth below the skin against the box's exact
// one, each element's modulus against its layers (exact inside a layer, the volume
// average across a boundary), the tumour rule against the element's own tissue, the
// scenario path and the presets file.
#include <QtTest>

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "mesh.h"
#include "simulation.h"
#include "tissue_layers.h"

using namespace palpation::sim;

namespace {

const Eigen::Vector3d kSize(0.04, 0.03, 0.02);  // m; base on z = 0, centred on x = y = 0

// Skin 2 mm (stiff), fat 5 mm, glandular below: bands the 2.5 mm cells cut through.
std::vector<TissueLayer> layers() { return {{"skin", 0.002, 56000.0}, {"fat", 0.005, 19000.0}, {"glandular", 0.0, 31500.0}}; }

// The box with only its top as skin (its other boundary faces taken off the model's
// surface, as if the box were cut from a wider slab): depth = top - z.
Model slab() {
  Model m = build_model(make_box_mesh(kSize, 16, 12, 8), Material{19000.0, 0.45, 1000.0}, fix_base());
  std::erase_if(m.surface, [&](const std::array<int, 3>& t) {
    for (int v : t)
      if (m.rest[std::size_t(v)].z() < kSize.z() - 1e-12) return true;
    return false;
  });
  return m;
}

}  // namespace

class TestTissueLayers : public QObject {
  Q_OBJECT

 private slots:
  // The box fixed at its base: the skin is the top and the four sides, and a node's depth
  // is its distance to the nearest of the five planes (the box is convex). Only depths up
  // to the search's reach are exact; deeper nodes read the reach.
  void depthsAreDistancesToTheSkin() {
    const Model m = build_model(make_box_mesh(kSize, 16, 12, 8), Material{}, fix_base());
    const double reach = 0.006;
    const std::vector<double> d = skin_depths(m, reach);
    QCOMPARE(int(d.size()), m.num_nodes());
    int inside = 0;
    for (int v = 0; v < m.num_nodes(); ++v) {
      const Eigen::Vector3d& p = m.rest[std::size_t(v)];
      const double exact = std::min({kSize.z() - p.z(), 0.5 * kSize.x() - std::abs(p.x()), 0.5 * kSize.y() - std::abs(p.y())});
      QVERIFY2(std::abs(d[std::size_t(v)] - std::min(exact, reach)) < 1e-12, qPrintable(QString::number(v)));
      inside += exact < reach;
    }
    QVERIFY(inside > 0 && inside < m.num_nodes());  // both kinds of node were checked
  }

  // Depth = top - z on the slab. An element within one band takes its modulus exactly; one
  // cut by a boundary lies strictly between the two; and the volume-weighted compliance
  // (1 / E: the bands in series) matches the bands' integral: the 216-point rule puts a cut
  // element's boundary within a sixth of its depth span, and the errors of the cut elements
  // (about a third of those in the two cut cell layers) partly cancel; 1 % bounds it
  // (measured 0.03 %).
  void elementsTakeTheirLayersModulus() {
    Model m = slab();
    const std::vector<int> count = apply_layers(m, layers());
    QCOMPARE(int(count.size()), 3);
    QCOMPARE(count[0] + count[1] + count[2], m.num_tets());
    for (int c : count) QVERIFY(c > 0);
    const std::vector<double> depth = skin_depths(m, 0.014);
    double sum = 0, volume = 0;
    int cut = 0;
    for (int e = 0; e < m.num_tets(); ++e) {
      double lo = 1e9, hi = -1e9;
      for (int v : m.tets[std::size_t(e)]) {
        const double d = kSize.z() - m.rest[std::size_t(v)].z();
        QVERIFY2(std::abs(d - depth[std::size_t(v)]) < 1e-12 || depth[std::size_t(v)] == 0.014,
                 qPrintable(QString("node %1 at depth %2 read %3").arg(v).arg(d).arg(depth[std::size_t(v)])));
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
      const double E = m.materials.young[std::size_t(e)];
      QCOMPARE(m.tissue_young[std::size_t(e)], E);
      QCOMPARE(m.materials.poisson[std::size_t(e)], 0.45);
      const double Elo = layer_modulus(layers(), lo + 1e-12), Ehi = layer_modulus(layers(), hi - 1e-12);
      if (Elo == Ehi) {
        QCOMPARE(E, Elo);
      } else {
        ++cut;
        QVERIFY(E > std::min(Elo, Ehi) && E < std::max(Elo, Ehi));
      }
      sum += m.volume[std::size_t(e)] / E;
      volume += m.volume[std::size_t(e)];
    }
    QVERIFY(cut > 0);
    const double area = kSize.x() * kSize.y();
    const double exact = area * (0.002 / 56000.0 + 0.005 / 19000.0 + (kSize.z() - 0.007) / 31500.0);
    QVERIFY(std::abs(volume - area * kSize.z()) < 1e-12);
    qInfo("volume-weighted compliance against the bands: relative error %.2e", (sum - exact) / exact);
    QVERIFY2(std::abs(sum - exact) < 0.01 * exact, qPrintable(QString("relative error %1").arg((sum - exact) / exact)));
  }

  // Through a scenario: the layers come first, the tumour after; the glandular tissue is
  // stiffer than the reference tissue by more than the tumour factor yet is no tumour, and
  // the sphere's elements are, against the tissue they replaced.
  void tumourRuleReadsTheElementsTissue() {
    Scenario s;
    s.patient.phantom = "box";
    s.patient.size = kSize;
    s.patient.resolution.clear();
    s.patient.edge = 0.0025;
    s.layers = layers();
    Inclusion inc;
    inc.center = Eigen::Vector3d(0, 0, 0.01);
    inc.radii = Eigen::Vector3d::Constant(0.004);
    inc.young_modulus = 107000.0;
    s.inclusions.push_back(inc);
    const Model m = build_scenario_model(s, patient_mesh(s));
    QVERIFY(31500.0 > kTumourFactor * s.young_modulus);
    int tumour = 0, gland = 0;
    for (int e = 0; e < m.num_tets(); ++e) {
      const bool stiff = m.materials.young[std::size_t(e)] == 107000.0;
      QCOMPARE(is_tumour_modulus(m.materials.young[std::size_t(e)], m.tissue_young[std::size_t(e)]), stiff);
      tumour += stiff;
      gland += m.materials.young[std::size_t(e)] == 31500.0;
    }
    QVERIFY(tumour > 0 && gland > 0);
    // No layers: every element's tissue is the scenario's.
    s.layers.clear();
    const Model u = build_scenario_model(s, patient_mesh(s));
    for (double E : u.tissue_young) QCOMPARE(E, s.young_modulus);
  }

  // resources/tissue_presets.json documents the built-in breasts' layers with sources: it
  // must say what breast_layers() does.
  void presetsFileMatches() {
    std::ifstream f(PALPATION_SOURCE_DIR "/resources/tissue_presets.json");
    QVERIFY(f.good());
    const nlohmann::json j = nlohmann::json::parse(f);
    const std::vector<TissueLayer> b = breast_layers();
    QCOMPARE(j["layers"].size(), b.size());
    for (std::size_t i = 0; i < b.size(); ++i) {
      const auto& l = j["layers"][i];
      QCOMPARE(l["name"].get<std::string>(), b[i].name);
      QCOMPARE(l.value("thickness", 0.0), b[i].thickness);
      QCOMPARE(l["young_modulus"].get<double>(), b[i].young_modulus);
      QVERIFY(!l["source"].get<std::string>().empty());
    }
    QCOMPARE(b.back().name, std::string("glandular"));
    // The skin preset is what tissue.skin defaults its modulus to.
    QCOMPARE(j["skin"]["young_modulus"].get<double>(), SkinSpec{}.young_modulus);
    QVERIFY(j["skin"]["thickness"].get<double>() > 0 && j["skin"]["thickness"].get<double>() <= kMaxSkinThickness);
  }
};

QTEST_APPLESS_MAIN(TestTissueLayers)
#include "tst_tissue_layers.moc"
