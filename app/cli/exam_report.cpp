#include "cli/exam_report.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "cli/plot_png.h"
#include "store/output_dir.h"

namespace palpation::app::cli {

using train::ExamScore;
using train::level_name;

namespace {

std::string pct(double v) { return std::to_string(int(std::lround(100 * v))) + "%"; }
std::string mm(double m) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f mm", m * 1000);
  return b;
}
std::string secs(double s) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f s", s);
  return b;
}
std::string esc(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '<') o += "&lt;";
    else if (c == '>') o += "&gt;";
    else if (c == '&') o += "&amp;";
    else if (c == '"') o += "&quot;";
    else o += c;
  }
  return o;
}

}  // namespace

std::string exam_report_html(const train::ScoredExam& exam, const ReportInfo& info, bool images) {
  const ExamScore& s = exam.score;
  std::string h;
  h += "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>Palpation exam report</title>\n";
  h += "<style>body{font-family:sans-serif;max-width:60em;margin:1em auto}table{border-collapse:collapse}"
       "td,th{border:1px solid #999;padding:3px 8px;text-align:left}.miss{color:#b00}.hit{color:#070}</style></head><body>\n";
  h += "<h1>Palpation exam report</h1>\n<p>";
  if (!info.trainee.empty()) h += "Trainee: <b>" + esc(info.trainee) + "</b><br>";
  if (!info.case_name.empty()) h += "Case: " + esc(info.case_name) + "<br>";
  if (!info.recording.empty()) h += "Recording: " + esc(info.recording) + "<br>";
  if (!info.created.empty()) h += "Scored: " + esc(info.created) + "<br>";
  h += "Exam time: " + secs(s.exam_time) + " (session " + secs(s.duration) + ")</p>\n";
  h += "<h2>Findings</h2>\n<table><tr><th>Tumours found</th><td>" + std::to_string(s.hits) + " of " +
       std::to_string(s.tumours.size()) + "</td></tr>";
  h += "<tr><th>Sensitivity</th><td>" + (s.sensitivity ? pct(*s.sensitivity) : std::string("no tumour in this case")) +
       "</td></tr>";
  h += "<tr><th>False positives</th><td>" + std::to_string(s.false_positives) + "</td></tr>";
  h += "<tr><th>Positive predictive value</th><td>" + (s.ppv ? pct(*s.ppv) : std::string("no marks")) + "</td></tr>";
  if (s.specific) h += std::string("<tr><th>No-tumour case</th><td>") + (*s.specific ? "correctly nothing marked" : "marked a lump that is not there") + "</td></tr>";
  if (s.hits) h += "<tr><th>Mean position error</th><td>" + mm(s.mean_error) + "</td></tr>";
  h += "</table>\n";
  if (!s.tumours.empty()) {
    h += "<h3>Each tumour</h3>\n<table><tr><th>#</th><th>Depth</th><th>Size</th><th>Stiffness</th><th>Found</th><th>Error</th>"
         "<th>Time to find</th><th>Pressure over it</th></tr>\n";
    for (std::size_t i = 0; i < s.tumours.size(); ++i) {
      const auto& r = s.tumours[i];
      char stiff[32];
      std::snprintf(stiff, sizeof stiff, "%.1fx tissue", r.truth.contrast);
      h += "<tr><td>" + std::to_string(i + 1) + "</td><td>" + mm(r.truth.depth) + "</td><td>" + mm(2 * r.truth.lateral_radius) +
           " across</td><td>" + stiff + "</td><td class=\"" + (r.found ? "hit\">yes" : "miss\">missed") + "</td><td>" +
           (r.found ? mm(r.error) : "") + "</td><td>" + (r.found ? secs(r.time_to_find) : "") + "</td><td>" +
           level_name(r.max_level_over) + (r.deep_reached ? "" : " (deep not reached)") + "</td></tr>\n";
    }
    h += "</table>\n";
  }
  h += "<h2>Coverage and pressure</h2>\n<table><tr><th>Touched</th><td>" + pct(s.touched) + "</td></tr><tr><th>Light</th><td>" +
       pct(s.coverage[0]) + "</td></tr><tr><th>Medium</th><td>" + pct(s.coverage[1]) + "</td></tr><tr><th>Deep</th><td>" +
       pct(s.coverage[2]) + "</td></tr></table>\n";
  h += "<p>Search pattern: " + std::to_string(s.pattern.strips) + " vertical strip(s), " + pct(s.pattern.vertical_fraction) +
       " of the pressed path in strips";
  if (s.pattern.strips >= 2) h += ", overlap between neighbouring strips " + pct(s.pattern.mean_overlap);
  h += "; " + std::to_string(s.pattern.skipped.size()) + " skipped region(s) of 1 cm&sup2; or more";
  if (!s.pattern.skipped.empty()) {
    char b[64];
    std::snprintf(b, sizeof b, " (largest %.1f cm&sup2;)", s.pattern.skipped.front().area * 1e4);
    h += b;
  }
  h += ".</p>\n";
  if (images)
    h += "<p><img src=\"coverage.png\" width=\"480\" alt=\"coverage map\"><br><small>The skin seen from above: grey untouched, "
         "yellow light, orange medium, red deep; circles: each tumour's hit tolerance on the skin; crosses: marks (green hit, "
         "red false positive).</small></p>\n<p><img src=\"forces.png\" width=\"640\" alt=\"finger forces\"></p>\n";
  h += "<h2>What to practise next</h2>\n<ul>";
  for (const auto& a : s.advice) h += "<li>" + esc(a.text()) + "</li>";
  h += "</ul>\n<p><small>Pressure levels: light from " + pct(s.thresholds.light_depth) + " of the tissue's thickness or " +
       std::to_string(s.thresholds.light_force).substr(0, 4) + " N, medium from " + pct(s.thresholds.medium_depth) + " or " +
       std::to_string(s.thresholds.medium_force).substr(0, 4) + " N, deep from " + pct(s.thresholds.deep_depth) + " or " +
       std::to_string(s.thresholds.deep_force).substr(0, 4) + " N.</small></p>\n</body></html>\n";
  return h;
}

bool write_report_pdf(const std::string& html_path, const std::string& html, const std::string& pdf_path);

std::vector<std::string> write_exam_report(const train::ScoredExam& exam, const std::string& dir, const ReportInfo& info) {
  store::OutputDir out(dir);
  std::vector<std::string> files;
  {
    nlohmann::json j = train::to_json(exam.score);
    j["recording"] = info.recording;
    j["patient"] = exam.patient;
    if (!info.trainee.empty()) j["trainee"] = info.trainee;
    if (!info.case_name.empty()) j["case"] = info.case_name;
    std::ofstream f(out.path("score.json"));
    f << j.dump(2) << "\n";
    if (!f) throw std::runtime_error(out.path("score.json") + ": write failed");
    files.push_back("score.json");
  }
  bool images = write_coverage_png(exam, out.path("coverage.png"));
  if (images) {
    files.push_back("coverage.png");
    PlotSpec p;
    p.title = "Force on each finger";
    p.xlabel = "time (s)";
    p.ylabel = "|force| (N)";
    const char* names[5] = {"thumb", "index", "middle", "ring", "little"};
    for (std::size_t k = 0; k < exam.plot_force.size(); ++k) {
      double peak = 0;
      for (double v : exam.plot_force[k]) peak = std::max(peak, v);
      if (peak <= 0) continue;  // a finger that never touched
      p.series.push_back({exam.plot_force.size() == 5 ? names[k] : "finger " + std::to_string(k), exam.plot_t, exam.plot_force[k]});
    }
    std::string why;
    if (!write_plot_png(out.path("forces.png"), p, &why)) throw std::runtime_error(out.path("forces.png") + ": " + why);
    files.push_back("forces.png");
  }
  const std::string html = exam_report_html(exam, info, images);
  {
    std::ofstream f(out.path("report.html"));
    f << html;
    if (!f) throw std::runtime_error(out.path("report.html") + ": write failed");
    files.push_back("report.html");
  }
  if (write_report_pdf(out.path("report.html"), html, out.path("report.pdf"))) files.push_back("report.pdf");
  out.commit();
  return files;
}

}  // namespace palpation::app::cli
