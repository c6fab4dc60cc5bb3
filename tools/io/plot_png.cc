#include "io/plot_png.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "io/image_file.h"
#include "io/yaml_strict.h"
#include "vb/engine/error.h"

namespace vb::io {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
const cv::Scalar kBlack(0, 0, 0), kGrid(225, 225, 225), kWhite(255, 255, 255);

// Tableau-like palette (BGR); twelve colours, so the eleven systems of a full comparison (the
// paper's ten and the oracle) each get their own.
cv::Scalar Colour(size_t i) {
  static const cv::Scalar kPalette[] = {
      {180, 119, 31}, {14, 127, 255}, {44, 160, 44}, {40, 39, 214}, {189, 103, 148},
      {75, 86, 140},  {194, 119, 227}, {127, 127, 127}, {34, 189, 188}, {207, 190, 23},
      {40, 40, 40},   {138, 223, 152}};
  return kPalette[i % (sizeof(kPalette) / sizeof(kPalette[0]))];
}

struct Axis {
  double lo = 0.0, hi = 1.0, step = 0.2;
};

// Range [lo, hi] widened to multiples of a 1/2/5 x 10^k step giving about 5 intervals.
Axis NiceAxis(double lo, double hi) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) lo = 0.0, hi = 1.0;
  if (hi - lo < 1e-12) {
    const double pad = std::max(std::abs(lo) * 0.1, 1.0);
    lo -= pad;
    hi += pad;
  }
  const double raw = (hi - lo) / 5.0;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10.0 * mag;
  for (double m : {1.0, 2.0, 5.0}) {
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  }
  Axis a;
  a.step = step;
  a.lo = std::floor(lo / step + 1e-9) * step;
  a.hi = std::ceil(hi / step - 1e-9) * step;
  return a;
}

std::string TickText(double v, double step) {
  char buf[32];
  const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  std::snprintf(buf, sizeof(buf), "%.*f", std::min(decimals, 6), std::abs(v) < 1e-12 ? 0.0 : v);
  return buf;
}

void Text(cv::Mat& img, const std::string& s, cv::Point p, double scale, bool centre = false) {
  int baseline = 0;
  const cv::Size sz = cv::getTextSize(s, kFont, scale, 1, &baseline);
  if (centre) p.x -= sz.width / 2;
  cv::putText(img, s, p, kFont, scale, kBlack, 1, cv::LINE_AA);
}

// Frame with title, axis labels, y ticks and grid; returns the plotting rectangle.
cv::Rect DrawFrame(cv::Mat& img, const std::string& title, const std::string& x_label,
                   const std::string& y_label, const Axis& y) {
  const cv::Rect r(80, 45, img.cols - 80 - 170, img.rows - 45 - 70);
  Text(img, title, {img.cols / 2, 28}, 0.6, true);
  Text(img, x_label, {r.x + r.width / 2, img.rows - 18}, 0.5, true);
  // y label, rotated: draw on a strip and rotate it
  int baseline = 0;
  const cv::Size sz = cv::getTextSize(y_label, kFont, 0.5, 1, &baseline);
  cv::Mat strip(sz.height + baseline + 4, sz.width + 4, CV_8UC3, kWhite);
  cv::putText(strip, y_label, {2, sz.height + 1}, kFont, 0.5, kBlack, 1, cv::LINE_AA);
  cv::Mat rotated;
  cv::rotate(strip, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
  const int ry = std::max(0, r.y + r.height / 2 - rotated.rows / 2);
  if (ry + rotated.rows <= img.rows && rotated.cols + 8 <= img.cols)
    rotated.copyTo(img(cv::Rect(8, ry, rotated.cols, rotated.rows)));
  for (double v = y.lo; v <= y.hi + y.step * 1e-6; v += y.step) {
    const int py = r.y + r.height - static_cast<int>(std::lround((v - y.lo) / (y.hi - y.lo) * r.height));
    cv::line(img, {r.x, py}, {r.x + r.width, py}, kGrid, 1);
    const std::string t = TickText(v, y.step);
    const cv::Size ts = cv::getTextSize(t, kFont, 0.4, 1, &baseline);
    Text(img, t, {r.x - 6 - ts.width, py + ts.height / 2}, 0.4);
  }
  return r;
}

void DrawLegend(cv::Mat& img, const cv::Rect& r, const std::vector<std::string>& labels) {
  int py = r.y + 10;
  for (size_t i = 0; i < labels.size(); ++i, py += 20) {
    cv::rectangle(img, {r.x + r.width + 12, py - 8}, {r.x + r.width + 26, py + 4}, Colour(i),
                  cv::FILLED);
    Text(img, labels[i], {r.x + r.width + 32, py + 3}, 0.4);
  }
}

void Save(const cv::Mat& img, const std::string& path) {
  VB_DEMAND(img.depth() == CV_8U);
  WriteFileAtomic(path, EncodePng8(img.ptr(), img.rows, img.cols, img.channels(), img.step,
                                   /*bgr=*/true));
}

}  // namespace

void WriteLinePlot(const LinePlot& plot, const std::string& path) {
  if (plot.series.empty()) throw std::runtime_error(path + ": line plot '" + plot.title + "' has no series");
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  for (const PlotSeries& s : plot.series) {
    if (s.x.size() != s.y.size())
      throw std::runtime_error(path + ": series '" + s.label + "' has " + std::to_string(s.x.size()) +
                               " x values but " + std::to_string(s.y.size()) + " y values");
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      x_lo = std::min(x_lo, s.x[i]);
      x_hi = std::max(x_hi, s.x[i]);
      y_lo = std::min(y_lo, s.y[i]);
      y_hi = std::max(y_hi, s.y[i]);
    }
  }
  cv::Mat img(plot.height_px, plot.width_px, CV_8UC3, kWhite);
  const Axis xa = NiceAxis(x_lo, x_hi), ya = NiceAxis(y_lo, y_hi);
  const cv::Rect r = DrawFrame(img, plot.title, plot.x_label, plot.y_label, ya);
  int baseline = 0;
  for (double v = xa.lo; v <= xa.hi + xa.step * 1e-6; v += xa.step) {
    const int px = r.x + static_cast<int>(std::lround((v - xa.lo) / (xa.hi - xa.lo) * r.width));
    cv::line(img, {px, r.y}, {px, r.y + r.height}, kGrid, 1);
    const std::string t = TickText(v, xa.step);
    const cv::Size ts = cv::getTextSize(t, kFont, 0.4, 1, &baseline);
    Text(img, t, {px - ts.width / 2, r.y + r.height + 18}, 0.4);
  }
  cv::rectangle(img, r, kBlack, 1);
  auto to_px = [&](double x, double y) {
    return cv::Point(r.x + static_cast<int>(std::lround((x - xa.lo) / (xa.hi - xa.lo) * r.width)),
                     r.y + r.height - static_cast<int>(std::lround((y - ya.lo) / (ya.hi - ya.lo) * r.height)));
  };
  std::vector<std::string> labels;
  for (size_t k = 0; k < plot.series.size(); ++k) {
    const PlotSeries& s = plot.series[k];
    labels.push_back(s.label);
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      const cv::Point p = to_px(s.x[i], s.y[i]);
      if (i > 0 && std::isfinite(s.x[i - 1]) && std::isfinite(s.y[i - 1]))
        cv::line(img, to_px(s.x[i - 1], s.y[i - 1]), p, Colour(k), 2, cv::LINE_AA);
      if (s.markers) cv::circle(img, p, 3, Colour(k), cv::FILLED, cv::LINE_AA);
    }
  }
  DrawLegend(img, r, labels);
  Save(img, path);
}

void WriteBarChart(const BarChart& chart, const std::string& path) {
  if (chart.values.size() != chart.group_labels.size())
    throw std::runtime_error(path + ": bar chart '" + chart.title + "' has " +
                             std::to_string(chart.values.size()) + " value rows for " +
                             std::to_string(chart.group_labels.size()) + " groups");
  if (!chart.errors.empty() && chart.errors.size() != chart.values.size())
    throw std::runtime_error(path + ": bar chart '" + chart.title + "': errors do not match values");
  const size_t n_series = chart.series_labels.size();
  if (n_series == 0) throw std::runtime_error(path + ": bar chart '" + chart.title + "' has no series");
  double hi = chart.y_min;
  for (size_t g = 0; g < chart.values.size(); ++g) {
    if (chart.values[g].size() != n_series)
      throw std::runtime_error(path + ": group '" + chart.group_labels[g] + "' has " +
                               std::to_string(chart.values[g].size()) + " values for " +
                               std::to_string(n_series) + " series");
    for (size_t s = 0; s < n_series; ++s) {
      const double e = chart.errors.empty() ? 0.0 : chart.errors[g].at(s);
      if (std::isfinite(chart.values[g][s])) hi = std::max(hi, chart.values[g][s] + (std::isfinite(e) ? e : 0.0));
    }
  }
  const Axis ya = NiceAxis(chart.y_min, chart.y_max > chart.y_min ? chart.y_max : hi);
  cv::Mat img(chart.height_px, chart.width_px, CV_8UC3, kWhite);
  const cv::Rect r = DrawFrame(img, chart.title, "", chart.y_label, ya);
  auto to_py = [&](double y) {
    y = std::clamp(y, ya.lo, ya.hi);
    return r.y + r.height - static_cast<int>(std::lround((y - ya.lo) / (ya.hi - ya.lo) * r.height));
  };
  const size_t n_groups = std::max<size_t>(chart.group_labels.size(), 1);
  const double group_w = static_cast<double>(r.width) / static_cast<double>(n_groups);
  const double bar_w = group_w * 0.8 / static_cast<double>(n_series);
  for (size_t g = 0; g < chart.group_labels.size(); ++g) {
    const double x0 = r.x + g * group_w + group_w * 0.1;
    for (size_t s = 0; s < n_series; ++s) {
      const double v = chart.values[g][s];
      if (!std::isfinite(v)) continue;
      const int bx0 = static_cast<int>(std::lround(x0 + s * bar_w));
      const int bx1 = static_cast<int>(std::lround(x0 + (s + 1) * bar_w)) - 1;
      cv::rectangle(img, {bx0, to_py(v)}, {bx1, to_py(ya.lo)}, Colour(s), cv::FILLED);
      const double e = chart.errors.empty() ? 0.0 : chart.errors[g][s];
      if (std::isfinite(e) && e > 0.0) {
        const int cx = (bx0 + bx1) / 2;
        cv::line(img, {cx, to_py(v - e)}, {cx, to_py(v + e)}, kBlack, 1);
        cv::line(img, {cx - 3, to_py(v + e)}, {cx + 3, to_py(v + e)}, kBlack, 1);
        cv::line(img, {cx - 3, to_py(v - e)}, {cx + 3, to_py(v - e)}, kBlack, 1);
      }
    }
    Text(img, chart.group_labels[g],
         {static_cast<int>(std::lround(r.x + (g + 0.5) * group_w)), r.y + r.height + 18}, 0.45, true);
  }
  cv::rectangle(img, r, kBlack, 1);
  DrawLegend(img, r, chart.series_labels);
  Save(img, path);
}

}  // namespace vb::io
