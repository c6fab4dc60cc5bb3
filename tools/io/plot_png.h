// Small PNG charts for reports and docs (line plots and grouped bar charts), drawn with OpenCV so
// vb needs no plotting stack. Output is deterministic (same data -> same bytes) and written
// atomically. Axes get "nice" ticks (1, 2, 5 x 10^k); series colours follow a fixed palette.
#pragma once

#include <string>
#include <vector>

namespace vb::io {

struct PlotSeries {
  std::string label;
  std::vector<double> x;
  std::vector<double> y;
  bool markers = true;   // draw a dot at every point
};

struct LinePlot {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<PlotSeries> series;
  int width_px = 800;
  int height_px = 500;
};

// Grouped bars: groups along x (e.g. elevation levels), one bar per series (e.g. system) in each.
struct BarChart {
  std::string title;
  std::string y_label;
  std::vector<std::string> series_labels;
  std::vector<std::string> group_labels;
  std::vector<std::vector<double>> values;   // [group][series]; NaN = no bar
  std::vector<std::vector<double>> errors;   // optional, same shape: +-error bar half-height
  double y_min = 0.0;
  double y_max = 0.0;                        // 0 = automatic
  int width_px = 800;
  int height_px = 500;
};

// Throw std::runtime_error naming `path` when the data is unusable (no series, x/y size
// mismatch, values/groups mismatch) or the file cannot be written.
void WriteLinePlot(const LinePlot& plot, const std::string& path);
void WriteBarChart(const BarChart& chart, const std::string& path);

}  // namespace vb::io
