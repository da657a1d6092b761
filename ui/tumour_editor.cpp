#include "tumour_editor.h"

#include <QUndoCommand>

#include "recorded_text.h"

namespace palpation::ui {

std::vector<TissuePreset> tissue_presets() {
  // shared/reference/facts.md: the paper (Ueda et al.), Krouskop et al. 1998 (5%
  // precompression, midpoints of the ranges), Samani et al. 2007 (small strain).
  return {
      {TumourEditor::tr("Tumour (paper, 107 kPa)"), 107000, TumourEditor::tr("Ueda et al., paper section 4.1")},
      {TumourEditor::tr("Invasive ductal carcinoma (Krouskop, 5%)"), 102500, TumourEditor::tr("Krouskop et al. 1998: 93-112 kPa at 5% precompression")},
      {TumourEditor::tr("Invasive ductal carcinoma (Krouskop, 20%)"), 509000, TumourEditor::tr("Krouskop et al. 1998: 460-558 kPa at 20% precompression")},
      {TumourEditor::tr("Fibrous tissue (Krouskop, 5%)"), 106000, TumourEditor::tr("Krouskop et al. 1998: 96-116 kPa at 5% precompression")},
      {TumourEditor::tr("DCIS (Krouskop, 20%)"), 299000, TumourEditor::tr("Krouskop et al. 1998: 291-307 kPa at 20% precompression")},
      {TumourEditor::tr("Fibroglandular (Krouskop, 5%)"), 31500, TumourEditor::tr("Krouskop et al. 1998: 28-35 kPa at 5% precompression")},
      {TumourEditor::tr("IDC high grade (Samani)"), 42000, TumourEditor::tr("Samani et al. 2007: 10-43 kPa by grade, small strain")},
      {TumourEditor::tr("Fibroadenoma (Samani, 2x fat)"), 6400, TumourEditor::tr("Samani et al. 2007: about 6.4 kPa")},
  };
}

namespace {

// The editor keeps its texts (change names, tumour names) in English only: they go to
// the simulation's event log and the recording as data, and are shown in the chosen
// language through RecordedText (ui/recorded_text.h), as a review shows them. The
// sources are marked for lupdate with QT_TRANSLATE_NOOP in TumourEditor's context, whose
// catalogue entries RecordedText translates with.
QString english(const char* source, int n = -1) {
  QString s = QString::fromUtf8(source);
  if (n >= 0) s.replace(QLatin1String("%n"), QString::number(n));
  return s;
}
QString shown(const QString& english_text) { return RecordedText::event(english_text.toStdString()); }

// One change of element moduli, optionally adding or removing a tumour list entry.
class MaterialCommand : public QUndoCommand {
 public:
  MaterialCommand(TumourEditor* ed, std::map<int, double> before, std::map<int, double> after, const QString& logged)
      : ed_(ed), before_(std::move(before)), after_(std::move(after)) {
    set_logged(logged);
  }
  // The English text (logged) and the undo stack's (shown: the chosen language).
  void set_logged(const QString& logged) {
    logged_ = logged;
    setText(shown(logged));
  }
  void add_entry(int at, const QString& name, std::vector<int> elements, bool remove) {
    entry_ = true;
    at_ = at;
    name_ = name;
    elements_ = std::move(elements);
    remove_ = remove;
  }
  void redo() override {
    ed_->apply(after_, logged_);
    if (entry_) remove_ ? ed_->erase_tumour(at_) : ed_->insert_tumour(at_, name_, elements_);
  }
  void undo() override {
    ed_->apply(before_, QStringLiteral("Undo: %1").arg(logged_));  // English: see english()
    if (entry_) remove_ ? ed_->insert_tumour(at_, name_, elements_) : ed_->erase_tumour(at_);
  }

 private:
  TumourEditor* ed_;
  std::map<int, double> before_, after_;
  bool entry_ = false, remove_ = false;
  int at_ = 0;
  QString name_, logged_;  // English
  std::vector<int> elements_;
};

}  // namespace

TumourEditor::TumourEditor(app::live::Workstation* ws, QObject* parent) : QObject(parent), ws_(ws) {}

void TumourEditor::set_patient(std::shared_ptr<const app::live::PatientGeometry> g) {
  g_ = std::move(g);
  young_ = g_ ? g_->young : std::vector<double>{};
  tumours_.clear();
  undo_.clear();
  painted_count_ = 0;
  if (g_) {
    // Tumours the patient came with (scenario inclusions): one entry.
    std::vector<int> stiff;
    for (std::size_t e = 0; e < young_.size(); ++e)
      if (young_[e] > g_->tissue_young * 1.2) stiff.push_back(int(e));
    const char* own = QT_TRANSLATE_NOOP("palpation::ui::TumourEditor", "Patient's tumour");
    if (!stiff.empty()) tumours_.push_back({english(own), stiff});
  }
  emit changed();
}

QStringList TumourEditor::tumour_names() const {
  QStringList l;
  for (const auto& t : tumours_) l << tr("%1 (%n elements)", nullptr, int(t.elements.size())).arg(shown(t.name));
  return l;
}

void TumourEditor::apply(const std::map<int, double>& young, const QString& text) {
  std::vector<std::pair<int, double>> changes;
  changes.reserve(young.size());
  for (const auto& [e, E] : young) {
    if (e < 0 || e >= int(young_.size())) continue;
    young_[e] = E;
    changes.emplace_back(e, E);
  }
  if (ws_) ws_->set_element_young(std::move(changes), text.toStdString());
  emit changed();
}

void TumourEditor::insert_tumour(int at, const QString& name, const std::vector<int>& elements) {
  at = std::clamp(at, 0, int(tumours_.size()));
  tumours_.insert(tumours_.begin() + at, Tumour{name, elements});
  emit changed();
}

void TumourEditor::erase_tumour(int at) {
  if (at >= 0 && at < int(tumours_.size())) tumours_.erase(tumours_.begin() + at);
  emit changed();
}

int TumourEditor::add_shape(const QString& shape, const Eigen::Vector3d& centre, const Eigen::Vector3d& radii, double young) {
  if (!g_) return 0;
  sim::Inclusion inc;
  inc.shape = shape.toStdString();
  inc.center = centre;
  inc.radii = shape == QLatin1String("sphere") ? Eigen::Vector3d::Constant(radii.x()) : radii;
  std::map<int, double> before, after;
  std::vector<int> elements;
  for (std::size_t e = 0; e < g_->centroid.size(); ++e) {
    if (!inc.contains(g_->centroid[e])) continue;
    before[int(e)] = young_[e];
    after[int(e)] = young;
    elements.push_back(int(e));
  }
  if (elements.empty()) return 0;
  const char* kind = shape == QLatin1String("sphere") ? QT_TRANSLATE_NOOP("palpation::ui::TumourEditor", "Sphere")
                                                     : QT_TRANSLATE_NOOP("palpation::ui::TumourEditor", "Ellipsoid");
  const QString name = english(QT_TRANSLATE_NOOP("palpation::ui::TumourEditor", "%1 at (%2, %3, %4) cm, %5 kPa"))
                           .arg(english(kind))
                           .arg(centre.x() * 100, 0, 'f', 1)
                           .arg(centre.y() * 100, 0, 'f', 1)
                           .arg(centre.z() * 100, 0, 'f', 1)
                           .arg(young / 1000, 0, 'f', 0);
  auto* c = new MaterialCommand(this, std::move(before), std::move(after),
                                english(QT_TRANSLATE_NOOP("palpation::ui::TumourEditor", "Add tumour: %1")).arg(name));
  c->add_entry(int(tumours_.size()), name, elements, false);
  undo_.push(c);
  return int(elements.size());
}

void TumourEditor::remove_tumour(int i) {
  if (!g_ || i < 0 || i >= int(tumours_.size())) return;
  std::map<int, double> before, after;
  for (int e : tumours_[i].elements) {
    before[e] = young_[e];
    after[e] = g_->tissue_young;
  }
  const Tumour& t = tumours_[std::size_t(i)];
  auto* c = new MaterialCommand(this, std::move(before), std::move(after),
                                english(QT_TRANSLATE_NOOP("palpation::ui::TumourEditor", "Remove tumour: %1")).arg(t.name));
  c->add_entry(i, t.name, t.elements, true);
  undo_.push(c);
}

void TumourEditor::begin_stroke(bool erase) {
  stroking_ = true;
  erase_ = erase;
  stroke_old_.clear();
  stroke_new_.clear();
}

int TumourEditor::dab(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  if (!g_ || !stroking_) return 0;
  const Eigen::Vector3d c = point - normal.normalized() * brush_depth_;
  const double target = erase_ ? g_->tissue_young : brush_young_;
  std::map<int, double> now;
  for (std::size_t e = 0; e < g_->centroid.size(); ++e) {
    if ((g_->centroid[e] - c).norm() > brush_radius_) continue;
    const int id = int(e);
    if (young_[e] == target) continue;
    if (!stroke_old_.count(id)) stroke_old_[id] = young_[e];
    stroke_new_[id] = target;
    now[id] = target;
  }
  // One dab is logged, never listed in the undo stack.
  if (!now.empty())
    apply(now, english(erase_ ? QT_TRANSLATE_NOOP("palpation::ui::TumourEditor", "Erase")
                              : QT_TRANSLATE_NOOP("palpation::ui::TumourEditor", "Paint")));
  return int(now.size());
}

void TumourEditor::end_stroke() {
  if (!stroking_) return;
  stroking_ = false;
  if (stroke_new_.empty()) return;
  std::vector<int> elements;
  for (const auto& [e, E] : stroke_new_) elements.push_back(e);
  const int n = int(elements.size());
  auto* c = new MaterialCommand(this, stroke_old_, stroke_new_, QString());
  const char* stroke = erase_ ? QT_TRANSLATE_N_NOOP("palpation::ui::TumourEditor", "Erase stroke (%n elements)")
                              : QT_TRANSLATE_N_NOOP("palpation::ui::TumourEditor", "Paint stroke (%n elements)");
  if (!erase_) {
    ++painted_count_;
    c->add_entry(int(tumours_.size()),
                 english(QT_TRANSLATE_NOOP("palpation::ui::TumourEditor", "Painted tumour %1, %2 kPa"))
                     .arg(painted_count_)
                     .arg(brush_young_ / 1000, 0, 'f', 0),
                 elements, false);
  }
  c->set_logged(english(stroke, n));
  // push() calls redo(): the stroke is already applied, re-applying the same values is
  // harmless and keeps undo/redo symmetric.
  undo_.push(c);
  stroke_old_.clear();
  stroke_new_.clear();
}

}  // namespace palpation::ui
