#include "io/plot_png.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace vb::io {
namespace {

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Width and height from the PNG IHDR chunk (big-endian at bytes 16..23).
void PngSize(const std::string& png, int* w, int* h) {
  auto be32 = [&](size_t o) {
    return (static_cast<unsigned char>(png[o]) << 24) | (static_cast<unsigned char>(png[o + 1]) << 16) |
           (static_cast<unsigned char>(png[o + 2]) << 8) | static_cast<unsigned char>(png[o + 3]);
  };
  *w = static_cast<int>(be32(16));
  *h = static_cast<int>(be32(20));
}

std::string TempPath(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "vb_plot_png_test";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

LinePlot SlipCurve() {
  LinePlot p;
  p.title = "drawbar pull vs slip";
  p.x_label = "slip [-]";
  p.y_label = "DP / W [-]";
  p.width_px = 640;
  p.height_px = 400;
  PlotSeries s{"sand", {}, {}};
  for (int i = 0; i <= 10; ++i) {
    s.x.push_back(0.1 * i);
    s.y.push_back(0.5 * (1.0 - std::exp(-5.0 * 0.1 * i)));
  }
  p.series.push_back(s);
  return p;
}

TEST(PlotPng, LinePlotIsAPngOfTheRequestedSizeAndDeterministic) {
  const std::string a = TempPath("a.png"), b = TempPath("b.png");
  WriteLinePlot(SlipCurve(), a);
  WriteLinePlot(SlipCurve(), b);
  const std::string png = ReadBytes(a);
  ASSERT_GT(png.size(), 24u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  int w = 0, h = 0;
  PngSize(png, &w, &h);
  EXPECT_EQ(w, 640);
  EXPECT_EQ(h, 400);
  EXPECT_EQ(png, ReadBytes(b));
}

TEST(PlotPng, BarChartWithErrorBars) {
  BarChart c;
  c.title = "success rate by elevation";
  c.y_label = "success [%]";
  c.series_labels = {"pid", "mppi"};
  c.group_labels = {"low", "mid", "high"};
  c.values = {{90, 80}, {70, std::nan("")}, {40, 30}};
  c.errors = {{5, 5}, {5, 0}, {10, 10}};
  const std::string path = TempPath("bars.png");
  WriteBarChart(c, path);
  int w = 0, h = 0;
  PngSize(ReadBytes(path), &w, &h);
  EXPECT_EQ(w, 800);
  EXPECT_EQ(h, 500);
}

TEST(PlotPng, MismatchedDataIsRejectedWithThePath) {
  LinePlot p = SlipCurve();
  p.series[0].y.pop_back();
  try {
    WriteLinePlot(p, TempPath("bad.png"));
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.png"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("'sand'"), std::string::npos);
  }
  BarChart c;
  c.series_labels = {"pid"};
  c.group_labels = {"low", "mid"};
  c.values = {{1.0}};
  EXPECT_THROW(WriteBarChart(c, TempPath("bad_bars.png")), std::runtime_error);
  EXPECT_THROW(WriteLinePlot(LinePlot{}, TempPath("empty.png")), std::runtime_error);
}

}  // namespace
}  // namespace vb::io
