// A trainee's progress over their exams (docs/training.md, "The workstation's training
// views"): the library's results (store::ExamResult, oldest first) as series over sessions
// for the instructor's plots, and the figures of one result as the progress table shows
// them. Qt-free; the GUI's progress window draws what this builds.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "store/patient_library.h"

namespace palpation::app::train {

/// One series per figure, one point per exam (exam 1, 2, ... in the results' order).
/// A case without tumours has no sensitivity nor deep-over-tumour fraction: those series
/// skip it (their `session` lists which exams they have).
struct ProgressSeries {
  struct Series {
    std::vector<double> session;   // 1-based exam number
    std::vector<double> value;
  };
  Series sensitivity;              // 0..1
  Series false_positives;
  Series coverage[3];              // light, medium, deep: skin fractions 0..1
  Series exam_time;                // s
  Series deep_reached;             // fraction of tumours pressed deep over
  int sessions = 0;
};
ProgressSeries progress_series(const std::vector<store::ExamResult>& results);

/// The date part of a result's start ("2026-11-24" of "2026-11-24T06:12:00Z").
std::string result_date(const store::ExamResult& r);

}  // namespace palpation::app::train
