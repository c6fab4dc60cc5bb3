// The success and stuck rules of the two rule sets (outcome_rules.h).
#include "vb/engine/runner/outcome_rules.h"

namespace vb::runner {

GoalRule GoalRule::Make(RuleSet rules, const Vec2& goal_m, double goal_ground_z_m, double scale,
                        double vb_radius_m) {
  GoalRule g;
  g.rules = rules;
  g.goal_m = goal_m;
  if (rules == RuleSet::kVb) {
    g.radius_m = vb_radius_m * scale;
  } else {
    g.radius_m = kVertiBenchGoalRadius_m * scale;
    g.marker_z_m = goal_ground_z_m + kVertiBenchMarkerHeight_m * scale;
  }
  return g;
}

double GoalRule::Distance(const Vec3& p) const {
  if (rules == RuleSet::kVb) return (goal_m - p.head<2>()).norm();
  return (Vec3(goal_m.x(), goal_m.y(), marker_z_m) - p).norm();
}

bool GoalRule::Reached(const Vec3& p) const {
  // vb: within the radius (<=); the original: strictly inside (<).
  const double d = Distance(p);
  return rules == RuleSet::kVb ? d <= radius_m : d < radius_m;
}

double VertiBenchSlowStep_m(double step_s, double scale) {
  return kVertiBenchSlowSpeed_mps * scale * step_s;
}

}  // namespace vb::runner
