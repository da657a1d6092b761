#include "event_text.h"

#include <QLocale>

namespace palpation::ui {

using app::live::Event;
using app::live::EventKind;
using app::live::MaterialEdit;
using app::live::ModeChange;
using app::live::TumourLabel;
using app::live::TumourShape;

namespace {
QString fixed(double v, int decimals) { return QString::number(v, 'f', decimals); }
QString text(const std::string& s) { return QString::fromStdString(s); }
}  // namespace

QString EventText::tumour(const TumourLabel& l) {
  switch (l.origin) {
    case TumourLabel::Origin::Patient: return tr("Patient's tumour");
    case TumourLabel::Origin::Shape:
      return tr("%1 at (%2, %3, %4) cm, %5 kPa")
          .arg(l.shape == TumourShape::Sphere ? tr("Sphere") : tr("Ellipsoid"), fixed(l.centre.x() * 100, 1),
               fixed(l.centre.y() * 100, 1), fixed(l.centre.z() * 100, 1), fixed(l.young / 1000, 0));
    case TumourLabel::Origin::Painted: return tr("Painted tumour %1, %2 kPa").arg(QString::number(l.number), fixed(l.young / 1000, 0));
  }
  return {};
}

QString EventText::tumour_entry(const TumourLabel& l, int elements) { return tr("%1 (%n elements)", nullptr, elements).arg(tumour(l)); }

QString EventText::material_edit(const MaterialEdit& e) {
  QString s;
  switch (e.kind) {
    case MaterialEdit::Kind::AddTumour: s = tr("Add tumour: %1").arg(tumour(e.tumour)); break;
    case MaterialEdit::Kind::RemoveTumour: s = tr("Remove tumour: %1").arg(tumour(e.tumour)); break;
    case MaterialEdit::Kind::Dab: s = e.erase ? tr("Erase") : tr("Paint"); break;
    case MaterialEdit::Kind::Stroke:
      s = e.erase ? tr("Erase stroke (%n elements)", nullptr, e.elements) : tr("Paint stroke (%n elements)", nullptr, e.elements);
      break;
  }
  return e.undo ? tr("Undo: %1").arg(s) : s;
}

QString EventText::event(const Event& e) {
  switch (e.kind) {
    case EventKind::PatientLoading: return tr("loading patient: %1").arg(text(e.detail));
    case EventKind::PatientLoaded:
      return tr("patient loaded: %1 nodes, %2 tetrahedra, backend %3").arg(QString::number(e.nodes), QString::number(e.tetrahedra), text(e.detail));
    case EventKind::PatientNotLoaded: return tr("patient not loaded: %1").arg(text(e.detail));
    case EventKind::Params: return tr("solver/contact parameters changed");
    case EventKind::Material: return material_edit(e.edit);
    case EventKind::Mode:
      switch (e.mode) {
        case ModeChange::MousePalpation: return tr("device: mouse palpation");
        case ModeChange::ScriptedHand: return tr("device: scripted hand");
        case ModeChange::Trainee: return tr("trainee mode");
        case ModeChange::Instructor: return tr("instructor mode");
        case ModeChange::GuidedPractice: return tr("guided practice (trainee)");
        case ModeChange::Exam: return tr("exam (trainee)");
      }
      return {};
    case EventKind::Mark: {
      QString s = e.position ? tr("trainee mark %1 at (%2, %3, %4) cm")
                                   .arg(QString::number(e.mark), fixed(e.position->x() * 100, 1), fixed(e.position->y() * 100, 1),
                                        fixed(e.position->z() * 100, 1))
                             : tr("trainee mark %1").arg(e.mark);
      if (e.confidence < 1.0) s += tr(", %1 % confident").arg(fixed(e.confidence * 100, 0));
      if (!e.detail.empty()) s += tr(": %1").arg(text(e.detail));
      return s;
    }
    case EventKind::ExamEnded: return e.mode == ModeChange::GuidedPractice ? tr("guided practice ended") : tr("exam ended");
    case EventKind::Fallback: return tr("backend error: %1; continuing on the CPU from rest (forces held, then blended)").arg(text(e.detail));
    case EventKind::Reset: return tr("simulation diverged (%1): body reset to rest (forces held, then blended)").arg(text(e.detail));
    case EventKind::Error: return text(e.detail);
    case EventKind::Stopped: return tr("simulation stopped: %1").arg(text(e.detail));
  }
  return {};
}

QString EventText::patient_description(const app::store::BuiltinDescription& d) {
  using D = app::store::BuiltinDescription;
  switch (d.kind) {
    case D::Kind::Healthy: {
      const QString what = d.size == D::Size::Small      ? tr("small")
                           : d.size == D::Size::Medium   ? tr("medium")
                           : d.size == D::Size::Large    ? tr("large")
                           : d.size == D::Size::WideFlat ? tr("wide and flat")
                                                         : tr("narrow and projecting");
      // Grouped as the library writes it (1,249 mL), whatever the language.
      const QString ml = QLocale(QLocale::English).toString(d.volume_ml);
      return d.paper_size ? tr("Healthy breast, %1 (%2 mL), the paper's size, no tumour").arg(what, ml)
                          : tr("Healthy breast, %1 (%2 mL), no tumour").arg(what, ml);
    }
    case D::Kind::PaperCase: return tr("The paper's case: medium breast, tumour 3 cm diameter, 107 kPa, centre 2.0 cm below the skin");
    case D::Kind::Tumour: {
      const QString hard = d.hardness == D::Hardness::Soft ? tr("soft") : d.hardness == D::Hardness::Hard ? tr("hard") : tr("firm");
      return tr("Medium breast, %1 tumour %2 cm diameter (%3 kPa), centre %4 cm below the skin")
          .arg(hard, fixed(d.diameter_cm, 1), fixed(d.young_kpa, 0), fixed(d.depth_cm, 1));
    }
  }
  return {};
}

}  // namespace palpation::ui
