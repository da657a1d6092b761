#include "cli/plot_png.h"

namespace palpation::app::cli {
void ensure_gui_application() {}
bool can_plot() { return false; }
bool write_plot_png(const std::string&, const PlotSpec&, std::string* why) {
  if (why) *why = "this build has no Qt: no PNG plots";
  return false;
}
}  // namespace palpation::app::cli
