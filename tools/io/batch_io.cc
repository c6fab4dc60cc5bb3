// Batch files. Trial JSON is read with yaml-cpp (JSON as written by result_io is valid YAML 1.2
// flow); every missing or mistyped field is an InputError naming the file and key.
#include "io/batch_io.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "io/image_file.h"
#include "io/plot_png.h"
#include "io/yaml_strict.h"
#include "vb/engine/error.h"
#include "vb/engine/runner/outcome_rules.h"
#include "vb/terrain/obstacle_shape.h"
#include "vb/terrain/surface_class.h"

namespace vb::io {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

YAML::Node Need(const YAML::Node& parent, const std::string& key, const std::string& path) {
  // operator[] on a scalar or list throws YAML::BadSubscript, which is not an InputError (found by
  // fuzzing, fuzz/corpus/*/fuzz_*_not_an_object*): say what is wrong instead.
  if (!parent.IsMap()) {
    throw InputError(path, parent.Mark().line + 1, key, "expected a JSON object holding it");
  }
  const YAML::Node n = parent[key];
  if (!n.IsDefined()) throw InputError(path, 0, key, "missing in trial record");
  return n;
}

template <typename T>
T As(const YAML::Node& parent, const std::string& key, const std::string& path) {
  const YAML::Node n = Need(parent, key, path);
  try {
    return n.as<T>();
  } catch (const YAML::Exception&) {
    throw InputError(path, n.Mark().line + 1, key, "wrong type in trial record");
  }
}

double NumOrNaN(const YAML::Node& parent, const std::string& key, const std::string& path) {
  const YAML::Node n = Need(parent, key, path);
  if (n.IsNull()) return kNaN;
  return As<double>(parent, key, path);
}

}  // namespace

batch::TrialRow ReadTrialJson(const std::string& path) {
  YAML::Node root;
  // A directory, FIFO or /dev/zero would block or be read forever.
  const std::string problem = InputFileProblem(path, kMaxYamlFileBytes);
  if (!problem.empty()) throw InputError(path, 0, "", problem);
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw InputError(path, 0, "", "cannot read trial record");
  } catch (const YAML::Exception& e) {
    throw InputError(path, e.mark.line + 1, "", "malformed trial record: " + e.msg);
  }
  if (!root.IsMap()) throw InputError(path, 0, "", "trial record is not a JSON object");
  batch::TrialRow r;
  r.task = As<std::string>(root, "task", path);
  r.pair = As<int>(root, "pair", path);
  r.seed = As<uint64_t>(root, "seed", path);
  r.vehicle = As<std::string>(root, "vehicle", path);
  r.system = As<std::string>(root, "system", path);
  r.perception = root["perception"] ? As<std::string>(root, "perception", path) : "none";
  r.rules = root["rules"] ? As<std::string>(root, "rules", path) : "vb";
  runner::ParseRuleSet("rules", r.rules, path);
  r.status = As<std::string>(root, "status", path);
  if (!batch::IsKnownStatus(r.status)) {
    throw InputError(path, 0, "status", "unknown status '" + r.status + "'");
  }
  r.message = As<std::string>(root, "message", path);
  r.traversal_time_s = NumOrNaN(root, "traversal_time_s", path);
  r.sim_time_s = NumOrNaN(root, "sim_time_s", path);
  r.final_goal_distance_m = NumOrNaN(root, "final_goal_distance_m", path);
  const YAML::Node roll = Need(root, "abs_roll_deg", path);
  const YAML::Node pitch = Need(root, "abs_pitch_deg", path);
  r.mean_abs_roll_deg = roll.IsNull() ? kNaN : NumOrNaN(roll, "mean", path);
  r.mean_abs_pitch_deg = pitch.IsNull() ? kNaN : NumOrNaN(pitch, "mean", path);
  r.wall_time_s = NumOrNaN(root, "wall_time_s", path);
  const YAML::Node samples = root["trajectory_samples"];
  if (samples.IsDefined() && !samples.IsNull()) {
    r.trajectory_samples = As<long>(root, "trajectory_samples", path);
    if (r.trajectory_samples < 0) {
      throw InputError(path, 0, "trajectory_samples", "negative in trial record");
    }
  }
  const YAML::Node prov = Need(root, "provenance", path);
  r.vb_version = As<std::string>(prov, "vb_version", path);
  r.git_commit = As<std::string>(prov, "git_commit", path);
  r.task_file = As<std::string>(prov, "task_file", path);
  r.task_fnv1a64 = As<std::string>(prov, "task_fnv1a64", path);
  r.host = As<std::string>(prov, "host", path);
  return r;
}

std::string TrajectoryProblem(const std::string& traj_path, const batch::TrialRow& record) {
  if (record.trajectory_samples < 0) return "";   // error/crashed: no trajectory expected
  std::ifstream in(traj_path, std::ios::binary);
  if (!in) return "trajectory " + traj_path + " is missing";
  // Rows are lines (no field of a trajectory holds a newline): count them in chunks.
  long lines = 0;
  char last = '\n';
  std::vector<char> buf(1 << 16);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    const std::streamsize n = in.gcount();
    lines += std::count(buf.data(), buf.data() + n, '\n');
    if (n > 0) last = buf[static_cast<size_t>(n) - 1];
  }
  const long rows = lines - 1;   // the header
  if (last != '\n' || rows != record.trajectory_samples) {
    return "trajectory " + traj_path + " has " + std::to_string(std::max(rows, 0L)) +
           (last != '\n' ? " rows and a cut-off last line" : " rows") + ", its record says " +
           std::to_string(record.trajectory_samples);
  }
  return "";
}

std::string RecordKeyProblem(const batch::TrialRow& record, const std::string& task, int pair,
                             uint64_t seed, const std::string& vehicle,
                             const std::string& system, const std::string& perception) {
  batch::TrialRow expected;
  expected.task = task;
  expected.pair = pair;
  expected.seed = seed;
  expected.vehicle = vehicle;
  expected.system = system;
  expected.perception = perception;
  if (batch::RowStem(record) == batch::RowStem(expected)) return "";
  return "the record is of trial " + batch::RowStem(record) + ", not of " +
         batch::RowStem(expected);
}

void WriteUnrunTrialJson(const std::string& path, const std::string& task_name, int pair,
                         const Provenance& p, const std::string& status,
                         const std::string& message) {
  std::string t = "{\n";
  t += "  \"task\": " + JsonString(task_name) + ",\n";
  t += "  \"pair\": " + std::to_string(pair) + ",\n";
  t += "  \"seed\": " + std::to_string(p.seed) + ",\n";
  t += "  \"vehicle\": " + JsonString(p.vehicle) + ",\n";
  t += "  \"system\": " + JsonString(p.system) + ",\n";
  if (p.perception != "none") t += "  \"perception\": " + JsonString(p.perception) + ",\n";
  if (p.rules != "vb") t += "  \"rules\": " + JsonString(p.rules) + ",\n";
  t += "  \"status\": " + JsonString(status) + ",\n";
  t += "  \"failure_type\": " + JsonString(status) + ",\n";
  t += "  \"message\": " + JsonString(message) + ",\n";
  for (const char* k : {"traversal_time_s", "sim_time_s", "final_goal_distance_m",
                        "path_length_m", "obstacle_contacts", "roll_deg", "pitch_deg",
                        "abs_roll_deg", "abs_pitch_deg", "throttle", "steering", "abs_steering",
                        "trajectory_samples", "wall_time_s", "real_time_factor"}) {
    t += std::string("  \"") + k + "\": null,\n";
  }
  t += "  \"provenance\": {\n";
  t += "    \"vb_version\": " + JsonString(p.vb_version) + ",\n";
  t += "    \"git_commit\": " + JsonString(p.git_commit) + ",\n";
  t += "    \"task_file\": " + JsonString(p.task_file) + ",\n";
  t += "    \"task_fnv1a64\": " + JsonString(p.task_fnv1a64) + ",\n";
  t += "    \"vehicle\": " + JsonString(p.vehicle) + ",\n";
  t += "    \"system\": " + JsonString(p.system) + ",\n";
  t += "    \"seed\": " + std::to_string(p.seed) + ",\n";
  t += "    \"host\": " + JsonString(p.host) + "\n";
  t += "  }\n}\n";
  WriteFileAtomic(path, t);
}

void WriteBatchJson(const BatchInfo& b, const std::string& path) {
  std::string t = "{\n";
  t += "  \"matrix_fingerprint\": " + JsonString(b.matrix_fingerprint) + ",\n";
  t += "  \"matrix_trials\": " + std::to_string(b.matrix_trials) + ",\n";
  t += "  \"shard\": " + JsonString(b.shard) + ",\n";
  t += "  \"shard_trials\": " + std::to_string(b.shard_trials) + ",\n";
  t += "  \"settings\": " + JsonString(b.settings) + ",\n";
  t += "  \"vb_version\": " + JsonString(b.vb_version) + ",\n";
  t += "  \"git_commit\": " + JsonString(b.git_commit) + "\n}\n";
  WriteFileAtomic(path, t);
}

BatchInfo ReadBatchJson(const std::string& path) {
  YAML::Node root;
  // A directory, FIFO or /dev/zero would block or be read forever.
  const std::string problem = InputFileProblem(path, kMaxYamlFileBytes);
  if (!problem.empty()) throw InputError(path, 0, "", problem);
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw InputError(path, 0, "", "cannot read (not a vb_batch output directory?)");
  } catch (const YAML::Exception& e) {
    throw InputError(path, e.mark.line + 1, "", "malformed: " + e.msg);
  }
  BatchInfo b;
  b.matrix_fingerprint = As<std::string>(root, "matrix_fingerprint", path);
  b.matrix_trials = As<size_t>(root, "matrix_trials", path);
  b.shard = As<std::string>(root, "shard", path);
  b.shard_trials = As<size_t>(root, "shard_trials", path);
  b.settings = As<std::string>(root, "settings", path);
  b.vb_version = As<std::string>(root, "vb_version", path);
  b.git_commit = As<std::string>(root, "git_commit", path);
  return b;
}

std::vector<std::string> WriteReportPlots(const batch::Report& report, const std::string& dir) {
  std::vector<std::string> written;
  {
    BarChart c;
    c.title = "Table I: outcomes per system";
    c.y_label = "% of trials that ran";
    c.series_labels = {"success", "rollover", "stuck", "timeout", "sim_error", "out_of_bounds"};
    for (const batch::Table1Row& r : report.table1) {
      c.group_labels.push_back(r.system);
      c.values.push_back({r.stats.success_pct, r.stats.rollover_pct, r.stats.stuck_pct,
                          r.stats.timeout_pct, r.stats.sim_error_pct,
                          r.stats.out_of_bounds_pct});
    }
    c.y_max = 100.0;
    if (!c.group_labels.empty()) {
      WriteBarChart(c, dir + "/table1.png");
      written.push_back("table1.png");
    }
  }
  if (!report.robustness.empty()) {
    // Success vs perception preset, one bar per system (the presets are ordered by severity).
    BarChart c;
    c.title = "Robustness: success rate per perception preset";
    c.y_label = "success % of trials that ran";
    c.series_labels = report.robustness_systems;
    c.group_labels = report.perceptions;
    c.values.assign(report.perceptions.size(),
                    std::vector<double>(report.robustness_systems.size(), kNaN));
    for (const batch::RobustnessRow& r : report.robustness) {
      const size_t g = static_cast<size_t>(
          std::find(report.perceptions.begin(), report.perceptions.end(), r.perception) -
          report.perceptions.begin());
      const size_t s = static_cast<size_t>(std::find(report.robustness_systems.begin(),
                                                     report.robustness_systems.end(), r.system) -
                                           report.robustness_systems.begin());
      c.values[g][s] = r.stats.success_pct;
    }
    c.y_max = 100.0;
    WriteBarChart(c, dir + "/robustness.png");
    written.push_back("robustness.png");
  }
  struct Metric {
    const char* name;
    const char* title;
    const char* y_label;
    double batch::GroupStats::*mean;
    double batch::GroupStats::*var;   // nullptr: no error bars
  };
  const Metric metrics[] = {
      {"success", "success rate", "success %", &batch::GroupStats::success_pct, nullptr},
      {"traversal_time", "traversal time (successful trials)", "s (mean, +-1 sd)",
       &batch::GroupStats::traversal_mean_s, &batch::GroupStats::traversal_var_s2},
      {"roll", "mean |roll| (successful trials)", "deg (mean, +-1 sd)",
       &batch::GroupStats::roll_mean_deg, &batch::GroupStats::roll_var_deg2},
      {"pitch", "mean |pitch| (successful trials)", "deg (mean, +-1 sd)",
       &batch::GroupStats::pitch_mean_deg, &batch::GroupStats::pitch_var_deg2}};
  for (const std::string& factor : batch::FactorNames()) {
    std::vector<std::string> levels;
    for (const batch::FactorRow& r : report.factors) {
      if (r.factor == factor && (levels.empty() || levels.back() != r.level)) {
        levels.push_back(r.level);
      }
    }
    if (levels.empty() || report.systems.empty()) continue;
    for (const Metric& m : metrics) {
      BarChart c;
      c.title = std::string(m.title) + " by " + factor;
      c.y_label = m.y_label;
      c.series_labels = report.systems;
      c.group_labels = levels;
      c.values.assign(levels.size(), std::vector<double>(report.systems.size(), kNaN));
      if (m.var != nullptr) c.errors = c.values;
      for (const batch::FactorRow& r : report.factors) {
        if (r.factor != factor) continue;
        const size_t g = static_cast<size_t>(
            std::find(levels.begin(), levels.end(), r.level) - levels.begin());
        const size_t s = static_cast<size_t>(
            std::find(report.systems.begin(), report.systems.end(), r.system) -
            report.systems.begin());
        c.values[g][s] = r.stats.*m.mean;
        if (m.var != nullptr) c.errors[g][s] = std::sqrt(r.stats.*m.var);
      }
      if (m.var == nullptr) c.y_max = 100.0;
      const std::string name = "fig6_" + factor + "_" + m.name + ".png";
      WriteBarChart(c, dir + "/" + name);
      written.push_back(name);
    }
  }
  return written;
}

namespace {

// BGR tint per surface class (index = SurfaceClass id).
cv::Vec3b ClassColour(int id) {
  static const cv::Vec3b kColours[] = {
      {60, 110, 170},  {180, 180, 180}, {60, 90, 120},  {70, 160, 70},  {150, 150, 130},
      {110, 110, 110}, {40, 90, 140},   {30, 60, 90},   {120, 200, 230}, {250, 250, 250}};
  return kColours[(id >= 0 && id < 10) ? id : 1];
}

// x, y columns of a trajectory CSV (missing or unreadable file: empty).
std::vector<cv::Point2d> ReadTrajectoryXY(const std::string& path) {
  std::vector<cv::Point2d> pts;
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) return pts;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string t, x, y;
    if (std::getline(ls, t, ',') && std::getline(ls, x, ',') && std::getline(ls, y, ',')) {
      pts.emplace_back(std::strtod(x.c_str(), nullptr), std::strtod(y.c_str(), nullptr));
    }
  }
  return pts;
}

}  // namespace

void WriteTopDownPng(const terrain::TaskSpec& task, int pair, const std::string& traj_csv,
                     const std::string& caption, double goal_radius_m,
                     const std::string& png_path) {
  const int map_px = 640, band_px = 36;
  cv::Mat img(map_px + band_px, map_px, CV_8UC3, cv::Scalar(255, 255, 255));
  cv::Mat map = img(cv::Rect(0, band_px, map_px, map_px));
  const double sx = task.size_x_m, sy = task.size_y_m;
  auto to_px = [&](double x, double y) {
    return cv::Point(static_cast<int>(std::lround((x + sx / 2) / sx * (map_px - 1))),
                     static_cast<int>(std::lround((sy / 2 - y) / sy * (map_px - 1))));
  };
  // Height shading: grey level from height, tinted by the semantic class of the patch.
  const terrain::HeightGrid& h = task.heights;
  double lo = 0.0, hi = 1.0;
  if (!h.heights_m.empty()) {
    lo = *std::min_element(h.heights_m.begin(), h.heights_m.end());
    hi = *std::max_element(h.heights_m.begin(), h.heights_m.end());
  }
  const terrain::PatchGrid& pg = task.patches;
  for (int py = 0; py < map_px; ++py) {
    for (int px = 0; px < map_px; ++px) {
      double g = 0.5;
      if (h.rows > 1 && h.cols > 1) {
        const int r = std::min(h.rows - 1, py * h.rows / map_px);
        const int c = std::min(h.cols - 1, px * h.cols / map_px);
        g = hi > lo ? (h.At(r, c) - lo) / (hi - lo) : 0.5;
      }
      cv::Vec3b tint(180, 180, 180);
      bool deformable = false;
      if (pg.rows > 0 && pg.cols > 0) {
        const terrain::SurfaceClass cls = pg.ClassAt(py * pg.rows / map_px, px * pg.cols / map_px);
        tint = ClassColour(static_cast<int>(cls));
        deformable = terrain::IsDeformable(cls);
      }
      const double shade = 0.45 + 0.55 * g;
      cv::Vec3b& out = map.at<cv::Vec3b>(py, px);
      for (int k = 0; k < 3; ++k) out[k] = static_cast<uint8_t>(std::lround(tint[k] * shade));
      if (deformable && ((px + py) % 12 == 0)) out = cv::Vec3b(20, 20, 20);   // hatching
    }
  }
  const double m_per_px = sx / map_px;
  // the obstacles' outlines: the projections of their shapes (obstacle_shape.h)
  auto fill_outline = [&](const std::vector<Vec3>& local, const Vec2& at, const cv::Scalar& c) {
    std::vector<cv::Point> poly;
    for (const Vec2& q : terrain::Outline(local)) poly.push_back(to_px(at.x() + q.x(), at.y() + q.y()));
    cv::fillConvexPoly(map, poly, c, cv::LINE_AA);
  };
  for (const terrain::RockSpec& rock : task.rocks) {
    fill_outline(terrain::RockShapePoints(task, rock), Vec2(rock.x_m, rock.y_m),
                 cv::Scalar(40, 40, 40));
  }
  const std::vector<Vec3> tree_local = terrain::TreeShapePoints(task);
  for (const terrain::TreeSpec& tree : task.trees) {
    fill_outline(tree_local, Vec2(tree.x_m, tree.y_m), cv::Scalar(0, 90, 0));
    // at least a dot: a 1 m trunk is ~5 px at 128 m
    const int r = std::max(2, static_cast<int>(std::lround(0.5 / m_per_px)));
    cv::circle(map, to_px(tree.x_m, tree.y_m), r, cv::Scalar(0, 90, 0), cv::FILLED);
  }
  if (pair >= 0 && pair < static_cast<int>(task.pairs.size())) {
    const terrain::StartGoalPair& p = task.pairs[static_cast<size_t>(pair)];
    std::vector<cv::Point> path;
    for (const Vec2& q : p.path_m) path.push_back(to_px(q.x(), q.y()));
    if (path.size() > 1) cv::polylines(map, path, false, cv::Scalar(255, 140, 0), 2, cv::LINE_AA);
    std::vector<cv::Point> driven;
    for (const cv::Point2d& q : ReadTrajectoryXY(traj_csv)) driven.push_back(to_px(q.x, q.y));
    if (driven.size() > 1) cv::polylines(map, driven, false, cv::Scalar(0, 0, 230), 2, cv::LINE_AA);
    cv::circle(map, to_px(p.start_m.x(), p.start_m.y()), 6, cv::Scalar(0, 200, 0), cv::FILLED);
    cv::circle(map, to_px(p.goal_m.x(), p.goal_m.y()), 6, cv::Scalar(0, 0, 255), cv::FILLED);
    const int goal_r = static_cast<int>(std::lround(goal_radius_m / m_per_px));
    cv::circle(map, to_px(p.goal_m.x(), p.goal_m.y()), goal_r, cv::Scalar(0, 0, 255), 1,
               cv::LINE_AA);
    if (!driven.empty()) {
      cv::drawMarker(map, driven.back(), cv::Scalar(255, 0, 255), cv::MARKER_TILTED_CROSS, 14, 2);
    }
  }
  cv::putText(img, caption, cv::Point(8, 24), cv::FONT_HERSHEY_SIMPLEX, 0.55,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  VB_DEMAND(img.depth() == CV_8U);
  WriteFileAtomic(png_path, EncodePng8(img.ptr(), img.rows, img.cols, img.channels(), img.step,
                                       /*bgr=*/true));
}

}  // namespace vb::io
