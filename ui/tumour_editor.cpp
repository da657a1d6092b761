#include "tumour_editor.h"

#include <QUndoCommand>

#include "event_text.h"

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

using app::live::MaterialChange;
using app::live::MaterialEdit;
using app::live::Moduli;
using app::live::Tumour;

// One change of element moduli (an undo step), optionally adding or removing a tumour list
// entry. The edit is data: the workstation logs it (English, live/event.h) and the undo
// stack shows it in the language of the moment.
class MaterialCommand : public QUndoCommand {
 public:
  MaterialCommand(TumourEditor* ed, MaterialChange change, const MaterialEdit& edit) : ed_(ed), change_(std::move(change)), edit_(edit) {
    setText(EventText::material_edit(edit));
  }
  void add_entry(int at, Tumour t, bool remove) {
    entry_ = true;
    at_ = at;
    tumour_ = std::move(t);
    remove_ = remove;
  }
  void redo() override {
    ed_->apply(change_.after, edit_);
    if (entry_) remove_ ? ed_->erase_tumour(at_) : ed_->insert_tumour(at_, tumour_);
  }
  void undo() override {
    MaterialEdit undone = edit_;
    undone.undo = true;
    ed_->apply(change_.before, undone);
    if (entry_) remove_ ? ed_->insert_tumour(at_, tumour_) : ed_->erase_tumour(at_);
  }

 private:
  TumourEditor* ed_;
  MaterialChange change_;
  MaterialEdit edit_;
  bool entry_ = false, remove_ = false;
  int at_ = 0;
  Tumour tumour_;
};


}  // namespace

TumourEditor::TumourEditor(app::live::Workstation* ws, QObject* parent) : QObject(parent), ws_(ws) {}

void TumourEditor::patient_changed() {
  undo_.clear();
  emit changed();
}

QStringList TumourEditor::tumour_names() const {
  QStringList l;
  for (const auto& t : document().tumours()) l << EventText::tumour_entry(t.label, int(t.elements.size()));
  return l;
}

void TumourEditor::apply(const Moduli& young, const MaterialEdit& edit) {
  ws_->set_element_young(std::vector<std::pair<int, double>>(young.begin(), young.end()), edit);
  emit changed();
}

void TumourEditor::insert_tumour(int at, const Tumour& t) {
  ws_->tumours().insert_tumour(at, t);
  emit changed();
}

void TumourEditor::erase_tumour(int at) {
  ws_->tumours().erase_tumour(at);
  emit changed();
}

int TumourEditor::add_shape(app::live::TumourShape shape, const Eigen::Vector3d& centre, const Eigen::Vector3d& radii, double young) {
  MaterialChange change = document().shape_change(shape, centre, radii, young);
  if (change.empty()) return 0;
  MaterialEdit edit;
  edit.kind = MaterialEdit::Kind::AddTumour;
  edit.tumour.origin = app::live::TumourLabel::Origin::Shape;
  edit.tumour.shape = shape;
  edit.tumour.centre = centre;
  edit.tumour.young = young;
  Tumour t{edit.tumour, change.elements()};
  const int n = int(t.elements.size());
  auto* c = new MaterialCommand(this, std::move(change), edit);
  c->add_entry(int(document().tumours().size()), std::move(t), false);
  undo_.push(c);
  return n;
}

void TumourEditor::remove_tumour(int i) {
  MaterialChange change = document().removal(i);
  if (change.empty()) return;
  const Tumour& t = document().tumours()[std::size_t(i)];
  MaterialEdit edit;
  edit.kind = MaterialEdit::Kind::RemoveTumour;
  edit.tumour = t.label;
  auto* c = new MaterialCommand(this, std::move(change), edit);
  c->add_entry(i, t, true);
  undo_.push(c);
}

void TumourEditor::set_brush(double radius, double depth, double young) { ws_->tumours().set_brush({radius, depth, young}); }

void TumourEditor::begin_stroke(bool erase) { ws_->tumours().begin_stroke(erase); }

int TumourEditor::dab(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  auto& doc = ws_->tumours();
  const Moduli now = doc.stroke_dab(point, normal);
  // One dab is logged, never listed in the undo stack.
  if (!now.empty()) {
    MaterialEdit edit;
    edit.kind = MaterialEdit::Kind::Dab;
    edit.erase = doc.stroke_erases();
    apply(now, edit);
  }
  return int(now.size());
}

void TumourEditor::end_stroke() {
  auto stroke = ws_->tumours().end_stroke();
  if (!stroke) return;
  MaterialEdit edit;
  edit.kind = MaterialEdit::Kind::Stroke;
  edit.erase = stroke->erase;
  edit.elements = int(stroke->change.after.size());
  auto* c = new MaterialCommand(this, std::move(stroke->change), edit);
  if (stroke->painted) c->add_entry(int(document().tumours().size()), std::move(*stroke->painted), false);
  // push() calls redo(): the stroke is already applied, re-applying the same values is
  // harmless and keeps undo/redo symmetric.
  undo_.push(c);
}

}  // namespace palpation::ui
