// Imperfect perception: the error processes and map error fields of perception.h.
#include "vb/engine/runner/perception.h"

#include <algorithm>
#include <cmath>

#include "vb/engine/error.h"
#include "vb/terrain/gt_maps.h"

namespace vb::runner {

namespace {

using terrain::SurfaceClass;

// Salts of the map error fields (any distinct constants).
constexpr uint64_t kSaltElevation = 0x51ED270B2A3D4E1Full;
constexpr uint64_t kSaltHole = 0x7C2B9E5D1A0F3C47ull;
constexpr uint64_t kSaltSemantics = 0x2F8A4C6E9B1D3057ull;
constexpr uint64_t kSaltObstacles = 0x6A09E667F3BCC909ull;
constexpr uint64_t kSaltPose = 0x3C6EF372FE94F82Bull;

// SplitMix64's finaliser: a bijective 64-bit mix.
uint64_t Mix(uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double UnitFromHash(uint64_t h) { return static_cast<double>(h >> 11) * 0x1.0p-53; }

// Standard normal from a hash: one of 4096 equiprobable quantiles of N(0, 1) (the inverse CDF at
// (i + 1/2) / 4096, |z| <= 3.5), picked by 12 bits of the hash. The map error fields draw one
// per crop cell per observation, where Box-Muller's log and cos cost ~5x more; the quantised
// normal has the right mean and a variance within 0.2 % of 1.
constexpr int kQuantileBits = 12;
constexpr int kQuantiles = 1 << kQuantileBits;
struct NormalQuantiles {
  double z[kQuantiles];
  NormalQuantiles() {
    for (int i = 0; i < kQuantiles; ++i) {
      const double p = (i + 0.5) / kQuantiles;
      // Bisection on Phi(z) = erfc(-z / sqrt 2) / 2: monotone, exact to the last bit we need.
      double lo = -10.0, hi = 10.0;
      for (int it = 0; it < 80; ++it) {
        const double mid = 0.5 * (lo + hi);
        (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
      }
      z[i] = 0.5 * (lo + hi);
    }
  }
};
double NormalFromHash(uint64_t h) {
  static const NormalQuantiles kTable;
  return kTable.z[h >> (64 - kQuantileBits)];
}

// Poisson count by inversion (Knuth); the rates used give means below a few hundred.
int Poisson(double mean, Rng* rng) {
  if (!(mean > 0.0)) return 0;
  const double limit = std::exp(-std::min(mean, 700.0));
  int k = 0;
  double p = rng->Uniform();
  while (p > limit && k < 100000) {
    ++k;
    p *= rng->Uniform();
  }
  return k;
}

void Require(bool ok, const std::string& source, const char* key, const std::string& what) {
  if (!ok) throw InputError(source, 0, key, what);
}

}  // namespace

ConfusionMatrix ConfusionFromErrorRate(double error_rate) {
  // Look-alikes by class id (surface_class.h): 0 clay, 1 concrete, 2 dirt, 3 grass, 4 gravel,
  // 5 rock, 6 wood, 7 mud, 8 sand, 9 snow.
  static const std::vector<std::vector<int>> kLookAlikes = {
      {2, 7},     // clay: dirt, mud
      {5, 4},     // concrete: rock, gravel
      {0, 7, 8},  // dirt: clay, mud, sand
      {2, 6},     // grass: dirt, wood
      {5, 2, 8},  // gravel: rock, dirt, sand
      {4, 1},     // rock: gravel, concrete
      {2, 3},     // wood: dirt, grass
      {2, 0},     // mud: dirt, clay
      {2, 4},     // sand: dirt, gravel
      {1, 5},     // snow: concrete, rock
  };
  ConfusionMatrix m{};
  for (int i = 0; i < terrain::kNumSurfaceClasses; ++i) {
    m[i][i] = 1.0 - error_rate;
    const std::vector<int>& alike = kLookAlikes[static_cast<size_t>(i)];
    for (int j : alike) m[i][j] += error_rate / static_cast<double>(alike.size());
  }
  return m;
}

bool PerceptionParams::HasSemanticErrors() const {
  for (int i = 0; i < terrain::kNumSurfaceClasses; ++i) {
    if (semantics_confusion[i][i] != 1.0) return true;
  }
  return false;
}

bool PerceptionParams::Enabled() const {
  return position_bias_sd_m > 0.0 || position_drift_m_per_sqrt_s > 0.0 ||
         position_noise_sd_m > 0.0 || yaw_bias_sd_rad > 0.0 || yaw_drift_rad_per_sqrt_s > 0.0 ||
         yaw_noise_sd_rad > 0.0 || attitude_noise_sd_rad > 0.0 || velocity_noise_sd_mps > 0.0 ||
         angular_velocity_noise_sd_radps > 0.0 || elevation_noise_sd_m > 0.0 ||
         elevation_hole_fraction > 0.0 || mapping_delay_s > 0.0 || HasSemanticErrors() ||
         HasObstacleErrors() || latency_s > 0.0;
}

void ValidatePerception(const PerceptionParams& p, const std::string& source) {
  auto non_negative = [&](double v, const char* key, double max) {
    Require(std::isfinite(v) && v >= 0.0 && v <= max, source, key,
            "must be in [0, " + std::to_string(max) + "], got " + std::to_string(v));
  };
  non_negative(p.position_bias_sd_m, "pose.position_bias_sd_m", 100.0);
  non_negative(p.position_drift_m_per_sqrt_s, "pose.position_drift_m_per_sqrt_s", 10.0);
  non_negative(p.position_noise_sd_m, "pose.position_noise_sd_m", 100.0);
  non_negative(p.yaw_bias_sd_rad, "pose.yaw_bias_sd_rad", 3.2);
  non_negative(p.yaw_drift_rad_per_sqrt_s, "pose.yaw_drift_rad_per_sqrt_s", 1.0);
  non_negative(p.yaw_noise_sd_rad, "pose.yaw_noise_sd_rad", 3.2);
  non_negative(p.attitude_noise_sd_rad, "pose.attitude_noise_sd_rad", 1.0);
  non_negative(p.noise_correlation_s, "pose.noise_correlation_s", 3600.0);
  non_negative(p.velocity_noise_sd_mps, "pose.velocity_noise_sd_mps", 100.0);
  non_negative(p.angular_velocity_noise_sd_radps, "pose.angular_velocity_noise_sd_radps", 100.0);
  Require(std::isfinite(p.map_cell_m) && p.map_cell_m >= 0.01 && p.map_cell_m <= 10.0, source,
          "maps.map_cell_m", "must be in [0.01, 10] m");
  non_negative(p.elevation_noise_sd_m, "maps.elevation_noise_sd_m", 10.0);
  non_negative(p.elevation_hole_fraction, "maps.elevation_hole_fraction", 1.0);
  Require(std::isfinite(p.elevation_hole_size_m) && p.elevation_hole_size_m >= 0.01 &&
              p.elevation_hole_size_m <= 100.0,
          source, "maps.elevation_hole_size_m", "must be in [0.01, 100] m");
  non_negative(p.mapping_delay_s, "maps.mapping_delay_s", 10.0);
  for (int i = 0; i < terrain::kNumSurfaceClasses; ++i) {
    double sum = 0.0;
    for (int j = 0; j < terrain::kNumSurfaceClasses; ++j) {
      const double v = p.semantics_confusion[i][j];
      Require(std::isfinite(v) && v >= 0.0 && v <= 1.0, source, "semantics.confusion",
              "entries must be in [0, 1]");
      sum += v;
    }
    Require(std::abs(sum - 1.0) <= 1e-6, source, "semantics.confusion",
            "row " + std::to_string(i) + " (" +
                std::string(terrain::SurfaceClassName(static_cast<SurfaceClass>(i))) +
                ") must sum to 1, sums to " + std::to_string(sum));
  }
  non_negative(p.obstacle_miss_probability, "obstacles.miss_probability", 1.0);
  non_negative(p.phantom_rocks_per_ha, "obstacles.phantom_rocks_per_ha", 100.0);
  non_negative(p.latency_s, "latency_s", 10.0);
}

PerceptionModel::PerceptionModel(const PerceptionParams& params, double step_s)
    : params_(params), enabled_(params.Enabled()), step_s_(step_s) {
  VB_DEMAND(step_s > 0.0);
  latency_steps_ = std::lround(params.latency_s / step_s);
  mapping_delay_steps_ = std::lround(params.mapping_delay_s / step_s);
  history_steps_ = latency_steps_ + mapping_delay_steps_;
}

void PerceptionModel::Reset(uint64_t trial_seed, const terrain::TaskSpec& task) {
  if (!enabled_) return;
  scale_ = task.scale;
  map_seed_ = Mix(trial_seed ^ kSaltPose);
  PerceptionState& s = state_;
  s = PerceptionState();
  s.rng = Rng(Mix(map_seed_));
  s.last_update_s = 0.0;
  const PerceptionParams& p = params_;
  // Bias constant for the trial; Gauss-Markov noises start in their stationary distribution.
  s.position_bias_m = Vec2(s.rng.Normal(0.0, p.position_bias_sd_m * scale_),
                           s.rng.Normal(0.0, p.position_bias_sd_m * scale_));
  s.yaw_bias_rad = s.rng.Normal(0.0, p.yaw_bias_sd_rad);
  for (int a = 0; a < 3; ++a) s.position_noise_m[a] = s.rng.Normal(0.0, p.position_noise_sd_m * scale_);
  s.yaw_noise_rad = s.rng.Normal(0.0, p.yaw_noise_sd_rad);
  s.roll_noise_rad = s.rng.Normal(0.0, p.attitude_noise_sd_rad);
  s.pitch_noise_rad = s.rng.Normal(0.0, p.attitude_noise_sd_rad);
  if (history_steps_ > 0) {
    s.history.assign(static_cast<size_t>(history_steps_ + 1), vehicles::VehicleState());
  }

  missed_ = 0;
  phantoms_ = 0;
  if (!p.HasObstacleErrors()) return;
  // What the vehicle believes is there: a light task with just the fields the rasteriser reads.
  Rng obstacle_rng(Mix(map_seed_ ^ kSaltObstacles));
  terrain::TaskSpec seen;
  seen.size_x_m = task.size_x_m;
  seen.size_y_m = task.size_y_m;
  seen.scale = task.scale;
  seen.heights.rows = task.heights.rows;
  seen.heights.cols = task.heights.cols;
  double min_scale = 1.0, max_scale = 1.0;
  for (size_t i = 0; i < task.rocks.size(); ++i) {
    const terrain::RockSpec& rock = task.rocks[i];
    min_scale = i == 0 ? rock.scale : std::min(min_scale, rock.scale);
    max_scale = i == 0 ? rock.scale : std::max(max_scale, rock.scale);
    if (obstacle_rng.Uniform() < p.obstacle_miss_probability) {
      ++missed_;
    } else {
      seen.rocks.push_back(rock);
    }
  }
  for (const terrain::TreeSpec& tree : task.trees) {
    if (obstacle_rng.Uniform() < p.obstacle_miss_probability) {
      ++missed_;
    } else {
      seen.trees.push_back(tree);
    }
  }
  // Phantom rocks, uniform over the world, sized like the task's rocks.
  const double area_ha = task.size_x_m * task.size_y_m / 1.0e4;
  phantoms_ = Poisson(p.phantom_rocks_per_ha * area_ha, &obstacle_rng);
  for (int i = 0; i < phantoms_; ++i) {
    terrain::RockSpec rock;
    rock.x_m = obstacle_rng.Uniform(-0.5 * task.size_x_m, 0.5 * task.size_x_m);
    rock.y_m = obstacle_rng.Uniform(-0.5 * task.size_y_m, 0.5 * task.size_y_m);
    rock.scale = obstacle_rng.Uniform(min_scale, max_scale);
    seen.rocks.push_back(rock);
  }
  perceived_bare_ = terrain::RasterizeObstacles(seen);
  perceived_inflated_ = terrain::Inflate(perceived_bare_, terrain::PlannerInflationCells(seen));
}

void PerceptionModel::Record(long k, const vehicles::VehicleState& s) {
  if (history_steps_ == 0) return;
  PerceptionState& st = state_;
  const size_t n = st.history.size();
  // Steps skipped (none in practice: the episode records every step) repeat the last state.
  for (long j = st.last_recorded_step + 1; j < k; ++j) {
    st.history[static_cast<size_t>(j) % n] = st.history[static_cast<size_t>(j - 1 < 0 ? 0 : j - 1) % n];
  }
  st.history[static_cast<size_t>(k) % n] = s;
  st.last_recorded_step = k;
}

const vehicles::VehicleState& PerceptionModel::Delayed(
    long k, long delay_steps, const vehicles::VehicleState& current) const {
  if (delay_steps <= 0 || history_steps_ == 0 || state_.last_recorded_step < 0) return current;
  // Before the trial started, the state was the start state (step 0).
  const long j = std::max(0L, k - delay_steps);
  VB_DEMAND(j <= state_.last_recorded_step && state_.last_recorded_step - j <= history_steps_);
  return state_.history[static_cast<size_t>(j) % state_.history.size()];
}

PoseError PerceptionModel::AdvanceTo(double t_s) {
  PerceptionState& s = state_;
  const PerceptionParams& p = params_;
  const double dt = t_s - s.last_update_s;
  if (dt > 0.0) {
    // Random walks.
    const double sq = std::sqrt(dt);
    s.position_drift_m += Vec2(s.rng.Normal(0.0, p.position_drift_m_per_sqrt_s * scale_ * sq),
                               s.rng.Normal(0.0, p.position_drift_m_per_sqrt_s * scale_ * sq));
    s.yaw_drift_rad += s.rng.Normal(0.0, p.yaw_drift_rad_per_sqrt_s * sq);
    // Gauss-Markov: x <- a x + sd sqrt(1 - a^2) n, a = exp(-dt / tau) (a = 0: white).
    const double a = p.noise_correlation_s > 0.0 ? std::exp(-dt / p.noise_correlation_s) : 0.0;
    const double b = std::sqrt(std::max(0.0, 1.0 - a * a));
    for (int i = 0; i < 3; ++i) {
      s.position_noise_m[i] =
          a * s.position_noise_m[i] + s.rng.Normal(0.0, p.position_noise_sd_m * scale_ * b);
    }
    s.yaw_noise_rad = a * s.yaw_noise_rad + s.rng.Normal(0.0, p.yaw_noise_sd_rad * b);
    s.roll_noise_rad = a * s.roll_noise_rad + s.rng.Normal(0.0, p.attitude_noise_sd_rad * b);
    s.pitch_noise_rad = a * s.pitch_noise_rad + s.rng.Normal(0.0, p.attitude_noise_sd_rad * b);
    s.last_update_s = t_s;
  }
  PoseError e;
  e.position_m = s.position_noise_m;
  e.position_m.x() += s.position_bias_m.x() + s.position_drift_m.x();
  e.position_m.y() += s.position_bias_m.y() + s.position_drift_m.y();
  e.roll_rad = s.roll_noise_rad;
  e.pitch_rad = s.pitch_noise_rad;
  e.yaw_rad = s.yaw_bias_rad + s.yaw_drift_rad + s.yaw_noise_rad;
  return e;
}

Vec3 PerceptionModel::VelocityNoise() {
  const double sd = params_.velocity_noise_sd_mps * scale_;
  if (!(sd > 0.0)) return Vec3::Zero();
  Rng& r = state_.rng;
  return Vec3(r.Normal(0.0, sd), r.Normal(0.0, sd), r.Normal(0.0, sd));
}

Vec3 PerceptionModel::AngularVelocityNoise() {
  const double sd = params_.angular_velocity_noise_sd_radps;
  if (!(sd > 0.0)) return Vec3::Zero();
  Rng& r = state_.rng;
  return Vec3(r.Normal(0.0, sd), r.Normal(0.0, sd), r.Normal(0.0, sd));
}

uint64_t PerceptionModel::CellHash(uint64_t salt, double cell_m, const Vec2& p_m) const {
  const int64_t ix = static_cast<int64_t>(std::floor(p_m.x() / cell_m));
  const int64_t iy = static_cast<int64_t>(std::floor(p_m.y() / cell_m));
  uint64_t h = Mix(map_seed_ ^ salt);
  h = Mix(h ^ static_cast<uint64_t>(ix));
  return Mix(h ^ (static_cast<uint64_t>(iy) * 0xD1B54A32D192ED03ull));
}

double PerceptionModel::ElevationError(const Vec2& p_m) const {
  if (!(params_.elevation_noise_sd_m > 0.0)) return 0.0;
  return params_.elevation_noise_sd_m * scale_ *
         NormalFromHash(CellHash(kSaltElevation, params_.map_cell_m * scale_, p_m));
}

bool PerceptionModel::IsHole(const Vec2& p_m) const {
  if (!(params_.elevation_hole_fraction > 0.0)) return false;
  return UnitFromHash(CellHash(kSaltHole, params_.elevation_hole_size_m * scale_, p_m)) <
         params_.elevation_hole_fraction;
}

int PerceptionModel::PerceivedClass(int true_class, const Vec2& p_m) const {
  if (true_class < 0 || true_class >= terrain::kNumSurfaceClasses) return true_class;
  const std::array<double, terrain::kNumSurfaceClasses>& row =
      params_.semantics_confusion[static_cast<size_t>(true_class)];
  if (row[static_cast<size_t>(true_class)] == 1.0) return true_class;
  const double u = UnitFromHash(CellHash(kSaltSemantics, params_.map_cell_m * scale_, p_m));
  double acc = 0.0;
  for (int j = 0; j < terrain::kNumSurfaceClasses; ++j) {
    acc += row[static_cast<size_t>(j)];
    if (u < acc) return j;
  }
  return true_class;  // rounding: the remainder stays true
}

void PerceptionModel::ApplyToCrop(terrain::MapLayer layer, const Vec2& position_m,
                                  double yaw_rad, const terrain::GridMap* true_semantics,
                                  terrain::GridMap* crop) const {
  if (!enabled_) return;
  using terrain::MapLayer;
  const PerceptionParams& p = params_;
  const bool elevation = layer == MapLayer::kElevation &&
                         (p.elevation_noise_sd_m > 0.0 || p.elevation_hole_fraction > 0.0);
  const bool semantic =
      (layer == MapLayer::kSemantics || layer == MapLayer::kFriction) && p.HasSemanticErrors();
  const bool occupancy = layer == MapLayer::kOccupancy && p.HasObstacleErrors();
  if (!elevation && !semantic && !occupancy) return;
  VB_DEMAND(layer != MapLayer::kFriction ||
            (true_semantics != nullptr && true_semantics->rows == crop->rows &&
             true_semantics->cols == crop->cols));
  // The crop's cell positions, as gt_maps.h defines them.
  const int n = crop->rows;
  const double res = crop->resolution_m;
  const double centre = 0.5 * (n - 1);
  const double cos_yaw = std::cos(yaw_rad);
  const double sin_yaw = std::sin(yaw_rad);
  const terrain::OccupancyGrid& g = perceived_bare_;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < crop->cols; ++j) {
      const double forward = (centre - i) * res;
      const double left = (centre - j) * res;
      const Vec2 q(position_m.x() + cos_yaw * forward - sin_yaw * left,
                   position_m.y() + sin_yaw * forward + cos_yaw * left);
      double& v = crop->values[static_cast<size_t>(i) * crop->cols + j];
      if (elevation) {
        v = IsHole(q) ? std::nan("") : v + ElevationError(q);
      } else if (occupancy) {
        const double half = 0.5 * g.cell_m;
        if (std::abs(q.x()) > 0.5 * g.size_x_m + half || std::abs(q.y()) > 0.5 * g.size_y_m + half) {
          v = 1.0;
        } else {
          const terrain::Cell c = g.CellOf(q);
          v = g.Occupied(c.row, c.col) ? 1.0 : 0.0;
        }
      } else if (layer == MapLayer::kSemantics) {
        v = static_cast<double>(PerceivedClass(static_cast<int>(v), q));
      } else {  // friction: where the class is mistaken, the perceived class's mean friction
        const int truth = static_cast<int>(true_semantics->values[static_cast<size_t>(i) * n + j]);
        const int seen = PerceivedClass(truth, q);
        if (seen != truth) {
          v = terrain::ClassFriction(static_cast<terrain::SurfaceClass>(seen)).mean;
        }
      }
    }
  }
}

}  // namespace vb::runner
