// palpation hertz [--backend B] [--elements E,...] [--nu V,...] [--cells N,...]
// [--preconditioner P]: the Hertz indentation (sim/hertz_probe.h) on a backend, one row
// per element, Poisson's ratio and mesh: the force against Hertz's law, the CG iterations
// of the hardest step and the median step time. With --limit, exit 1 when a row is
// further off than that.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "cli/cli.h"
#include "hertz_probe.h"
#include "store/output_dir.h"

namespace palpation::app::cli {

CommandAction add_hertz_command(CLI::App& app) {
  auto* sub = app.add_subcommand("hertz",
                                 "Hertz indentation of a block: the simulated force against Hertz's law (finite-layer "
                                 "corrected) per element, Poisson's ratio and mesh");
  struct Opts {
    std::string backend = "cpu", precision = "double", preconditioner = "block-jacobi", out;
    std::vector<std::string> elements = sim::element_names();
    std::vector<double> nu{0.45, 0.49, 0.499};
    std::vector<int> cells{28};
    double radius = 0.01, young = 19000, depth = 0.001, cg_tolerance = 1e-8, limit = 0;
  };
  auto o = std::make_shared<Opts>();
  sub->add_option("--backend", o->backend, "cpu, cuda, cuda-csr or cuda-bsr")->capture_default_str();
  sub->add_option("--elements", o->elements, "tissue.element values: linear, nodal-pressure")
      ->delimiter(',')
      ->check(CLI::IsMember(sim::element_names()));
  sub->add_option("--nu", o->nu, "Poisson's ratios")->delimiter(',')->check(CLI::Range(0.0, 0.4999));
  sub->add_option("--cells", o->cells, "Cells across the block (its thickness gets half)")
      ->delimiter(',')
      ->check(CLI::Range(4, 80));
  sub->add_option("--radius", o->radius, "Sphere radius, m")->check(CLI::Range(0.002, 0.03))->capture_default_str();
  sub->add_option("--young", o->young, "Young's modulus, Pa")->check(CLI::Range(100.0, 1e7))->capture_default_str();
  sub->add_option("--depth", o->depth, "Indentation, m")->check(CLI::Range(1e-5, 0.005))->capture_default_str();
  sub->add_option("--precision", o->precision, "double or float")->check(CLI::IsMember({"double", "float"}));
  sub->add_option("--cg-tolerance", o->cg_tolerance, "CG relative tolerance")->check(CLI::Range(1e-14, 1e-2));
  sub->add_option("--limit", o->limit, "Exit 1 when |F / Hertz - 1| exceeds this in any row (0: never)")
      ->check(CLI::Range(0.0, 10.0));
  sub->add_option("--preconditioner", o->preconditioner, "CG preconditioner: block-jacobi, multigrid, multigrid-chebyshev or multigrid-jacobi (multigrid: cpu and cuda backends)")
      ->check(CLI::IsMember(sim::preconditioner_names()))
      ->capture_default_str();
  sub->add_option("--out", o->out, "Folder for hertz.json");
  return [o]() {
    nlohmann::json rows = nlohmann::json::array();
    bool within = true;
    std::printf("%-15s %-7s %6s %7s %8s | %10s %10s %8s | %6s %7s %9s %9s %6s\n", "element", "backend", "nu", "cells", "tets",
                "force N", "Hertz N", "error", "max CG", "all CG", "step ms", "smoother", "share");
    for (const auto& el : o->elements)
      for (double nu : o->nu)
        for (int n : o->cells) {
          sim::HertzCase c;
          c.element = sim::parse_element(el);
          c.nu = nu;
          c.cells = n;
          c.radius = o->radius;
          c.young = o->young;
          c.depth = o->depth;
          c.cg_tolerance = o->cg_tolerance;
          c.preconditioner = sim::parse_preconditioner(o->preconditioner);
          c.precision = o->precision == "float" ? sim::Precision::Float : sim::Precision::Double;
          const sim::HertzResult r = sim::hertz_indent(c, o->backend);
          const bool ok = r.ok && (o->limit <= 0 || std::abs(r.error) <= o->limit);
          within = within && ok;
          if (r.ok)
            std::printf("%-15s %-7s %6.3f %7d %8d | %10.5f %10.5f %+7.1f%% | %6d %7ld %9.3f %9s %6.3f%s\n", el.c_str(),
                        o->backend.c_str(), nu, n, r.tets, r.force, r.reference, 100 * r.error, r.max_iterations,
                        r.total_iterations, r.step_ms, r.smoother.c_str(), r.pressure_share, ok ? "" : "  OFF");
          else
            std::printf("%-15s %-7s %6.3f %7d %8d | FAILED: %s\n", el.c_str(), o->backend.c_str(), nu, n, r.tets, r.why.c_str());
          std::fflush(stdout);
          rows.push_back({{"element", el},
                          {"backend", o->backend},
                          {"precision", o->precision},
                          {"preconditioner", o->preconditioner},
                          {"nu", nu},
                          {"cells", n},
                          {"nodes", r.nodes},
                          {"tets", r.tets},
                          {"radius", o->radius},
                          {"young", o->young},
                          {"ok", r.ok},
                          {"why", r.why},
                          {"force", r.force},
                          {"depth", r.depth},
                          {"hertz", r.reference},
                          {"error", r.error},
                          {"max_cg_iterations", r.max_iterations},
                          {"cg_iterations", r.total_iterations},
                          {"multigrid_smoother", r.smoother},
                          {"multigrid_pressure_share", r.pressure_share},
                          {"step_ms_median", r.step_ms}});
        }
    if (!o->out.empty()) {
      store::OutputDir out(o->out);
      std::ofstream f(out.path("hertz.json"));
      f << nlohmann::json{{"commit", PALPATION_GIT_COMMIT}, {"limit", o->limit}, {"rows", rows}}.dump(2) << "\n";
      if (!f) throw std::runtime_error(out.path("hertz.json") + ": write failed");
      out.commit();
    }
    return within ? kExitOk : kExitFailure;
  };
}

}  // namespace palpation::app::cli
