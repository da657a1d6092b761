// The workstation's events and the built-in patients' descriptions in the chosen language.
// The app keeps them as data (a kind and its arguments: app/live/event.h; a built-in
// patient's description: app/store/patient_library.h's BuiltinDescription) and composes
// their English text there (logs, the command line, recordings); this composes the shown
// text from the same data through tr(). Text the app holds only as text (a reason from the
// system, a trainee's note, an imported scan's description, events of recordings made
// before events carried their arguments) is shown as it is.
#pragma once

#include <QCoreApplication>
#include <QString>

#include "live/event.h"
#include "store/patient_library.h"

namespace palpation::ui {

class EventText {
  Q_DECLARE_TR_FUNCTIONS(palpation::ui::EventText)

 public:
  /// An event's one-line text.
  static QString event(const app::live::Event& e);
  /// A tumour editor's step (the undo stack's text, a Material event).
  static QString material_edit(const app::live::MaterialEdit& e);
  /// A tumour list entry's name.
  static QString tumour(const app::live::TumourLabel& l);
  /// A tumour list entry: its name and element count.
  static QString tumour_entry(const app::live::TumourLabel& l, int elements);
  /// A built-in patient's description.
  static QString patient_description(const app::store::BuiltinDescription& d);
};

}  // namespace palpation::ui
