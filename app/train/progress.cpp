#include "train/progress.h"

namespace palpation::app::train {

ProgressSeries progress_series(const std::vector<store::ExamResult>& results) {
  ProgressSeries s;
  auto add = [](ProgressSeries::Series& series, int session, double v) {
    series.session.push_back(session);
    series.value.push_back(v);
  };
  for (const auto& r : results) {
    const int n = ++s.sessions;
    if (r.sensitivity) add(s.sensitivity, n, *r.sensitivity);
    add(s.false_positives, n, r.false_positives);
    add(s.coverage[0], n, r.coverage_light);
    add(s.coverage[1], n, r.coverage_medium);
    add(s.coverage[2], n, r.coverage_deep);
    add(s.exam_time, n, r.exam_time);
    if (r.deep_reached) add(s.deep_reached, n, *r.deep_reached);
  }
  return s;
}

std::string result_date(const store::ExamResult& r) { return r.started.substr(0, r.started.find('T')); }

}  // namespace palpation::app::train
