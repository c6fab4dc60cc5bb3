// Goal + obstacle cost of the MPPI baseline (mppi_goal_cost.h).
#include "vb/controllers/mppi_goal_cost.h"

#include <algorithm>
#include <cmath>

namespace vb::controllers {

GoalObstacleCost::GoalObstacleCost(const GoalObstacleCostParams& params,
                                   const terrain::GridMap* obstacles, double world_size_x_m,
                                   double world_size_y_m)
    : params_(params),
      obstacles_(obstacles),
      half_x_m_(0.5 * world_size_x_m),
      half_y_m_(0.5 * world_size_y_m) {}

double GoalObstacleCost::ObstacleAt(double x_m, double y_m) const {
  if (obstacles_ == nullptr || obstacles_->rows == 0) return 0.0;
  if (params_.original_transposed_lookup) {
    const double x = x_m;
    x_m = -y_m;
    y_m = -x;
  }
  // Nearest cell (grid cell (r, c) is centred at x = -half_x + c res, y = half_y - r res); beyond
  // half a cell past the border is outside the world (GroundTruthMaps::Sample's rule).
  const double res = obstacles_->resolution_m;
  const double c = (x_m + half_x_m_) / res;
  const double r = (half_y_m_ - y_m) / res;
  if (!(c > -0.5 && r > -0.5 && c < obstacles_->cols - 0.5 && r < obstacles_->rows - 0.5)) {
    return 1.0;
  }
  const int ci = std::min(obstacles_->cols - 1, static_cast<int>(c + 0.5));
  const int ri = std::min(obstacles_->rows - 1, static_cast<int>(r + 0.5));
  return obstacles_->At(ri, ci) > 0.5 ? 1.0 : 0.0;
}

void GoalObstacleCost::Evaluate(int /*step*/, const PlannerState* states,
                                const MppiControl* /*controls*/, int count, double* cost) {
  if (static_cast<int>(d2_.size()) != count) d2_.assign(static_cast<size_t>(count), 0.0);
  double lo = 0.0, hi = 0.0;
  for (int k = 0; k < count; ++k) {
    const double dx = states[k].x_m - goal_m_.x();
    const double dy = states[k].y_m - goal_m_.y();
    d2_[k] = dx * dx + dy * dy;
    lo = k == 0 ? d2_[k] : std::min(lo, d2_[k]);
    hi = k == 0 ? d2_[k] : std::max(hi, d2_[k]);
  }
  const double inv_range = hi > lo ? 1.0 / (hi - lo) : 0.0;
  for (int k = 0; k < count; ++k) {
    cost[k] = params_.goal_weight * (d2_[k] - lo) * inv_range +
              params_.obstacle_weight * ObstacleAt(states[k].x_m, states[k].y_m);
  }
}

std::unique_ptr<RolloutCost> GoalObstacleCost::Clone() const {
  return std::make_unique<GoalObstacleCost>(*this);
}

}  // namespace vb::controllers
