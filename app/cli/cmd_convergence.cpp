// palpation convergence SCENARIO [--levels L,...] [--out DIR]: what resolution a case
// needs (sim/convergence.h). A table on stdout; with --out, DIR/convergence.json,
// convergence.csv and convergence.png (where the build has Qt).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli/cli.h"
#include "cli/plot_png.h"
#include "convergence.h"
#include "store/output_dir.h"

namespace palpation::app::cli {

namespace {

using nlohmann::json;

json nan_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json to_json(const sim::Extrapolation& x) {
  json j = {{"ok", x.ok}, {"limit", nan_null(x.limit)}, {"order", nan_null(x.order)}};
  if (!x.ok) j["why"] = x.why;
  return j;
}

json to_json(const sim::ConvergenceStudy& st) {
  json levels = json::array();
  for (const auto& lv : st.levels) {
    json tumours = json::array();
    for (const auto& t : lv.tumours)
      tumours.push_back({{"elements", t.elements}, {"volume_ratio", t.volume_ratio}, {"mean_edge", t.mean_edge},
                         {"across", t.across}, {"resolved", t.resolved}});
    levels.push_back({{"level", lv.name}, {"edge", lv.edge}, {"nodes", lv.nodes}, {"tets", lv.tets},
                      {"force", lv.force}, {"force_no_tumour", lv.force_plain}, {"contrast", nan_null(lv.contrast)},
                      {"finite", lv.finite}, {"seconds", lv.seconds}, {"tumours", tumours}});
  }
  return {{"scenario", st.scenario},
          {"site", {st.site.skin.x(), st.site.skin.y(), st.site.skin.z()}},
          {"depth", st.depth},
          {"has_tumour", st.has_tumour},
          {"levels", levels},
          {"force_limit", to_json(st.force)},
          {"contrast_limit", st.has_tumour ? to_json(st.contrast) : json(nullptr)},
          {"recommended", st.recommended.empty() ? json(nullptr) : json(st.recommended)},
          {"criteria",
           {{"force_within", sim::kForceTolerance},
            {"contrast_excess_within", sim::kContrastTolerance},
            {"tumour_min_elements_across", sim::kMinAcross},
            {"tumour_volume_within", sim::kVolumeTolerance}}}};
}

std::string percent_off(double v, const sim::Extrapolation& x) {
  if (!x.ok || !std::isfinite(v) || x.limit == 0) return "     -";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%+5.1f%%", 100.0 * (v - x.limit) / std::fabs(x.limit));
  return buf;
}

std::string table(const sim::ConvergenceStudy& st) {
  std::ostringstream o;
  char line[256];
  std::snprintf(line, sizeof line, "%s: press %.1f mm deep at (%.4f, %.4f) m, fingertip %s\n", st.scenario.c_str(),
                st.depth * 1e3, st.site.skin.x(), st.site.skin.y(), st.has_tumour ? "over the tumour" : "(no tumour)");
  o << line;
  o << "level      edge mm   nodes    tets   force N  vs limit  no-tumour N  contrast  tumour: elems across vol    s\n";
  for (const auto& lv : st.levels) {
    std::snprintf(line, sizeof line, "%-9s %7.2f %7d %7d %9.4f   %s  %11.4f  %8.4f", lv.name.c_str(), lv.edge * 1e3,
                  lv.nodes, lv.tets, lv.force, percent_off(lv.force, st.force).c_str(), lv.force_plain, lv.contrast);
    o << line;
    if (!lv.tumours.empty()) {
      const auto& t = lv.tumours.front();
      std::snprintf(line, sizeof line, "  %6d %6.1f %4.2f%s", t.elements, t.across, t.volume_ratio, t.resolved ? "" : " (coarse)");
      o << line;
    } else {
      o << "       -      -    -";
    }
    std::snprintf(line, sizeof line, " %6.1f%s\n", lv.seconds, lv.finite ? "" : "  NOT FINITE");
    o << line;
  }
  auto limit_line = [&](const char* what, const sim::Extrapolation& x) {
    if (x.ok)
      std::snprintf(line, sizeof line, "%s limit %.4f (order %.2f, Richardson on the three finest levels)\n", what, x.limit, x.order);
    else
      std::snprintf(line, sizeof line, "%s limit: none (%s)\n", what, x.why.c_str());
    o << line;
  };
  limit_line("force", st.force);
  if (st.has_tumour) limit_line("contrast", st.contrast);
  o << "recommended level: " << (st.recommended.empty() ? std::string("none of these (refine further)") : st.recommended)
    << "\n";
  return o.str();
}

void write_plot(const std::string& path, const sim::ConvergenceStudy& st) {
  PlotSpec plot;
  plot.title = "Mesh convergence of the fingertip force (" + st.scenario + ")";
  plot.xlabel = "target edge length [mm]";
  plot.ylabel = "force [N]";
  plot.ylabel_right = "tumour / no-tumour contrast";
  PlotSeries f{"force over the tumour", {}, {}, false, false, true};
  PlotSeries p{"force without the tumour", {}, {}, true, false, true};
  PlotSeries c{"contrast", {}, {}, false, true, true};
  for (const auto& lv : st.levels) {
    f.x.push_back(lv.edge * 1e3);
    f.y.push_back(lv.force);
    p.x.push_back(lv.edge * 1e3);
    p.y.push_back(lv.force_plain);
    if (std::isfinite(lv.contrast)) {
      c.x.push_back(lv.edge * 1e3);
      c.y.push_back(lv.contrast);
    }
  }
  plot.series.push_back(std::move(f));
  if (st.has_tumour) {
    plot.series.push_back(std::move(p));
    plot.series.push_back(std::move(c));
  }
  // The extrapolated limit, drawn from h = 0 (where it lies) to the coarsest level.
  if (st.force.ok)
    plot.series.push_back({"force limit (Richardson)", {0.0, st.levels.front().edge * 1e3}, {st.force.limit, st.force.limit}, true, false, false});
  std::string why;
  if (!write_plot_png(path, plot, &why)) throw std::runtime_error(why);
}

}  // namespace

CommandAction add_convergence_command(CLI::App& app) {
  auto* sub = app.add_subcommand("convergence",
                                 "Mesh convergence of a case: the press over its tumour at each resolution, with and "
                                 "without the tumour, and the extrapolated limit");
  struct Opts {
    std::string scenario, out, levels = "coarse,paper,fine,xfine";
    double radius = 0.008, depth_fraction = 0.3, skin_edge = 0, skin = -1;
    bool quiet = false;
  };
  auto o = std::make_shared<Opts>();
  sub->add_option("scenario", o->scenario, "Scenario JSON file, a built-in scenario or a built-in patient's name")->required();
  sub->add_option("--levels", o->levels, "Comma-separated resolutions (coarse, paper, fine, xfine) or edge lengths in m")
      ->capture_default_str();
  sub->add_option("--radius", o->radius, "Fingertip radius, m")->check(CLI::Range(0.002, 0.02));
  sub->add_option("--depth-fraction", o->depth_fraction, "Press depth as a fraction of the tissue under the site")
      ->check(CLI::Range(0.02, 0.6));
  sub->add_option("--skin-edge", o->skin_edge, "Breast: edge length at the skin, m (patient.skin_edge) on every level")
      ->check(CLI::Range(sim::kMinEdge, sim::kMaxEdge));
  sub->add_option("--skin", o->skin,
                  "Skin membrane thickness, m (tissue.skin.thickness; 0: no skin); its modulus is the scenario's or 56 kPa")
      ->check(CLI::Range(0.0, sim::kMaxSkinThickness));
  sub->add_option("--out", o->out, "Folder for convergence.json, convergence.csv and convergence.png");
  sub->add_flag("--quiet", o->quiet, "No progress on stderr");
  return [o]() {
    sim::Scenario s = load_scenario_arg(o->scenario);
    if (o->skin_edge > 0) {
      if (s.patient.phantom != "breast") throw sim::ScenarioError("--skin-edge: only the breast phantom takes a skin edge");
      s.patient.skin_edge = o->skin_edge;
    }
    if (o->skin >= 0) s.skin.thickness = o->skin;
    sim::ConvergenceOptions opt;
    opt.levels.clear();
    std::stringstream ss(o->levels);
    for (std::string l; std::getline(ss, l, ',');) opt.levels.push_back(l);
    opt.radius = o->radius;
    opt.depth_fraction = o->depth_fraction;
    if (!o->quiet) opt.log = [](const std::string& m) { std::fprintf(stderr, "%s\n", m.c_str()); };
    std::unique_ptr<store::OutputDir> out;
    if (!o->out.empty()) out = std::make_unique<store::OutputDir>(o->out);  // an unwritable folder fails early
    const sim::ConvergenceStudy st = sim::convergence_study(s, opt);
    std::fputs(table(st).c_str(), stdout);
    if (out) {
      auto write = [&](const std::string& name, const std::string& text) {
        std::ofstream f(out->path(name));
        f << text;
        if (!f) throw std::runtime_error(out->path(name) + ": write failed");
      };
      write("convergence.json", to_json(st).dump(2) + "\n");
      std::ostringstream csv;
      csv << "level,edge_m,nodes,tets,force_n,force_no_tumour_n,contrast,tumour_elements,tumour_across,tumour_volume_ratio,"
             "seconds\n";
      for (const auto& lv : st.levels) {
        csv << lv.name << ',' << lv.edge << ',' << lv.nodes << ',' << lv.tets << ',' << lv.force << ',' << lv.force_plain << ','
            << (std::isfinite(lv.contrast) ? std::to_string(lv.contrast) : std::string()) << ',';
        if (!lv.tumours.empty())
          csv << lv.tumours[0].elements << ',' << lv.tumours[0].across << ',' << lv.tumours[0].volume_ratio;
        else
          csv << ",,";
        csv << ',' << lv.seconds << '\n';
      }
      write("convergence.csv", csv.str());
      if (can_plot()) write_plot(out->path("convergence.png"), st);
      out->commit();
    }
    bool finite = true;
    for (const auto& lv : st.levels) finite = finite && lv.finite;
    return finite ? kExitOk : kExitFailure;
  };
}

}  // namespace palpation::app::cli
