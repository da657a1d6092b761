// Texts that the app layer writes in English, shown in the chosen language. The recorded
// session events (app/live/workstation.cpp's log_event, app/review/review_session.cpp's one-line form)
// and the built-in patients' descriptions (app/store/patient_library.cpp) are data: a recording
// or a patient library reads the same whatever language wrote it. The GUI recomposes the
// texts it knows (fixed phrases and the patterns the app fills with numbers and names)
// through tr() when it shows them; anything else (error messages from the system, a
// trainee's note, an imported scan's description, tumour-editor texts recorded in another
// language) is shown as recorded.
#pragma once

#include <string>

#include <QCoreApplication>
#include <QString>

namespace palpation::ui {

class RecordedText {
  Q_DECLARE_TR_FUNCTIONS(palpation::ui::RecordedText)

 public:
  /// A recorded event's one-line text (ReviewMarker::text) in the current language.
  static QString event(const std::string& text);
  /// A patient's description (PatientRecord::description) in the current language.
  static QString patient_description(const std::string& text);
};

}  // namespace palpation::ui
