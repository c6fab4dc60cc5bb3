// The two rule sets an episode can decide success and stuck by (docs/task_format.md "Episode
// rules"): vb's own (the spec's, the default) and the original Verti-Bench runners' (to measure
// how much of a difference in results comes from the rules alone). Rollover at the end, timeout,
// out_of_bounds and sim_error are the same under both.
//
//   vb           success: planar distance of the reference point to the goal <= 10 m x scale;
//                stuck: moved <= 1 m x scale (planar) over the last 10 s
//   verti_bench  success: 3-D distance of the reference point to the goal marker, 2 m x scale
//                above the terrain at the goal, < 8 m x scale;
//                stuck: every step of the last 10 s moved less than 2 m/s x scale x step
//                (3-D; the original's 0.01 m per 5 ms step), so 10 s of slow climbing fails
//
// The original scales neither its 8 m nor its 0.01 m (reference quirk 8); vb scales both with the
// task's world scale like its own rules, so at scale 1 (tasks/, the original worlds) they are
// the original's numbers exactly and a 1/10 world keeps the same geometry.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <string_view>

#include "vb/engine/error.h"
#include "vb/engine/types.h"

namespace vb::runner {

enum class RuleSet { kVb, kVertiBench };

// The names are inline so that the batch library (index, report) reads them without the runner.
// "vb", "verti_bench".
inline std::string_view RuleSetName(RuleSet rules) {
  return rules == RuleSet::kVertiBench ? "verti_bench" : "vb";
}
// The rule set of a name, nullopt for anything else.
inline std::optional<RuleSet> RuleSetFromName(std::string_view name) {
  if (name == "vb") return RuleSet::kVb;
  if (name == "verti_bench") return RuleSet::kVertiBench;
  return std::nullopt;
}
// "vb, verti_bench" for messages and --help.
inline std::string RuleSetNames() { return "vb, verti_bench"; }
// What is wrong with a name RuleSetFromName refuses (every reader's message).
inline std::string UnknownRuleSet(const std::string& text) {
  return "unknown rule set '" + text + "'; valid: " + RuleSetNames();
}
// The rule set of `text`; InputError naming `key` (a CLI flag, config key or column), and the
// file and line it came from when there is one.
inline RuleSet ParseRuleSet(const std::string& key, const std::string& text,
                            const std::string& file = "", int line = 0) {
  const std::optional<RuleSet> r = RuleSetFromName(text);
  if (!r) throw InputError(file, line, key, UnknownRuleSet(text));
  return *r;
}

// The original's numbers at scale 1 (reference_verti_bench.md §6.1).
constexpr double kVertiBenchGoalRadius_m = 8.0;     // 3-D, to the goal marker
constexpr double kVertiBenchMarkerHeight_m = 2.0;   // goal marker above the terrain at the goal
constexpr double kVertiBenchSlowSpeed_mps = 2.0;    // 0.01 m per 5 ms step

// The radius of the circle around the goal that pictures draw (vb_report's top-down maps, the
// viewer): vb_radius_m x scale under vb's rules (planar, exact); under verti_bench the section
// of the 8 m sphere around the marker at the goal's ground height, sqrt(8² − 2²) x scale =
// 7.75 m x scale (the reference point rides ~0.5-1 m above the ground, so on level ground the
// trial ends up to ~0.1 m x scale further out; on slopes the section is not a circle).
inline double GoalCircleRadius_m(RuleSet rules, double scale, double vb_radius_m) {
  if (rules == RuleSet::kVb) return vb_radius_m * scale;
  return std::sqrt(kVertiBenchGoalRadius_m * kVertiBenchGoalRadius_m -
                   kVertiBenchMarkerHeight_m * kVertiBenchMarkerHeight_m) * scale;
}

// The success test of one trial.
struct GoalRule {
  RuleSet rules = RuleSet::kVb;
  Vec2 goal_m = Vec2::Zero();
  double radius_m = 10.0;    // vb: planar; verti_bench: 3-D to the marker
  double marker_z_m = 0.0;   // verti_bench only: the marker's height in W

  // vb_radius_m: vb's goal radius at scale 1 (EpisodeRules::goal_radius_m); goal_ground_z_m: the
  // terrain height at the goal.
  static GoalRule Make(RuleSet rules, const Vec2& goal_m, double goal_ground_z_m, double scale,
                       double vb_radius_m);
  // The distance the rule compares with radius_m.
  double Distance(const Vec3& position_W) const;
  bool Reached(const Vec3& position_W) const;
};

// The original's stuck counter: how many consecutive steps, up to the newest, moved (3-D) less
// than the threshold. O(1) per step, no allocation, copyable (part of an episode snapshot).
class SlowStepCounter {
 public:
  SlowStepCounter() = default;
  // threshold_m: the displacement per step below which a step is slow.
  explicit SlowStepCounter(double threshold_m) : threshold_m_(threshold_m) {}
  void Start(const Vec3& position_W) {
    last_ = position_W;
    slow_steps_ = 0;
  }
  void Push(const Vec3& position_W) {
    slow_steps_ = (position_W - last_).norm() < threshold_m_ ? slow_steps_ + 1 : 0;
    last_ = position_W;
  }
  long slow_steps() const { return slow_steps_; }
  double threshold_m() const { return threshold_m_; }

 private:
  double threshold_m_ = 0.0;
  Vec3 last_ = Vec3::Zero();
  long slow_steps_ = 0;
};

// The per-step displacement below which a step is slow under verti_bench.
double VertiBenchSlowStep_m(double step_s, double scale);

}  // namespace vb::runner
