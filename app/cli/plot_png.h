// Line plots written to PNG (forces.png, the bench's trade-off plot). Drawn with Qt Gui's
// QPainter on a QImage when the build has Qt; in the Qt-free build plots are skipped.
#pragma once

#include <string>
#include <vector>

namespace palpation::app::cli {

struct PlotSeries {
  std::string name;
  std::vector<double> x, y;
  bool dashed = false;
  bool right_axis = false;  // plotted against the right-hand y axis
  bool markers = false;
};

struct PlotSpec {
  std::string title, xlabel, ylabel, ylabel_right;
  bool log_x = false, log_y = false;
  std::vector<PlotSeries> series;
  int width = 1200, height = 600;
};

/// Qt builds: makes the offscreen QGuiApplication that drawing text needs, when the
/// program has none (the command line). Nothing without Qt.
void ensure_gui_application();
/// True when this build can write PNG plots.
bool can_plot();
/// Writes the plot. Returns false (and sets why) when it cannot.
bool write_plot_png(const std::string& path, const PlotSpec& spec, std::string* why = nullptr);

}  // namespace palpation::app::cli
