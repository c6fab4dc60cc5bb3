#include "io/world_picture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "io/image_file.h"
#include "io/yaml_strict.h"
#include "vb/engine/error.h"
#include "vb/terrain/grid_planner.h"
#include "vb/terrain/obstacle_shape.h"

namespace vb::io {
namespace {

constexpr int kPixelsPerCell = 3;
constexpr int kLegendHeight = 40;

// BGR colours per class id (clay ... snow).
const std::array<cv::Vec3b, terrain::kNumSurfaceClasses> kClassColour = {{
    {80, 110, 190},   // clay: reddish brown
    {170, 170, 170},  // concrete: grey
    {60, 90, 130},    // dirt: dark brown
    {60, 170, 70},    // grass: green
    {140, 150, 160},  // gravel: grey-beige
    {100, 100, 110},  // rock: dark grey
    {70, 140, 200},   // wood: ochre
    {40, 60, 90},     // mud: very dark brown
    {130, 200, 230},  // sand: pale yellow
    {250, 245, 240},  // snow: white
}};

// Height colour ramp: blue (low) -> green -> brown (high), t in [0, 1].
cv::Vec3b Ramp(double t) {
  const std::array<cv::Vec3d, 4> stops = {{{140, 90, 40}, {90, 160, 80}, {60, 140, 170},
                                           {50, 70, 120}}};
  t = std::min(std::max(t, 0.0), 1.0) * (stops.size() - 1);
  const size_t i = std::min(static_cast<size_t>(t), stops.size() - 2);
  const double f = t - i;
  const cv::Vec3d c = stops[i] * (1.0 - f) + stops[i + 1] * f;
  return cv::Vec3b(static_cast<uint8_t>(c[0]), static_cast<uint8_t>(c[1]),
                   static_cast<uint8_t>(c[2]));
}

// Lambertian hill shade of the height grid, light from the north-west, in [0.35, 1].
double Shade(const terrain::HeightGrid& g, int r, int c, double spacing_m) {
  const int cl = std::max(c - 1, 0), cr = std::min(c + 1, g.cols - 1);
  const int ru = std::max(r - 1, 0), rd = std::min(r + 1, g.rows - 1);
  const double dzdx = (g.At(r, cr) - g.At(r, cl)) / ((cr - cl) * spacing_m);
  const double dzdy = (g.At(ru, c) - g.At(rd, c)) / ((rd - ru) * spacing_m);  // +y is up (north)
  const cv::Vec3d n = cv::normalize(cv::Vec3d(-dzdx, -dzdy, 1.0));
  const cv::Vec3d light = cv::normalize(cv::Vec3d(-1.0, 1.0, 1.5));
  return 0.35 + 0.65 * std::max(0.0, n.dot(light));
}

cv::Point ToPixel(const terrain::TaskSpec& task, const Vec2& p, int offset_x) {
  const double cell_m = task.size_x_m / (task.heights.cols - 1);
  const double col = (p.x() + 0.5 * task.size_x_m) / cell_m;
  const double row = (0.5 * task.size_y_m - p.y()) / cell_m;
  return cv::Point(offset_x + static_cast<int>(std::lround((col + 0.5) * kPixelsPerCell)),
                   static_cast<int>(std::lround((row + 0.5) * kPixelsPerCell)));
}

}  // namespace

void WriteWorldPicture(const terrain::TaskSpec& task, const std::string& path) {
  const terrain::HeightGrid& g = task.heights;
  VB_DEMAND(g.rows >= 2 && g.cols >= 2 && task.patches.rows > 0);
  const int w = g.cols * kPixelsPerCell;
  const int h = g.rows * kPixelsPerCell;
  const int gap = 8;
  cv::Mat img(h + kLegendHeight, 2 * w + gap, CV_8UC3, cv::Scalar(255, 255, 255));
  const double spacing_m = task.size_x_m / (g.cols - 1);
  const auto [lo, hi] = std::minmax_element(g.heights_m.begin(), g.heights_m.end());
  const double span = std::max(*hi - *lo, 1e-9);
  const terrain::OccupancyGrid obstacles = terrain::RasterizeObstacles(task);
  // boxes as their occupied cells (the original's footprint squares); other shapes as their
  // outlines, the projections the occupancy grid is rasterised from (obstacle_shape.h)
  const bool boxes = task.rock_shape.kind == terrain::ObstacleShapeKind::kBox &&
                     task.tree_shape.kind == terrain::ObstacleShapeKind::kBox;

  for (int r = 0; r < g.rows; ++r) {
    for (int c = 0; c < g.cols; ++c) {
      const double shade = Shade(g, r, c, spacing_m);
      cv::Vec3b left = Ramp((g.At(r, c) - *lo) / span);
      const int pr = std::min(r * task.patches.rows / (g.rows - 1), task.patches.rows - 1);
      const int pc = std::min(c * task.patches.cols / (g.cols - 1), task.patches.cols - 1);
      cv::Vec3b right = kClassColour[static_cast<size_t>(task.patches.ClassAt(pr, pc))];
      for (int k = 0; k < 3; ++k) {
        left[k] = static_cast<uint8_t>(left[k] * shade);
        right[k] = static_cast<uint8_t>(right[k] * (0.6 + 0.4 * shade));
      }
      if (boxes && obstacles.Occupied(r, c)) left = right = cv::Vec3b(20, 20, 20);
      cv::rectangle(img, cv::Rect(c * kPixelsPerCell, r * kPixelsPerCell, kPixelsPerCell,
                                  kPixelsPerCell),
                    cv::Scalar(left), cv::FILLED);
      cv::rectangle(img, cv::Rect(w + gap + c * kPixelsPerCell, r * kPixelsPerCell,
                                  kPixelsPerCell, kPixelsPerCell),
                    cv::Scalar(right), cv::FILLED);
    }
  }
  if (!boxes) {
    auto fill = [&](const std::vector<Vec3>& local, const Vec2& at, const cv::Scalar& colour) {
      for (int offset : {0, w + gap}) {
        std::vector<cv::Point> poly;
        for (const Vec2& q : terrain::Outline(local)) {
          poly.push_back(ToPixel(task, at + q, offset));
        }
        cv::fillConvexPoly(img, poly, colour, cv::LINE_AA);
      }
    };
    for (const terrain::RockSpec& rock : task.rocks) {
      fill(terrain::RockShapePoints(task, rock), Vec2(rock.x_m, rock.y_m), cv::Scalar(20, 20, 20));
    }
    const std::vector<Vec3> tree_local = terrain::TreeShapePoints(task);
    for (const terrain::TreeSpec& tree : task.trees) {
      fill(tree_local, Vec2(tree.x_m, tree.y_m), cv::Scalar(30, 60, 100));
    }
  }
  // paths (pairs k and k+5 share a line, so only the first five are drawn) with start/goal dots
  for (size_t k = 0; k < task.pairs.size(); ++k) {
    const terrain::StartGoalPair& pair = task.pairs[k];
    if (k < 5 || task.pairs.size() <= 5) {
      for (size_t i = 1; i < pair.path_m.size(); ++i) {
        cv::line(img, ToPixel(task, pair.path_m[i - 1], 0), ToPixel(task, pair.path_m[i], 0),
                 cv::Scalar(30, 30, 230), 2, cv::LINE_AA);
      }
    }
    cv::circle(img, ToPixel(task, pair.start_m, 0), 5, cv::Scalar(255, 255, 255), cv::FILLED);
    cv::circle(img, ToPixel(task, pair.start_m, 0), 5, cv::Scalar(0, 0, 0), 1);
  }
  // legend: the classes present
  int x = 4;
  for (terrain::SurfaceClass c : terrain::ClassesPresent(task.patches)) {
    cv::rectangle(img, cv::Rect(x, h + 12, 16, 16),
                  cv::Scalar(kClassColour[static_cast<size_t>(c)]), cv::FILLED);
    cv::rectangle(img, cv::Rect(x, h + 12, 16, 16), cv::Scalar(0, 0, 0), 1);
    const std::string name(terrain::SurfaceClassName(c));
    cv::putText(img, name, cv::Point(x + 20, h + 26), cv::FONT_HERSHEY_SIMPLEX, 0.45,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    x += 28 + 9 * static_cast<int>(name.size());
  }
  const std::string title = task.name + ": " +
                            std::string(terrain::ElevationLevelName(task.labels.elevation)) + ", " +
                            std::string(terrain::TerrainTypeName(task.labels.terrain)) + ", " +
                            std::string(terrain::ObstacleDensityName(task.labels.density));
  cv::putText(img, title, cv::Point(w + gap + 4, h + 26), cv::FONT_HERSHEY_SIMPLEX, 0.5,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);

  VB_DEMAND(img.depth() == CV_8U);
  WriteFileAtomic(path, EncodePng8(img.ptr(), img.rows, img.cols, img.channels(), img.step,
                                   /*bgr=*/true));
}

}  // namespace vb::io
