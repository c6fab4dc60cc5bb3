// The learned baselines' features: python/vb_gym/learned.py, operation for operation (float32
// products of float32-rounded inputs, the 2 x 2 block sums in the same order).
#include "vb/controllers/learned_features.h"

#include <algorithm>
#include <cmath>

#include "vb/engine/error.h"

namespace vb::controllers {

namespace {

constexpr double kPiD = 3.14159265358979323846;

float Clip(float v) { return std::clamp(v, -kLearnedClip, kLearnedClip); }

}  // namespace

ObservationConfig LearnedObservationConfig() {
  ObservationConfig c;
  c.lookahead_m = 10.0;
  c.replan_period_s = 0.1;
  CropSpec crop;
  crop.layer = terrain::MapLayer::kElevation;
  crop.size_cells = kLearnedCropCells;
  crop.resolution_m = kLearnedCropResolution_m;
  c.crops.push_back(crop);
  // The policy reads the crop once per decision (LearnedController::Update, calls 0, 20, 40, ...
  // at 5 ms control), and the crop rebuilds fall on the same instants.
  c.crop_period_s = kLearnedDecisionPeriod_s;
  return c;
}

void LearnedFeatures(const Observation& obs, double applied_steering, float* out,
                     double max_speed_mps) {
  VB_DEMAND(!obs.crops.empty() && obs.crops[0].values.size() ==
                                      static_cast<size_t>(kLearnedCropCells * kLearnedCropCells));
  // The local goal in the vehicle frame, in double as the gym computes it.
  const double yaw = obs.rpy.yaw_rad;
  const double c = std::cos(yaw), s = std::sin(yaw);
  const double dx = obs.local_goal_m.x() - obs.position_W.x();
  const double dy = obs.local_goal_m.y() - obs.position_W.y();
  const double forward = c * dx + s * dy;
  const double left = -s * dx + c * dy;
  const double state[kLearnedStateFeatures] = {
      obs.heading_error_rad,        forward,
      left,                         obs.goal_distance_m,
      obs.forward_speed_mps,        obs.rpy.roll_rad,
      obs.rpy.pitch_rad,            obs.angular_velocity_B.x(),
      obs.angular_velocity_B.y(),   obs.angular_velocity_B.z(),
      obs.velocity_W.z(),           applied_steering};
  const float scale[kLearnedStateFeatures] = {
      static_cast<float>(1.0 / kPiD), 0.1f, 0.1f, 0.01f,
      static_cast<float>(1.0 / max_speed_mps), 2.0f, 2.0f, 1.0f, 1.0f, 1.0f, 0.5f, 1.0f};
  for (int i = 0; i < kLearnedStateFeatures; ++i) {
    out[i] = Clip(static_cast<float>(state[i]) * scale[i]);
  }
  // Elevation relative to the chassis (float32, as the gym's crop), unknown cells 0.
  const std::vector<double>& v = obs.crops[0].values;
  const float z = static_cast<float>(obs.position_W.z());
  auto cell = [&](int r, int col) {
    const float h = static_cast<float>(v[static_cast<size_t>(r * kLearnedCropCells + col)]) - z;
    return std::isnan(h) ? 0.0f : h;
  };
  constexpr int m = kLearnedCropCells / kLearnedPool;
  constexpr float kMean = 1.0f / (kLearnedPool * kLearnedPool * 2.0f);   // block mean / 2 m
  float* e = out + kLearnedStateFeatures;
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      const float top = cell(2 * i, 2 * j) + cell(2 * i, 2 * j + 1);
      const float bottom = cell(2 * i + 1, 2 * j) + cell(2 * i + 1, 2 * j + 1);
      e[i * m + j] = Clip((top + bottom) * kMean);
    }
  }
}

}  // namespace vb::controllers
