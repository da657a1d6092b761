// Without Qt: no pictures, no PDF (score.json and the HTML are still written).
#include "cli/exam_report.h"

namespace palpation::app::cli {

bool write_coverage_png(const train::ScoredExam&, const std::string&, int) { return false; }
bool write_report_pdf(const std::string&, const std::string&, const std::string&) { return false; }

}  // namespace palpation::app::cli
