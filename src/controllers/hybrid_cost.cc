// The hybrid baselines' cost (hybrid_cost.h).
#include "vb/controllers/hybrid_cost.h"

#include <algorithm>
#include <cmath>

namespace vb::controllers {

namespace {

// Min-max normalises v[0..n) in place to [0, 1] (all 0 when the range is empty).
void Normalise(std::vector<double>& v, int n) {
  double lo = v[0], hi = v[0];
  for (int k = 1; k < n; ++k) {
    lo = std::min(lo, v[k]);
    hi = std::max(hi, v[k]);
  }
  const double inv = hi > lo ? 1.0 / (hi - lo) : 0.0;
  for (int k = 0; k < n; ++k) v[k] = (v[k] - lo) * inv;
}

double WrapPi(double a) { return std::remainder(a, 2.0 * M_PI); }

}  // namespace

HybridCost::HybridCost(const HybridCostParams& params, const terrain::GridMap* obstacles,
                       double world_size_x_m, double world_size_y_m,
                       const TraversabilityMap* trav)
    : params_(params),
      obstacles_(GoalObstacleCostParams(), obstacles, world_size_x_m, world_size_y_m),
      trav_(trav) {}

void HybridCost::set_goal(const Vec2& goal_m, const Vec2& start_m) {
  goal_m_ = goal_m;
  start_d2_ = std::max(1e-6, (goal_m - start_m).squaredNorm());
}

void HybridCost::Evaluate(int /*step*/, const PlannerState* states,
                          const MppiControl* /*controls*/, int count, double* cost) {
  if (static_cast<int>(d2_.size()) != count) {
    for (auto* v : {&d2_, &roll_, &pitch_, &trav_cost_}) v->assign(static_cast<size_t>(count), 0.0);
  }
  const auto attitude = [&](double a) { return params_.signed_attitude ? a : std::abs(a); };
  for (int k = 0; k < count; ++k) {
    const double dx = goal_m_.x() - states[k].x_m;
    const double dy = goal_m_.y() - states[k].y_m;
    d2_[k] = dx * dx + dy * dy;
    cost[k] = params_.goal_raw_weight * d2_[k];
    if (params_.heading_weight != 0.0) {
      cost[k] += params_.heading_weight *
                 std::abs(WrapPi(std::atan2(dy, dx) - states[k].yaw_rad)) / start_d2_;
    }
    if (params_.obstacle_weight != 0.0) {
      cost[k] += params_.obstacle_weight * obstacles_.ObstacleAt(states[k].x_m, states[k].y_m);
    }
    roll_[k] = attitude(states[k].roll_rad);
    pitch_[k] = attitude(states[k].pitch_rad);
    if (params_.trav_weight != 0.0 && trav_ != nullptr) {
      trav_cost_[k] = trav_->Cost(states[k].x_m, states[k].y_m);
    }
  }
  if (params_.goal_weight != 0.0) {
    Normalise(d2_, count);
    for (int k = 0; k < count; ++k) cost[k] += params_.goal_weight * d2_[k];
  }
  if (params_.roll_weight != 0.0 || params_.pitch_weight != 0.0) {
    if (params_.attitude_normalised) {
      // TAL's rule: |angle| min-max normalised across the samples, 0 where the angle itself is
      // below the threshold
      for (std::vector<double>* a : {&roll_, &pitch_}) {
        std::vector<double>& v = *a;
        double lo = v[0], hi = v[0];
        for (int k = 1; k < count; ++k) {
          lo = std::min(lo, v[k]);
          hi = std::max(hi, v[k]);
        }
        const double inv = hi > lo ? 1.0 / (hi - lo) : 0.0;
        for (int k = 0; k < count; ++k) {
          v[k] = v[k] < params_.attitude_threshold_rad ? 0.0 : (v[k] - lo) * inv;
        }
      }
    }
    for (int k = 0; k < count; ++k) {
      cost[k] += params_.roll_weight * roll_[k] + params_.pitch_weight * pitch_[k];
    }
  }
  if (params_.trav_weight != 0.0 && trav_ != nullptr) {
    Normalise(trav_cost_, count);
    for (int k = 0; k < count; ++k) cost[k] += params_.trav_weight * trav_cost_[k];
  }
}

std::unique_ptr<RolloutCost> HybridCost::Clone() const {
  return std::make_unique<HybridCost>(*this);
}

}  // namespace vb::controllers
