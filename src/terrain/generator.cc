#include "vb/terrain/generator.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "vb/engine/error.h"
#include "vb/engine/rng.h"
#include "vb/terrain/grid_planner.h"
#include "vb/terrain/obstacle_shape.h"

namespace vb::terrain {
namespace {

// ---------------------------------------------------------------------------------------------
// Layout constants of the original benchmark (reference_verti_bench.md §4.3-§4.6), for the
// 128 m world; other world sizes scale the lengths by world_size / 128.

constexpr double kReferenceWorldM = 128.0;
constexpr int kPatchesPerSide = 16;
constexpr int kNumPairs = 10;
constexpr double kPairRadiusM = 60.0;
constexpr double kObstacleBoundM = 58.0;       // obstacles inside +-58 m
constexpr double kClearanceToPairsM = 12.0;    // > 12 m from all 20 start/goal points
constexpr double kClearanceBetweenM = 10.0;    // > 10 m between obstacles
constexpr int kPlacementAttempts = 500;        // per obstacle, as the original
constexpr int kMaxPlacementRounds = 1000;
constexpr double kClusterCentreMean = 7.5;     // mean and std of the 16x16 patch index grid
constexpr double kClusterCentreStd = 4.6098;

// ---------------------------------------------------------------------------------------------
// Elevation targets: mean |grad h| per level from §9 (0.095 / 0.185 / 0.310 m/m). The field's
// spectrum (below) is shaped so that height std and p95 slope follow from it.

double TargetMeanGradient(ElevationLevel level) {
  switch (level) {
    case ElevationLevel::kLow: return 0.095;
    case ElevationLevel::kMid: return 0.185;
    case ElevationLevel::kHigh: return 0.310;
  }
  return 0.095;
}

// A random field component: white noise blurred by a Gaussian of std sigma_m (in cells at 1 m),
// normalised to unit std and weighted. Most of the original worlds' variance sits below ~9 m
// (their roughness is 0.74 of their height std), hence the short correlation lengths.
struct NoiseComponent {
  double sigma_cells;
  double weight;
};
constexpr std::array<NoiseComponent, 3> kNoise = {{{8.0, 0.05}, {2.5, 0.5}, {1.2, 0.65}}};

// Discrete features on top of the noise, in the same unit-std units: round boulders, narrow pits
// (the original worlds have many isolated deep pixels) and ridges/ditches along segments.
constexpr int kNumBoulders = 24;
constexpr int kNumPits = 110;
constexpr int kNumRidges = 10;

std::vector<double> GaussianKernel(double sigma) {
  const int half = static_cast<int>(std::ceil(3.0 * sigma));
  std::vector<double> k(static_cast<size_t>(2 * half + 1));
  double sum = 0.0;
  for (int i = -half; i <= half; ++i) {
    k[i + half] = std::exp(-0.5 * (i * i) / (sigma * sigma));
    sum += k[i + half];
  }
  for (double& v : k) v /= sum;
  return k;
}

// Adds weight * (unit-std blurred white noise) to field (n x n, row-major).
void AddBlurredNoise(Rng* rng, int n, double sigma, double weight, std::vector<double>* field) {
  const std::vector<double> kernel = GaussianKernel(sigma);
  const int half = static_cast<int>(kernel.size() / 2);
  // noise on a padded grid so the border has the same statistics as the interior
  const int m = n + 2 * half;
  std::vector<double> noise(static_cast<size_t>(m) * m);
  for (double& v : noise) v = rng->Normal();
  // separable blur: rows (m x n result), then columns (n x n)
  std::vector<double> tmp(static_cast<size_t>(m) * n, 0.0);
  for (int r = 0; r < m; ++r) {
    for (int c = 0; c < n; ++c) {
      double s = 0.0;
      for (int k = 0; k < static_cast<int>(kernel.size()); ++k) {
        s += kernel[k] * noise[static_cast<size_t>(r) * m + c + k];
      }
      tmp[static_cast<size_t>(r) * n + c] = s;
    }
  }
  std::vector<double> out(static_cast<size_t>(n) * n, 0.0);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      double s = 0.0;
      for (int k = 0; k < static_cast<int>(kernel.size()); ++k) {
        s += kernel[k] * tmp[static_cast<size_t>(r + k) * n + c];
      }
      out[static_cast<size_t>(r) * n + c] = s;
    }
  }
  // normalise to unit std so the weights mean what they say
  const double mean = std::accumulate(out.begin(), out.end(), 0.0) / out.size();
  double var = 0.0;
  for (double v : out) var += (v - mean) * (v - mean);
  const double scale = weight / std::sqrt(var / out.size());
  for (size_t i = 0; i < out.size(); ++i) (*field)[i] += scale * (out[i] - mean);
}

// Adds amplitude * exp(-d^2 / (2 sigma^2)) where d is the distance to segment (a, b) (a point if
// a == b), over the window where it matters.
void AddSegmentBump(int n, double ar, double ac, double br, double bc, double sigma,
                    double amplitude, std::vector<double>* field) {
  const double reach = 3.5 * sigma;
  const int r0 = std::max(0, static_cast<int>(std::floor(std::min(ar, br) - reach)));
  const int r1 = std::min(n - 1, static_cast<int>(std::ceil(std::max(ar, br) + reach)));
  const int c0 = std::max(0, static_cast<int>(std::floor(std::min(ac, bc) - reach)));
  const int c1 = std::min(n - 1, static_cast<int>(std::ceil(std::max(ac, bc) + reach)));
  const double sr = br - ar;
  const double sc = bc - ac;
  const double len2 = sr * sr + sc * sc;
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      double t = len2 > 0.0 ? ((r - ar) * sr + (c - ac) * sc) / len2 : 0.0;
      t = std::min(std::max(t, 0.0), 1.0);
      const double dr = r - (ar + t * sr);
      const double dc = c - (ac + t * sc);
      (*field)[static_cast<size_t>(r) * n + c] +=
          amplitude * std::exp(-0.5 * (dr * dr + dc * dc) / (sigma * sigma));
    }
  }
}

// Central-difference gradient magnitude (one-sided at the border), as numpy.gradient.
std::vector<double> GradientMagnitude(const HeightGrid& g, double spacing_m) {
  std::vector<double> out(g.heights_m.size());
  for (int r = 0; r < g.rows; ++r) {
    for (int c = 0; c < g.cols; ++c) {
      const int cl = std::max(c - 1, 0);
      const int cr = std::min(c + 1, g.cols - 1);
      const int ru = std::max(r - 1, 0);
      const int rd = std::min(r + 1, g.rows - 1);
      const double gx = (g.At(r, cr) - g.At(r, cl)) / ((cr - cl) * spacing_m);
      const double gy = (g.At(rd, c) - g.At(ru, c)) / ((rd - ru) * spacing_m);
      out[static_cast<size_t>(r) * g.cols + c] = std::sqrt(gx * gx + gy * gy);
    }
  }
  return out;
}

double MeanOf(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

// The height field: noise components and features, scaled to the level's mean gradient (with a
// per-world spread like the original's), shifted so the lowest point is 0, and quantised to the
// 16-bit levels of the height image so the task in memory equals the one read back from disk.
HeightGrid GenerateHeights(Rng* rng, int n, ElevationLevel level) {
  std::vector<double> field(static_cast<size_t>(n) * n, 0.0);
  for (const NoiseComponent& comp : kNoise) {
    AddBlurredNoise(rng, n, comp.sigma_cells, comp.weight, &field);
  }
  for (int i = 0; i < kNumBoulders; ++i) {
    const double r = rng->Uniform(0.0, n - 1.0);
    const double c = rng->Uniform(0.0, n - 1.0);
    AddSegmentBump(n, r, c, r, c, rng->Uniform(1.5, 3.0), rng->Uniform(0.4, 1.0), &field);
  }
  for (int i = 0; i < kNumPits; ++i) {
    const double r = rng->Uniform(0.0, n - 1.0);
    const double c = rng->Uniform(0.0, n - 1.0);
    AddSegmentBump(n, r, c, r, c, rng->Uniform(0.7, 1.3), -rng->Uniform(1.5, 3.5), &field);
  }
  for (int i = 0; i < kNumRidges; ++i) {
    const double r = rng->Uniform(0.0, n - 1.0);
    const double c = rng->Uniform(0.0, n - 1.0);
    const double angle = rng->Uniform(0.0, 2.0 * kPi);
    const double length = rng->Uniform(10.0, 40.0);
    const double sign = rng->Uniform() < 0.5 ? -1.0 : 1.0;
    AddSegmentBump(n, r, c, r + length * std::sin(angle), c + length * std::cos(angle),
                   rng->Uniform(1.0, 2.5), sign * rng->Uniform(0.3, 0.8), &field);
  }

  HeightGrid grid;
  grid.rows = n;
  grid.cols = n;
  grid.heights_m = field;
  const double target = TargetMeanGradient(level) * rng->Uniform(0.9, 1.1);
  const double scale = target / MeanOf(GradientMagnitude(grid, 1.0));
  const double lowest = *std::min_element(field.begin(), field.end());
  for (double& h : grid.heights_m) h = (h - lowest) * scale;
  const double highest = *std::max_element(grid.heights_m.begin(), grid.heights_m.end());
  for (double& h : grid.heights_m) h = std::round(h / highest * 65535.0) / 65535.0 * highest;
  return grid;
}

// ---------------------------------------------------------------------------------------------
// Semantics (§4.3): clusters in patch-index space, each patch takes its nearest centre's class.

// k distinct values of pool, drawn without replacement (partial Fisher-Yates), in draw order.
std::vector<int> SampleWithoutReplacement(Rng* rng, std::vector<int> pool, int k) {
  const int last = static_cast<int>(pool.size()) - 1;
  for (int i = 0; i < k; ++i) std::swap(pool[i], pool[rng->UniformInt(i, last)]);
  pool.resize(static_cast<size_t>(k));
  return pool;
}

double SampleFriction(Rng* rng, SurfaceClass c) {
  const FrictionDistribution d = ClassFriction(c);
  return std::min(std::max(rng->Normal(d.mean, d.std_dev), 0.1), 1.0);
}

// Largest-area rectangle of patches all equal to label (sizes by area descending, widths outer,
// heights inner on ties; top-left positions row-major; first fit wins), as the original's
// rectangle search. Returns {row0, col0, rows, cols}.
std::array<int, 4> LargestRectangle(const std::vector<int>& labels, int label) {
  struct Size {
    int w;
    int h;
  };
  std::vector<Size> sizes;
  for (int w = 1; w <= kPatchesPerSide; ++w) {
    for (int h = 1; h <= kPatchesPerSide; ++h) sizes.push_back({w, h});
  }
  std::stable_sort(sizes.begin(), sizes.end(),
                   [](const Size& a, const Size& b) { return a.w * a.h > b.w * b.h; });
  for (const Size& s : sizes) {
    for (int i = 0; i + s.h <= kPatchesPerSide; ++i) {
      for (int j = 0; j + s.w <= kPatchesPerSide; ++j) {
        bool fits = true;
        for (int a = i; a < i + s.h && fits; ++a) {
          for (int b = j; b < j + s.w && fits; ++b) fits = labels[a * kPatchesPerSide + b] == label;
        }
        if (fits) return {i, j, s.h, s.w};
      }
    }
  }
  return {0, 0, 0, 0};
}

PatchGrid GenerateSemantics(Rng* rng, TerrainType type) {
  const std::vector<int> rigid_pool = {0, 1, 2, 3, 4, 5, 6};
  const std::vector<int> deformable_pool = {7, 8, 9};
  std::vector<int> cluster_labels;
  if (type == TerrainType::kRigid) {
    cluster_labels = SampleWithoutReplacement(rng, rigid_pool, rng->UniformInt(1, 7));
  } else if (type == TerrainType::kDeformable) {
    cluster_labels = SampleWithoutReplacement(rng, deformable_pool, rng->UniformInt(1, 3));
  } else {
    const int n = rng->UniformInt(2, 10);
    const int n_rigid = std::min(rng->UniformInt(1, n - 1), 7);
    const int n_deformable = std::min(n - n_rigid, 3);
    cluster_labels = SampleWithoutReplacement(rng, rigid_pool, n_rigid);
    const std::vector<int> def = SampleWithoutReplacement(rng, deformable_pool, n_deformable);
    cluster_labels.insert(cluster_labels.end(), def.begin(), def.end());
  }

  // distinct cluster centres ~ truncated Normal over the patch grid, rejection as the original
  std::vector<std::array<int, 2>> centres;
  while (centres.size() < cluster_labels.size()) {
    const int y = static_cast<int>(rng->Normal(kClusterCentreMean, kClusterCentreStd));
    const int x = static_cast<int>(rng->Normal(kClusterCentreMean, kClusterCentreStd));
    if (y < 0 || y >= kPatchesPerSide || x < 0 || x >= kPatchesPerSide) continue;
    const std::array<int, 2> centre = {y, x};
    if (std::find(centres.begin(), centres.end(), centre) != centres.end()) continue;
    centres.push_back({y, x});
  }

  std::vector<int> labels(kPatchesPerSide * kPatchesPerSide);
  for (int i = 0; i < kPatchesPerSide; ++i) {
    for (int j = 0; j < kPatchesPerSide; ++j) {
      int best = 0;
      int best_d2 = 1 << 30;
      for (size_t k = 0; k < centres.size(); ++k) {
        const int di = i - centres[k][0];
        const int dj = j - centres[k][1];
        const int d2 = di * di + dj * dj;
        if (d2 < best_d2) {  // strict: ties keep the lowest cluster index
          best_d2 = d2;
          best = static_cast<int>(k);
        }
      }
      labels[i * kPatchesPerSide + j] = cluster_labels[best];
    }
  }

  PatchGrid patches;
  patches.rows = kPatchesPerSide;
  patches.cols = kPatchesPerSide;
  patches.classes.resize(labels.size());
  patches.friction.assign(labels.size(), 0.0);
  for (size_t k = 0; k < labels.size(); ++k) {
    patches.classes[k] = static_cast<SurfaceClass>(labels[k]);
    if (!IsDeformable(patches.classes[k])) {
      patches.friction[k] = SampleFriction(rng, patches.classes[k]);
    }
  }

  // mixed worlds: each deformable class keeps one rectangle; the rest becomes clay with one
  // shared friction sample, so every soil region is a rectangle as in the original's data
  if (type == TerrainType::kMixed) {
    std::vector<uint8_t> keep(labels.size(), 0);
    for (int label : cluster_labels) {
      if (label < 7) continue;
      const auto rect = LargestRectangle(labels, label);
      for (int a = rect[0]; a < rect[0] + rect[2]; ++a) {
        for (int b = rect[1]; b < rect[1] + rect[3]; ++b) keep[a * kPatchesPerSide + b] = 1;
      }
    }
    const double clay_friction = SampleFriction(rng, SurfaceClass::kClay);
    for (size_t k = 0; k < labels.size(); ++k) {
      if (IsDeformable(patches.classes[k]) && !keep[k]) {
        patches.classes[k] = SurfaceClass::kClay;
        patches.friction[k] = clay_friction;
      }
    }
  }
  return patches;
}

// ---------------------------------------------------------------------------------------------
// Obstacles (§4.4) and start/goal pairs (§4.5).

void CountsFor(ObstacleDensity density, int* rocks, int* trees) {
  switch (density) {
    case ObstacleDensity::kSparse: *rocks = 10; *trees = 1; return;
    case ObstacleDensity::kMedium: *rocks = 20; *trees = 2; return;
    case ObstacleDensity::kDense: *rocks = 40; *trees = 3; return;
  }
}

std::vector<StartGoalPair> CirclePairs(double radius_m) {
  std::vector<StartGoalPair> pairs(kNumPairs);
  for (int k = 0; k < kNumPairs; ++k) {
    const double angle = k * (2.0 * kPi / kNumPairs);
    pairs[k].start_m = Vec2(radius_m * std::cos(angle), radius_m * std::sin(angle));
    // 0 - v rather than -v, so an exact zero stays +0.0 in the task file
    pairs[k].goal_m = Vec2(0.0 - pairs[k].start_m.x(), 0.0 - pairs[k].start_m.y());
  }
  return pairs;
}

// One placement round: every obstacle gets up to kPlacementAttempts uniform candidates; false if
// one could not be placed (the caller starts a new round with the next draws).
bool PlaceObstacles(Rng* rng, double layout_scale, const std::vector<StartGoalPair>& pairs,
                    int num_rocks, int num_trees, TaskSpec* task) {
  const double bound = kObstacleBoundM * layout_scale;
  const double clear_pairs2 = std::pow(kClearanceToPairsM * layout_scale, 2);
  const double clear_between2 = std::pow(kClearanceBetweenM * layout_scale, 2);
  std::vector<Vec2> placed;
  auto try_place = [&](Vec2* out) {
    for (int attempt = 0; attempt < kPlacementAttempts; ++attempt) {
      const Vec2 p(rng->Uniform(-bound, bound), rng->Uniform(-bound, bound));
      bool ok = true;
      for (const StartGoalPair& pair : pairs) {
        ok = ok && (p - pair.start_m).squaredNorm() > clear_pairs2 &&
             (p - pair.goal_m).squaredNorm() > clear_pairs2;
      }
      for (const Vec2& q : placed) ok = ok && (p - q).squaredNorm() > clear_between2;
      if (ok) {
        placed.push_back(p);
        *out = p;
        return true;
      }
    }
    return false;
  };
  task->rocks.clear();
  task->trees.clear();
  // all rocks first, then trees, as the original
  for (int i = 0; i < num_rocks; ++i) {
    RockSpec rock;
    rock.scale = rng->Uniform(0.7, 1.2);
    Vec2 p;
    if (!try_place(&p)) return false;
    rock.x_m = p.x();
    rock.y_m = p.y();
    task->rocks.push_back(rock);
  }
  for (int j = 0; j < num_trees; ++j) {
    Vec2 p;
    if (!try_place(&p)) return false;
    task->trees.push_back({p.x(), p.y()});
  }
  return true;
}

// Plans every pair on the inflated obstacle grid; false if any pair is disconnected.
bool PlanAllPairs(TaskSpec* task) {
  AssignShapeSeeds(task);
  const OccupancyGrid inflated = Inflate(RasterizeObstacles(*task), PlannerInflationCells(*task));
  for (StartGoalPair& pair : task->pairs) {
    auto path = PlanPath(inflated, pair.start_m, pair.goal_m);
    if (!path) return false;
    pair.path_m = std::move(*path);
  }
  return true;
}

}  // namespace

GeneratorOptions BenchmarkEnvironment(int env_id) {
  VB_DEMAND(env_id >= 0 && env_id < kBenchmarkEnvironments);
  static constexpr ElevationLevel kLevels[3] = {ElevationLevel::kLow, ElevationLevel::kMid,
                                                ElevationLevel::kHigh};
  static constexpr ObstacleDensity kDensities[3] = {
      ObstacleDensity::kSparse, ObstacleDensity::kMedium, ObstacleDensity::kDense};
  GeneratorOptions o;
  o.seed = static_cast<uint64_t>(env_id);
  char name[16];
  std::snprintf(name, sizeof(name), "env%03d", env_id);
  o.name = name;
  o.terrain = env_id < 60   ? TerrainType::kRigid
              : env_id < 90 ? TerrainType::kDeformable
                            : TerrainType::kMixed;
  o.elevation = kLevels[env_id % 3];
  o.density = kDensities[(env_id / 3) % 3];
  return o;
}

HeightGrid GenerateElevation(const GeneratorOptions& options) {
  VB_DEMAND(options.grid_vertices >= 65);
  Rng master(options.seed);
  Rng height_rng(master.NextU64());  // first stream, as in GenerateTask
  return GenerateHeights(&height_rng, options.grid_vertices, options.elevation);
}

TaskSpec GenerateTask(const GeneratorOptions& options) {
  VB_DEMAND(options.grid_vertices >= 65);
  const int n = options.grid_vertices;
  const double world_m = n - 1.0;  // 1 m spacing
  const double layout_scale = world_m / kReferenceWorldM;

  // one independent stream per stage, so changing one stage leaves the others' draws intact
  // (GenerateElevation relies on the height stream being the first)
  Rng master(options.seed);
  Rng height_rng(master.NextU64());
  Rng semantics_rng(master.NextU64());
  Rng obstacle_rng(master.NextU64());

  TaskSpec task;
  task.name = options.name;
  task.generator_seed = options.seed;
  task.size_x_m = world_m;
  task.size_y_m = world_m;
  task.scale = 1.0;
  task.height_image = "";
  task.heights = GenerateHeights(&height_rng, n, options.elevation);
  task.min_height_m = 0.0;
  const std::vector<double>& h = task.heights.heights_m;
  task.max_height_m = *std::max_element(h.begin(), h.end());
  task.patches = GenerateSemantics(&semantics_rng, options.terrain);
  task.labels = {options.elevation, options.terrain, options.density,
                 ClassesPresent(task.patches)};
  task.pairs = CirclePairs(kPairRadiusM * layout_scale);
  // vb's obstacle family: boulders and trunks (obstacle_shape.h), seeded per rock
  task.rock_shape.kind = ObstacleShapeKind::kBoulder;
  task.tree_shape.kind = ObstacleShapeKind::kTrunk;

  int num_rocks = 0;
  int num_trees = 0;
  CountsFor(options.density, &num_rocks, &num_trees);
  for (int round = 0;; ++round) {
    // a round that cannot place everything or disconnects a pair is redrawn from the next draws
    VB_DEMAND(round < kMaxPlacementRounds);
    if (PlaceObstacles(&obstacle_rng, layout_scale, task.pairs, num_rocks, num_trees, &task) &&
        PlanAllPairs(&task)) {
      break;
    }
  }
  return task;
}

ElevationStats ComputeElevationStats(const HeightGrid& heights, double spacing_m) {
  VB_DEMAND(heights.rows >= 2 && heights.cols >= 2);
  const std::vector<double>& h = heights.heights_m;
  const double count = static_cast<double>(h.size());
  ElevationStats s;
  const auto [lo, hi] = std::minmax_element(h.begin(), h.end());
  s.range_m = *hi - *lo;
  s.mean_m = MeanOf(h);
  double var = 0.0;
  for (double v : h) var += (v - s.mean_m) * (v - s.mean_m);
  s.std_m = std::sqrt(var / count);

  const std::vector<double> grad = GradientMagnitude(heights, spacing_m);
  s.mean_gradient = MeanOf(grad);
  std::vector<double> slope_deg(grad.size());
  for (size_t i = 0; i < grad.size(); ++i) slope_deg[i] = std::atan(grad[i]) * 180.0 / kPi;
  s.mean_slope_deg = MeanOf(slope_deg);
  s.fraction_above_20deg =
      std::count_if(slope_deg.begin(), slope_deg.end(), [](double a) { return a > 20.0; }) / count;
  s.fraction_above_30deg =
      std::count_if(slope_deg.begin(), slope_deg.end(), [](double a) { return a > 30.0; }) / count;
  std::sort(slope_deg.begin(), slope_deg.end());
  s.max_slope_deg = slope_deg.back();
  // linear interpolation between order statistics, as numpy.percentile's default
  const double pos = 0.95 * (count - 1.0);
  const size_t k = static_cast<size_t>(pos);
  const double frac = pos - k;
  s.p95_slope_deg = k + 1 < slope_deg.size()
                        ? slope_deg[k] + frac * (slope_deg[k + 1] - slope_deg[k])
                        : slope_deg[k];

  // roughness: residual of a 9x9 box mean with clamped ("nearest") borders, separable
  const int rows = heights.rows;
  const int cols = heights.cols;
  constexpr int kHalf = 4;
  std::vector<double> tmp(h.size());
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      double sum = 0.0;
      for (int k2 = -kHalf; k2 <= kHalf; ++k2) {
        sum += heights.At(r, std::min(std::max(c + k2, 0), cols - 1));
      }
      tmp[static_cast<size_t>(r) * cols + c] = sum / (2 * kHalf + 1);
    }
  }
  double rough_sum = 0.0;
  double rough_sq = 0.0;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      double sum = 0.0;
      for (int k2 = -kHalf; k2 <= kHalf; ++k2) {
        sum += tmp[static_cast<size_t>(std::min(std::max(r + k2, 0), rows - 1)) * cols + c];
      }
      const double residual = heights.At(r, c) - sum / (2 * kHalf + 1);
      rough_sum += residual;
      rough_sq += residual * residual;
    }
  }
  const double rough_mean = rough_sum / count;
  s.roughness_m = std::sqrt(std::max(rough_sq / count - rough_mean * rough_mean, 0.0));
  return s;
}

}  // namespace vb::terrain
