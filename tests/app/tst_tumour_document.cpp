// The tumour document (app/live/tumour_document.h) without a window or a simulation: a
// structured box mesh with a stiff block in it. Checks the tumour rule, the tumour list a
// patient comes with, shapes, the brush (painting, erasing, strokes as one change), the
// tumours' boundary faces, and the material edits as events (English text, JSON round trip).
#include <QtTest>

#include <algorithm>
#include <map>
#include <set>

#include <Eigen/Geometry>

#include "live/event.h"
#include "live/tumour_document.h"
#include "live/workstation.h"
#include "mesh.h"

using namespace palpation;
using app::live::Brush;
using app::live::Event;
using app::live::EventKind;
using app::live::MaterialEdit;
using app::live::Moduli;
using app::live::PatientGeometry;
using app::live::TumourDocument;
using app::live::TumourLabel;
using app::live::TumourShape;

namespace {

constexpr double kTissue = 19000;

// A 6 x 6 x 3 cm box in 1 cm cubes (6 tetrahedra each); elements whose centroid lies in the
// box's central 2 x 2 x 1 cm at the top are `stiff` Pa, one element is at 1.19 x tissue.
std::shared_ptr<PatientGeometry> box_patient(double stiff, int* stiff_count = nullptr, int* almost = nullptr) {
  const sim::TetMesh m = sim::make_box_mesh(Eigen::Vector3d(0.06, 0.06, 0.03), 6, 6, 3);
  auto g = std::make_shared<PatientGeometry>();
  g->generation = 7;
  g->rest = m.nodes;
  g->tets = m.tets;
  g->surface = m.boundary_faces();
  g->tissue_young = kTissue;
  g->young.assign(m.tets.size(), kTissue);
  int n = 0;
  for (const auto& t : m.tets) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int a = 0; a < 4; ++a) c += m.nodes[std::size_t(t[a])];
    g->centroid.push_back(c / 4.0);
  }
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    const Eigen::Vector3d& c = g->centroid[e];
    if (std::abs(c.x()) < 0.01 && std::abs(c.y()) < 0.01 && c.z() > 0.02) {
      g->young[e] = stiff;
      ++n;
    }
  }
  // A corner element a little stiffer than tissue: not a tumour by the rule.
  int corner = 0;
  for (std::size_t e = 0; e < m.tets.size(); ++e)
    if (g->centroid[e].x() < -0.02 && g->centroid[e].y() < -0.02 && g->centroid[e].z() < 0.01) {
      corner = int(e);
      break;
    }
  g->young[std::size_t(corner)] = 1.19 * kTissue;
  if (stiff_count) *stiff_count = n;
  if (almost) *almost = corner;
  return g;
}

std::vector<std::pair<int, double>> pairs(const Moduli& m) { return {m.begin(), m.end()}; }

}  // namespace

class TstTumourDocument : public QObject {
  Q_OBJECT

 private slots:
  void the_tumour_rule() {
    QVERIFY(!app::live::is_tumour_modulus(kTissue, kTissue));
    QVERIFY(!app::live::is_tumour_modulus(1.2 * kTissue, kTissue));  // strictly above 1.2 x
    QVERIFY(app::live::is_tumour_modulus(1.2 * kTissue * (1 + 1e-9), kTissue));
    QVERIFY(app::live::is_tumour_modulus(107000, kTissue));
    int stiff = 0, almost = 0;
    TumourDocument doc(box_patient(107000, &stiff, &almost));
    QVERIFY(stiff > 0);
    QCOMPARE(doc.generation(), std::uint64_t(7));
    QCOMPARE(doc.tissue_young(), kTissue);
    QCOMPARE(doc.tumour_element_count(), stiff);
    QVERIFY(!doc.is_tumour(almost));
    QVERIFY(!doc.is_tumour(-1) && !doc.is_tumour(int(doc.young().size())));
    // The patient's own tumour: one list entry with exactly the stiff elements.
    QCOMPARE(doc.tumours().size(), std::size_t(1));
    QCOMPARE(int(doc.tumours()[0].label.origin), int(TumourLabel::Origin::Patient));
    QCOMPARE(int(doc.tumours()[0].elements.size()), stiff);
    for (int e : doc.tumours()[0].elements) QCOMPARE(doc.young()[std::size_t(e)], 107000.0);
    // A patient without a stiff element has no list entry.
    TumourDocument healthy(box_patient(kTissue));
    QVERIFY(healthy.tumours().empty());
    QCOMPARE(healthy.tumour_element_count(), 0);
  }

  // A layered patient: glandular tissue (31.5 kPa, 1.66 x the reference tissue) below
  // z = 0.02 m is its elements' own tissue, no tumour; a tumour there is judged against it,
  // and removing or erasing one gives each element its own tissue back.
  void the_tumour_rule_in_layered_tissue() {
    int stiff = 0;
    auto g = box_patient(107000, &stiff);
    constexpr double kGland = 31500;
    g->base_young.assign(g->tets.size(), kTissue);
    int gland = -1, soft_lump = -1;
    for (std::size_t e = 0; e < g->tets.size(); ++e)
      if (g->centroid[e].z() < 0.02 && std::abs(g->centroid[e].x()) > 0.015) {
        g->base_young[e] = kGland;
        if (g->young[e] == kTissue) g->young[e] = kGland;
        if (gland < 0) gland = int(e);
        else if (soft_lump < 0 && g->young[e] == kGland && g->centroid[e].x() > 0.02) soft_lump = int(e);
      }
    QVERIFY(gland >= 0 && soft_lump >= 0);
    g->young[std::size_t(soft_lump)] = 38000;  // 1.21 x the gland: a (soft) tumour there
    TumourDocument doc(g);
    QVERIFY(!doc.is_tumour(gland));
    QVERIFY(doc.is_tumour(soft_lump));
    // The patient's tumours, one entry: the top one and the soft lump.
    QCOMPARE(doc.tumours().size(), std::size_t(1));
    QCOMPARE(doc.tumour_element_count(), stiff + 1);
    const auto c = doc.removal(0);
    QCOMPARE(int(c.after.size()), stiff + 1);
    for (const auto& [e, after] : c.after) QCOMPARE(after, g->base_young[std::size_t(e)]);
    QCOMPARE(c.after.at(soft_lump), kGland);
    const Brush b{0.03, 0.0, 107000};
    const Moduli erase = doc.dab(g->centroid[std::size_t(soft_lump)], Eigen::Vector3d::UnitZ(), b, true);
    QVERIFY(erase.count(soft_lump));
    for (const auto& [e, E] : erase) QCOMPARE(E, g->base_young[std::size_t(e)]);
  }

  // The drawn layer boundary: glandular tissue in the lower two thirds of the box is
  // bounded inside the box by the plane z = 2 cm alone (its faces on the box's own sides
  // and base are left out): 6 x 6 squares of two triangles. Uniform tissue draws none.
  void deep_layer_faces_bound_the_gland() {
    auto g = box_patient(kTissue);
    QVERIFY(app::live::deep_layer_faces(*g).empty());
    g->base_young.assign(g->tets.size(), kTissue);
    QVERIFY(app::live::deep_layer_faces(*g).empty());
    for (std::size_t e = 0; e < g->tets.size(); ++e)
      if (g->centroid[e].z() < 0.02) g->base_young[e] = 31500;
    const auto faces = app::live::deep_layer_faces(*g);
    QCOMPARE(int(faces.size()), 6 * 6 * 2);
    for (const auto& f : faces)
      for (int v : f) QCOMPARE(g->rest[std::size_t(v)].z(), 0.02);
  }

  void shapes() {
    TumourDocument doc(box_patient(kTissue));
    const auto& g = *doc.patient();
    const Eigen::Vector3d c(0.01, -0.01, 0.015);
    // Sphere: radius x only; the centroids within it.
    const auto change = doc.shape_change(TumourShape::Sphere, c, Eigen::Vector3d(0.012, 0.001, 0.001), 200000);
    QVERIFY(!change.empty());
    int inside = 0;
    for (std::size_t e = 0; e < g.centroid.size(); ++e) {
      const bool in = (g.centroid[e] - c).norm() <= 0.012;
      inside += in;
      QCOMPARE(change.after.count(int(e)) == 1, in);
    }
    QCOMPARE(int(change.after.size()), inside);
    for (const auto& [e, E] : change.after) {
      QCOMPARE(E, 200000.0);
      QCOMPARE(change.before.at(e), kTissue);
    }
    // Ellipsoid: flat along z (2 mm) takes fewer than the sphere of its largest radius.
    const auto flat = doc.elements_in(TumourShape::Ellipsoid, c, Eigen::Vector3d(0.012, 0.012, 0.002));
    QVERIFY(flat.size() < change.after.size());
    for (int e : flat) {
      const Eigen::Vector3d d = (g.centroid[std::size_t(e)] - c).cwiseQuotient(Eigen::Vector3d(0.012, 0.012, 0.002));
      QVERIFY(d.squaredNorm() <= 1.0);
    }
    // Nothing changes until applied; applied, the rule sees a tumour.
    QCOMPARE(doc.tumour_element_count(), 0);
    doc.set_young(pairs(change.after));
    QCOMPARE(doc.tumour_element_count(), inside);
    // Out-of-range elements and non-positive moduli are skipped.
    const auto done = doc.set_young({{-1, 1e5}, {int(g.tets.size()), 1e5}, {0, 0.0}, {0, -5.0}});
    QVERIFY(done.empty());
  }

  void brush_paints_and_erases() {
    TumourDocument doc(box_patient(kTissue));
    const auto& g = *doc.patient();
    const Brush b{0.01, 0.008, 150000};
    const Eigen::Vector3d p(0.0, 0.0, 0.03), n(0, 0, 2.0);  // top face, unnormalized outward normal
    const Eigen::Vector3d ball = p - Eigen::Vector3d(0, 0, b.depth);
    const auto under = doc.elements_under_brush(p, n, b);
    QVERIFY(!under.empty());
    for (std::size_t e = 0; e < g.centroid.size(); ++e) {
      const bool in = (g.centroid[e] - ball).norm() <= b.radius;
      QCOMPARE(std::count(under.begin(), under.end(), int(e)) == 1, in);
    }
    // Painting: every touched element to the brush's modulus.
    const Moduli paint = doc.dab(p, n, b, false);
    QCOMPARE(paint.size(), under.size());
    for (const auto& [e, E] : paint) QCOMPARE(E, b.young);
    // Erasing healthy tissue changes nothing.
    QVERIFY(doc.dab(p, n, b, true).empty());
    doc.set_young(pairs(paint));
    // Painted elements are not painted again; erasing takes them back to the tissue's.
    QVERIFY(doc.dab(p, n, b, false).empty());
    const Moduli erase = doc.dab(p, n, b, true);
    QCOMPARE(erase.size(), under.size());
    for (const auto& [e, E] : erase) QCOMPARE(E, kTissue);
    // A smaller brush at the same point touches a subset.
    const auto small = doc.elements_under_brush(p, n, Brush{0.005, 0.008, 150000});
    QVERIFY(small.size() < under.size());
    for (int e : small) QVERIFY(std::count(under.begin(), under.end(), e) == 1);
  }

  void strokes_are_one_change() {
    TumourDocument doc(box_patient(kTissue));
    const std::vector<double> before = doc.young();
    doc.set_brush({0.008, 0.006, 150000});
    QVERIFY(doc.stroke_dab(Eigen::Vector3d(0, 0, 0.03), Eigen::Vector3d::UnitZ()).empty());  // no stroke yet
    doc.begin_stroke(false);
    QVERIFY(doc.stroking());
    std::set<int> painted;
    for (int i = 0; i < 3; ++i) {
      const Moduli m = doc.stroke_dab(Eigen::Vector3d(-0.01 + 0.01 * i, 0, 0.03), Eigen::Vector3d::UnitZ());
      for (const auto& [e, E] : m) painted.insert(e);
      doc.set_young(pairs(m));  // as the workstation applies each dab at once
    }
    QVERIFY(!painted.empty());
    const auto stroke = doc.end_stroke();
    QVERIFY(stroke && !doc.stroking());
    QVERIFY(!stroke->erase);
    QCOMPARE(stroke->change.after.size(), painted.size());
    for (const auto& [e, E] : stroke->change.after) {
      QCOMPARE(E, 150000.0);
      QCOMPARE(stroke->change.before.at(e), before[std::size_t(e)]);  // before the stroke, not before the dab
    }
    QVERIFY(stroke->painted);
    QCOMPARE(int(stroke->painted->label.origin), int(TumourLabel::Origin::Painted));
    QCOMPARE(stroke->painted->label.number, 1);
    QCOMPARE(stroke->painted->label.young, 150000.0);
    QCOMPARE(stroke->painted->elements.size(), painted.size());
    // Undo is the change's before.
    doc.set_young(pairs(stroke->change.before));
    QVERIFY(doc.young() == before);
    // A stroke that changes nothing gives nothing; the next paint stroke is number 2.
    doc.begin_stroke(true);
    QVERIFY(doc.stroke_dab(Eigen::Vector3d(0, 0, 0.03), Eigen::Vector3d::UnitZ()).empty());
    QVERIFY(!doc.end_stroke());
    doc.begin_stroke(false);
    doc.set_young(pairs(doc.stroke_dab(Eigen::Vector3d(0, 0, 0.03), Eigen::Vector3d::UnitZ())));
    const auto second = doc.end_stroke();
    QVERIFY(second && second->painted && second->painted->label.number == 2);
    // Erasing it: one change back to tissue, no list entry.
    doc.begin_stroke(true);
    doc.set_young(pairs(doc.stroke_dab(Eigen::Vector3d(0, 0, 0.03), Eigen::Vector3d::UnitZ())));
    const auto erased = doc.end_stroke();
    QVERIFY(erased && erased->erase && !erased->painted);
    for (const auto& [e, E] : erased->change.after) QCOMPARE(E, kTissue);
    QVERIFY(doc.young() == before);
  }

  void tumour_list() {
    int stiff = 0;
    TumourDocument doc(box_patient(107000, &stiff));
    const auto removal = doc.removal(0);
    QCOMPARE(int(removal.after.size()), stiff);
    for (const auto& [e, E] : removal.after) {
      QCOMPARE(E, kTissue);
      QCOMPARE(removal.before.at(e), 107000.0);
    }
    QVERIFY(doc.removal(1).empty() && doc.removal(-1).empty());
    app::live::Tumour t;
    t.label.origin = TumourLabel::Origin::Shape;
    t.elements = {1, 2};
    doc.insert_tumour(99, t);  // clamped to the end
    QCOMPARE(doc.tumours().size(), std::size_t(2));
    QCOMPARE(int(doc.tumours()[1].label.origin), int(TumourLabel::Origin::Shape));
    doc.erase_tumour(0);
    QCOMPARE(doc.tumours().size(), std::size_t(1));
    QCOMPARE(int(doc.tumours()[0].label.origin), int(TumourLabel::Origin::Shape));
    doc.erase_tumour(5);  // no such entry: nothing
    QCOMPARE(doc.tumours().size(), std::size_t(1));
    // A new patient starts afresh.
    doc.set_patient(box_patient(107000));
    QCOMPARE(doc.tumours().size(), std::size_t(1));
    QCOMPARE(int(doc.tumours()[0].label.origin), int(TumourLabel::Origin::Patient));
  }

  void boundary_faces() {
    TumourDocument doc(box_patient(kTissue));
    QVERIFY(doc.tumour_faces().empty());
    const auto& g = *doc.patient();
    // One tumour element: its four faces, outward (away from its centroid).
    const int e0 = 0;
    doc.set_young({{e0, 107000}});
    auto faces = doc.tumour_faces();
    QCOMPARE(faces.size(), std::size_t(4));
    for (const auto& f : faces) {
      const Eigen::Vector3d a = g.rest[std::size_t(f[0])], b = g.rest[std::size_t(f[1])], c = g.rest[std::size_t(f[2])];
      const Eigen::Vector3d normal = (b - a).cross(c - a);
      QVERIFY(normal.dot((a + b + c) / 3.0 - g.centroid[std::size_t(e0)]) > 0);
    }
    // A neighbour sharing a face: the shared face is inside, 6 faces remain.
    const std::set<int> n0(g.tets[0].begin(), g.tets[0].end());
    int e1 = -1;
    for (int e = 1; e < int(g.tets.size()) && e1 < 0; ++e) {
      int shared = 0;
      for (int v : g.tets[std::size_t(e)]) shared += int(n0.count(v));
      if (shared == 3) e1 = e;
    }
    QVERIFY(e1 > 0);
    doc.set_young({{e1, 107000}});
    faces = doc.tumour_faces();
    QCOMPARE(faces.size(), std::size_t(6));
    // The patient's stiff block: a closed surface (every edge in exactly two faces).
    TumourDocument block(box_patient(107000));
    std::map<std::pair<int, int>, int> edges;
    for (const auto& f : block.tumour_faces())
      for (int k = 0; k < 3; ++k) ++edges[{std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])}];
    QVERIFY(!edges.empty());
    for (const auto& [edge, count] : edges) QCOMPARE(count, 2);
  }

  // The edits as events: the one English text and the recording's JSON round trip.
  void edits_as_events() {
    MaterialEdit add;
    add.kind = MaterialEdit::Kind::AddTumour;
    add.tumour.origin = TumourLabel::Origin::Shape;
    add.tumour.centre = Eigen::Vector3d(0.10, 0.02, 0.02);
    add.tumour.young = 300000;
    QCOMPARE(QString::fromStdString(Event::material(add).text()), QStringLiteral("Add tumour: Sphere at (10.0, 2.0, 2.0) cm, 300 kPa"));
    MaterialEdit stroke;
    stroke.kind = MaterialEdit::Kind::Stroke;
    stroke.elements = 12;
    stroke.undo = true;
    QCOMPARE(QString::fromStdString(Event::material(stroke).text()), QStringLiteral("Undo: Paint stroke (12 elements)"));
    stroke.elements = 1;
    stroke.undo = false;
    stroke.erase = true;
    QCOMPARE(QString::fromStdString(app::live::material_edit_text(stroke)), QStringLiteral("Erase stroke (1 element)"));
    QCOMPARE(QString::fromStdString(Event::patient_loaded(1021, 4410, "cpu").text()),
             QStringLiteral("patient loaded: 1021 nodes, 4410 tetrahedra, backend cpu"));
    QCOMPARE(QString::fromStdString(Event::trainee_mark(2, Eigen::Vector3d(0.125, 0, 0.06), "hard").text()),
             QStringLiteral("trainee mark 2 at (12.5, 0.0, 6.0) cm: hard"));
    MaterialEdit painted;
    painted.kind = MaterialEdit::Kind::RemoveTumour;
    painted.tumour.origin = TumourLabel::Origin::Painted;
    painted.tumour.number = 3;
    painted.tumour.young = 150000;
    const std::vector<Event> all{Event::material(add),
                                 Event::material(stroke),
                                 Event::material(painted),
                                 Event::patient_loaded(1021, 4410, "cpu"),
                                 Event::patient_loading("breast-small"),
                                 Event::with_detail(EventKind::Reset, "energy grew"),
                                 Event::params(),
                                 Event::mode_change(app::live::ModeChange::Trainee),
                                 Event::trainee_mark(2, Eigen::Vector3d(0.125, 0, 0.06), "hard"),
                                 Event::trainee_mark(1)};
    for (const Event& e : all) {
      const auto back = app::live::event_from_json(app::live::event_kind_name(e.kind), app::live::event_args_json(e), 1.5);
      QVERIFY2(back, e.text().c_str());
      QCOMPARE(int(back->kind), int(e.kind));
      QCOMPARE(back->t, 1.5);
      QCOMPARE(QString::fromStdString(back->text()), QString::fromStdString(e.text()));
    }
    // Unknown kinds and malformed arguments are refused (the review shows the text then).
    QVERIFY(!app::live::event_from_json("patient", nlohmann::json::object()));
    QVERIFY(!app::live::event_from_json("patient-loaded", {{"nodes", "many"}}));
    QVERIFY(!app::live::event_from_json("material", {{"edit", "dab"}}));
  }
};

QTEST_GUILESS_MAIN(TstTumourDocument)
#include "tst_tumour_document.moc"
