// Kinematic bicycle steps (bicycle_model.h): heading change ds / L * tan(wheel angle), the step
// taken along the heading at mid-step (exact to second order in the heading change, which is at
// most 0.11 rad per step with the original's numbers), or along the original's unscaled angle.
#include "vb/controllers/bicycle_model.h"

#include <cmath>

namespace vb::controllers {

namespace {
// The original's normalisation constants (reference §7.3): the heading change of a step is
// 0.0649 times its normalised angle dtheta' = v' / 0.32 * tan(delta').
constexpr double kOriginalYawScale = 0.0649;
}  // namespace

BicycleModel::BicycleModel(const BicycleModelParams& params) : params_(params) {}

void BicycleModel::Step(int /*step*/, const PlannerState* states, const MppiControl* controls,
                        int count, PlannerState* next) const {
  const double step_per_speed = params_.step_length_per_speed_m * params_.scale;
  const double wheelbase = params_.wheelbase_m * params_.scale;
  for (int k = 0; k < count; ++k) {
    const PlannerState& s = states[k];
    const double ds = step_per_speed * controls[k][kMppiSpeed];
    // Trigonometry in single precision: it is most of a rollout's cost (16,000 steps per MPPI
    // update) and float's 1e-7 relative error is micrometres on a 10 m horizon.
    const double dyaw =
        ds / wheelbase *
        std::tan(static_cast<float>(params_.wheel_angle_per_steer_rad * controls[k][kMppiSteer]));
    const double direction =
        params_.original_step_direction ? s.yaw_rad + dyaw / kOriginalYawScale
                                        : s.yaw_rad + 0.5 * dyaw;
    const float direction_f = static_cast<float>(direction);   // |direction| < 10 rad here
    PlannerState& n = next[k];
    n = s;
    n.x_m = s.x_m + ds * std::cos(direction_f);
    n.y_m = s.y_m + ds * std::sin(direction_f);
    n.yaw_rad = s.yaw_rad + dyaw;
  }
}

std::unique_ptr<RolloutModel> BicycleModel::Clone() const {
  return std::make_unique<BicycleModel>(*this);
}

}  // namespace vb::controllers
