// EH baseline (eh_controller.h), reference §7.2, with vb's fixes (optimal A*, explicit clamp) as
// the PID's, and the regions where the original's target assumes them (ahead) unless
// original_left_regions.
#include "vb/controllers/eh_controller.h"

#include <algorithm>
#include <cmath>

#include "vb/controllers/pid_controller.h"
#include "vb/engine/error.h"

namespace vb::controllers {

int EhChooseRegion(const double* mean_m, const double* var_m2, int count, double under_mean_m) {
  int chosen = -1;
  double best_diff = 0.0, best_var = 0.0;
  for (int i = 0; i < count; ++i) {
    const double diff = std::abs(mean_m[i] - under_mean_m);
    if (chosen < 0 || diff < best_diff || (diff == best_diff && var_m2[i] < best_var)) {
      chosen = i;
      best_diff = diff;
      best_var = var_m2[i];
    }
  }
  return chosen;
}

EhController::EhController(const EhParams& params, std::string name)
    : params_(params), name_(std::move(name)) {
  VB_DEMAND(params_.num_regions >= 1 && params_.num_regions <= 9 && params_.num_regions % 2 == 1);
  VB_DEMAND(params_.region_size_m > 0.0 && params_.sample_spacing_m > 0.0);
}

ObservationConfig EhController::observation_config() const {
  ObservationConfig c;
  c.lookahead_m = params_.lookahead_m;
  c.replan_period_s = params_.replan_period_s;
  return c;
}

void EhController::Reset(const EpisodeContext& context) {
  VB_DEMAND(context.maps != nullptr);
  context_ = context;
  steering_ = 0.0;
  last_ = EhDecision();
}

void EhController::RegionStats(const Vec2& position_m, double cos_yaw, double sin_yaw,
                               double forward_m, double left_m, double* mean,
                               double* var) const {
  const double size = params_.region_size_m * context_.scale;
  const int n = std::max(1, static_cast<int>(std::lround(params_.region_size_m /
                                                         params_.sample_spacing_m)));
  const double spacing = size / n;
  const double first = -0.5 * size + 0.5 * spacing;   // sample cell centres
  const terrain::Terrain& terrain = context_.maps->terrain();
  double sum = 0.0, sum_sq = 0.0;
  for (int i = 0; i < n; ++i) {
    const double f = forward_m + first + i * spacing;
    for (int j = 0; j < n; ++j) {
      const double l = left_m + first + j * spacing;
      const double h = terrain.Height(position_m.x() + cos_yaw * f - sin_yaw * l,
                                      position_m.y() + sin_yaw * f + cos_yaw * l);
      sum += h;
      sum_sq += h * h;
    }
  }
  const double count = static_cast<double>(n) * n;
  *mean = sum / count;
  *var = std::max(0.0, sum_sq / count - *mean * *mean);
}

EhDecision EhController::Decide(const Vec2& position_m, double yaw_rad) const {
  EhDecision d;
  const double cos_yaw = std::cos(yaw_rad), sin_yaw = std::sin(yaw_rad);
  const double size = params_.region_size_m * context_.scale;
  const int half = params_.num_regions / 2;
  RegionStats(position_m, cos_yaw, sin_yaw, 0.0, 0.0, &d.under_mean_m, &d.under_var_m2);
  for (int idx = 0; idx < params_.num_regions; ++idx) {
    // Region idx aims at (size ahead, (half - idx) * size to the left); the original samples it
    // at ((half - idx) * size ahead, size to the left).
    const double lateral = (half - idx) * size;
    const double forward_at = params_.original_left_regions ? lateral : size;
    const double left_at = params_.original_left_regions ? size : lateral;
    RegionStats(position_m, cos_yaw, sin_yaw, forward_at, left_at, &d.mean_m[idx], &d.var_m2[idx]);
  }
  d.chosen = EhChooseRegion(d.mean_m.data(), d.var_m2.data(), params_.num_regions, d.under_mean_m);
  const double lateral = (half - d.chosen) * size;
  d.target_m = position_m + Vec2(cos_yaw * size - sin_yaw * lateral,
                                 sin_yaw * size + cos_yaw * lateral);
  const Vec2 to_target = d.target_m - position_m;
  d.terrain_error_rad = WrapAngle(std::atan2(to_target.y(), to_target.x()) - yaw_rad);
  return d;
}

Command EhController::Update(const Observation& obs) {
  last_ = Decide(obs.position_W.head<2>(), obs.rpy.yaw_rad);
  const double error = params_.terrain_weight * last_.terrain_error_rad +
                       params_.path_weight * obs.heading_error_rad;
  steering_ = RateLimitedSteering(params_.steering_kp * error, steering_,
                                  params_.steering_rate_per_s * context_.control_period_s);
  Command command;
  command.steering = steering_;
  SpeedControl(context_.target_speed_mps, obs.forward_speed_mps, params_.speed_kp, &command);
  return command;
}

std::unique_ptr<Controller> EhController::Clone() const {
  return std::make_unique<EhController>(*this);
}

}  // namespace vb::controllers
