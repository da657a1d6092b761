// The exam report (docs/training.md): score.json, the coverage and pressure map, the force
// plot, and the report in HTML and PDF. `palpation score` and the workstation's end of an
// exam write the same files. The pictures and the PDF are drawn with Qt Gui (QPainter,
// QTextDocument, QPdfWriter); the Qt-free build writes score.json and the HTML only.
#pragma once

#include <string>
#include <vector>

#include "train/score_recording.h"

namespace palpation::app::cli {

struct ReportInfo {
  std::string recording;   // the recording scored (a path), or empty
  std::string trainee;     // empty: not named
  std::string case_name;   // what the trainee was examining
  std::string created;     // when the report was made (ISO 8601)
};

/// Writes into `dir` (created; files replaced as a whole): score.json, report.html and,
/// with Qt, coverage.png, forces.png and report.pdf. Returns the files written. Throws
/// std::runtime_error naming a file that cannot be written (nothing half written stays).
std::vector<std::string> write_exam_report(const train::ScoredExam& exam, const std::string& dir, const ReportInfo& info);

/// The report as HTML (images referenced as coverage.png and forces.png when `images`).
std::string exam_report_html(const train::ScoredExam& exam, const ReportInfo& info, bool images);

/// The coverage map as an image file: the skin seen from above (the chest wall's outward
/// normal), each face coloured by the highest pressure level reached, the tumours' skin
/// points and hit tolerances, and the marks (hits green, false positives red). False
/// without Qt.
bool write_coverage_png(const train::ScoredExam& exam, const std::string& path, int size = 640);

}  // namespace palpation::app::cli
