// The mesh's order for locality (TetMesh::order_for_locality, which build_model applies):
// the same geometry, orientation and regions in the new numbering, tetrahedra sorted by
// their lowest node, each connected piece numbered in one run, a shuffled mesh's edges
// brought as near together as the box's own structured numbering has them, the result
// decided by the mesh alone, and a press that feels the same whatever order the mesh came in.
#include <QtTest>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "box_scenario.h"
#include "mesh.h"
#include "model.h"
#include "simulation.h"

using namespace palpation::sim;

namespace {

// The box's nodes and tetrahedra in a random order (fixed seed); each tetrahedron keeps
// its own node order, so its orientation.
TetMesh shuffled(const TetMesh& m, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<int> perm(m.nodes.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), rng);
  TetMesh s;
  s.nodes.resize(m.nodes.size());
  for (std::size_t i = 0; i < perm.size(); ++i) s.nodes[std::size_t(perm[i])] = m.nodes[i];
  std::vector<int> by(m.tets.size());
  std::iota(by.begin(), by.end(), 0);
  std::shuffle(by.begin(), by.end(), rng);
  for (int e : by) {
    auto t = m.tets[std::size_t(e)];
    for (int& v : t) v = perm[std::size_t(v)];
    s.tets.push_back(t);
    s.region.push_back(m.region[std::size_t(e)]);
  }
  return s;
}

// The box with a region tag that follows the geometry (the tetrahedra whose centroid lies
// above the middle are region 1), so that a tag left behind by the sort shows.
TetMesh tagged_box(int n) {
  TetMesh m = make_box_mesh(Eigen::Vector3d(0.04, 0.04, 0.02), n, n, n);
  m.region.assign(m.tets.size(), 0);
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    double z = 0;
    for (int v : m.tets[e]) z += m.nodes[std::size_t(v)].z() / 4;
    m.region[e] = z > 0.01 ? 1 : 0;
  }
  return m;
}

// Each tetrahedron as its corner coordinates (sorted) and region: what the order must keep.
std::vector<std::pair<std::array<double, 12>, int>> geometry(const TetMesh& m) {
  std::vector<std::pair<std::array<double, 12>, int>> g;
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    std::array<std::array<double, 3>, 4> c;
    for (int k = 0; k < 4; ++k) {
      const auto& p = m.nodes[std::size_t(m.tets[e][std::size_t(k)])];
      c[std::size_t(k)] = {p.x(), p.y(), p.z()};
    }
    std::sort(c.begin(), c.end());
    std::array<double, 12> flat;
    for (int k = 0; k < 12; ++k) flat[std::size_t(k)] = c[std::size_t(k / 3)][std::size_t(k % 3)];
    g.emplace_back(flat, m.region[e]);
  }
  std::sort(g.begin(), g.end());
  return g;
}

// Mean |i - j| over the tetrahedra's edges: how far apart in memory neighbours are.
double mean_edge_span(const TetMesh& m) {
  double sum = 0;
  long count = 0;
  for (const auto& t : m.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        sum += std::abs(t[std::size_t(a)] - t[std::size_t(b)]);
        ++count;
      }
  return sum / double(count);
}

}  // namespace

class TestMeshOrder : public QObject {
  Q_OBJECT
 private slots:
  void keepsGeometryOrientationAndRegions() {
    const TetMesh box = tagged_box(6);
    TetMesh m = shuffled(box, 7);
    const auto before = geometry(m);
    const std::size_t faces = m.boundary_faces().size();
    const TetMesh given = m;
    const std::vector<int> from = m.order_for_locality();
    QCOMPARE(m.validate(), std::string());
    QCOMPARE(m.num_nodes(), box.num_nodes());
    QCOMPARE(m.num_tets(), box.num_tets());
    QVERIFY(geometry(m) == before);
    QCOMPARE(m.boundary_faces().size(), faces);
    // Each tetrahedron says where it was: the same corners, by position, as that one.
    QCOMPARE(from.size(), m.tets.size());
    for (std::size_t e = 0; e < m.tets.size(); ++e) {
      const auto& was = given.tets[std::size_t(from[e])];
      for (int k = 0; k < 4; ++k)
        QCOMPARE(m.nodes[std::size_t(m.tets[e][std::size_t(k)])], given.nodes[std::size_t(was[std::size_t(k)])]);
      QCOMPARE(m.region[e], given.region[std::size_t(from[e])]);
    }
    // Every tetrahedron keeps its positive orientation (make_box_mesh's are positive):
    // nothing is flipped by a renumbering.
    for (const auto& t : m.tets)
      QVERIFY(tet_volume(m.nodes[std::size_t(t[0])], m.nodes[std::size_t(t[1])], m.nodes[std::size_t(t[2])],
                         m.nodes[std::size_t(t[3])]) > 0);
  }

  void sortsTetrahedraByTheirLowestNode() {
    TetMesh m = shuffled(tagged_box(5), 11);
    m.order_for_locality();
    int last = -1;
    for (const auto& t : m.tets) {
      const int low = *std::min_element(t.begin(), t.end());
      QVERIFY(low >= last);
      last = low;
    }
  }

  // The box's structured numbering (x fastest, then y, then z) keeps an edge's ends
  // within about one layer of nodes; the shuffled box spreads them over a third of the
  // mesh. The order must bring the shuffled box back to within the structured numbering's
  // span (reverse Cuthill-McKee walks level sets about a layer wide), at 8 and 12 cells a
  // side, so the bound is not one size's luck.
  void narrowsAShuffledMeshToTheStructuredSpan() {
    for (int n : {8, 12}) {
      const TetMesh box = tagged_box(n);
      TetMesh m = shuffled(box, 3);
      const double structured = mean_edge_span(box), scattered = mean_edge_span(m);
      m.order_for_locality();
      const double ordered = mean_edge_span(m);
      qInfo("%d cells a side: mean edge span structured %.1f, shuffled %.1f, ordered %.1f", n, structured, scattered,
            ordered);
      QVERIFY(scattered > 3 * structured);  // the shuffle did scatter them
      QVERIFY(ordered <= structured);
    }
  }

  void decidedByTheMeshAlone() {
    TetMesh a = shuffled(tagged_box(5), 5), b = shuffled(tagged_box(5), 5);
    a.order_for_locality();
    b.order_for_locality();
    QCOMPARE(a.hash(), b.hash());
  }

  // Two boxes apart, their nodes interleaved: each piece comes out as one run of node
  // numbers (the walk numbers a piece before it leaves it), and nothing is lost.
  void numbersEachPieceInOneRun() {
    const TetMesh one = make_box_mesh(Eigen::Vector3d(0.02, 0.02, 0.02), 3, 3, 3);
    TetMesh two = one;
    for (auto& p : two.nodes) p.x() += 0.1;
    TetMesh both = one;
    const int off = one.num_nodes();
    both.nodes.insert(both.nodes.end(), two.nodes.begin(), two.nodes.end());
    for (auto t : two.tets) {
      for (int& v : t) v += off;
      both.tets.push_back(t);
    }
    both.region.assign(both.tets.size(), 0);
    both = shuffled(both, 13);
    both.order_for_locality();
    QCOMPARE(both.num_nodes(), 2 * off);
    QCOMPARE(both.validate(), std::string());
    int lo_far = both.num_nodes(), hi_far = -1;
    for (int i = 0; i < both.num_nodes(); ++i)
      if (both.nodes[std::size_t(i)].x() > 0.05) {
        lo_far = std::min(lo_far, i);
        hi_far = std::max(hi_far, i);
      }
    QCOMPARE(hi_far - lo_far + 1, off);
  }

  // The physics does not see the numbering: a finger pressed 2 mm into the box over 60
  // steps and held, on the box as made and on the same box shuffled (build_model orders
  // both, from different starts, so their numberings differ). CG to 1e-10 in double, every
  // element re-rotated each step: the two solves differ only by rounding and their
  // stopping points, each within 1e-10 of the exact step, so the forces agree to far
  // better than 1e-6 of their size.
  void aPressFeelsTheSameInAnyOrder() {
    Scenario s = box_scenario("tst_mesh_order", Eigen::Vector3d(0.04, 0.04, 0.02), 0.004, "cpu");
    s.params.solver.precision = Precision::Double;
    s.params.solver.cg_tolerance = 1e-10;
    s.params.solver.cg_max_iterations = 5000;
    s.params.solver.force_error = 0;
    s.params.solver.corotation_tolerance = 0;
    const TetMesh box = make_box_mesh(s.patient.size, s.patient.edge);
    const Model made = build_scenario_model(s, box), mixed = build_scenario_model(s, shuffled(box, 17));
    QVERIFY(made.num_nodes() == mixed.num_nodes());
    auto press = [&](const Model& m) {
      Simulation sim(s, m);
      std::vector<FingerInput> in(1);
      std::vector<FingerOutput> out(1);
      const double r = 0.006;
      in[0].radius = r;
      std::vector<Eigen::Vector3d> f;
      for (int k = 1; k <= 80; ++k) {
        const double depth = 0.002 * std::min(1.0, k / 60.0);
        in[0].position = Eigen::Vector3d(0.001, -0.002, 0.02 + r - depth);
        const auto o = sim.advance(in, out, s.params.solver.dt);
        if (!o.ok) return std::vector<Eigen::Vector3d>{};
        f.push_back(out[0].force_raw);
      }
      return f;
    };
    const auto a = press(made), b = press(mixed);
    QCOMPARE(a.size(), std::size_t(80));
    QCOMPARE(b.size(), std::size_t(80));
    double worst = 0, peak = 0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      worst = std::max(worst, (a[k] - b[k]).norm());
      peak = std::max(peak, a[k].norm());
    }
    qInfo("peak force %.4g N, largest difference %.3g N", peak, worst);
    QVERIFY(peak > 0.05);  // the finger pressed
    QVERIFY(worst <= 1e-6 * peak);
  }
};

QTEST_APPLESS_MAIN(TestMeshOrder)
#include "tst_mesh_order.moc"
