// Line plots as SVG files, for the accuracy report: no plotting library, nothing to install.
#pragma once

#include <string>
#include <vector>

namespace tessera {

struct PlotPoint {
  double x = 0, y = 0;
  std::string label;  // written beside the point when non-empty
};

struct PlotSeries {
  std::string name;
  std::vector<PlotPoint> points;  // joined in this order
  bool dashed = false;
};

struct Plot {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  std::vector<PlotSeries> series;
};

// Writes the plot; points with a non-positive coordinate on a log axis are left out.
// Throws std::runtime_error when the file cannot be written.
void write_svg_plot(const Plot& plot, const std::string& path);

}  // namespace tessera
