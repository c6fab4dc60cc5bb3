// The two outcome rule sets (outcome_rules.h): the rule functions on constructed positions, then
// real HMMWV episodes on flat ground where vb's rules and the original's (verti_bench) disagree:
// a slow drive, a stop 9 m from the goal, and the goal marker's 2 m height.
#include "vb/engine/runner/outcome_rules.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "support/worlds.h"
#include "vb/engine/error.h"
#include "vb/engine/runner/episode.h"
#include "vb/engine/runner/result_digest.h"

namespace vb::runner {
namespace {

// --- the rule functions -------------------------------------------------------------------

TEST(OutcomeRulesTest, NamesRoundTripAndBadNamesAreInputErrors) {
  for (RuleSet r : {RuleSet::kVb, RuleSet::kVertiBench}) {
    EXPECT_EQ(RuleSetFromName(RuleSetName(r)), r);
  }
  EXPECT_EQ(RuleSetName(RuleSet::kVertiBench), "verti_bench");
  EXPECT_FALSE(RuleSetFromName("Verti_Bench").has_value());
  EXPECT_FALSE(RuleSetFromName("").has_value());
  EXPECT_EQ(ParseRuleSet("--rules", "vb"), RuleSet::kVb);
  try {
    ParseRuleSet("--rules", "paper");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "--rules");
    EXPECT_NE(std::string(e.what()).find("'paper'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("vb, verti_bench"), std::string::npos) << e.what();
  }
}

// vb: planar distance <= 10 m x scale. verti_bench: 3-D distance to the marker 2 m x scale above
// the terrain at the goal < 8 m x scale.
TEST(OutcomeRulesTest, GoalRulesOnConstructedPositions) {
  const Vec2 goal(20.0, 5.0);
  const double ground = 3.0;   // terrain height at the goal
  const GoalRule vb = GoalRule::Make(RuleSet::kVb, goal, ground, 1.0, 10.0);
  const GoalRule vt = GoalRule::Make(RuleSet::kVertiBench, goal, ground, 1.0, 10.0);
  EXPECT_DOUBLE_EQ(vt.marker_z_m, 5.0);
  // The HMMWV's reference point (wheel-centre height) stands ~0.45 m above the ground.
  auto at = [&](double planar_m, double above_ground_m) {
    return Vec3(goal.x() - planar_m, goal.y(), ground + above_ground_m);
  };
  // Stopped 9 m away: a success only under vb.
  EXPECT_TRUE(vb.Reached(at(9.0, 0.45)));
  EXPECT_FALSE(vt.Reached(at(9.0, 0.45)));
  EXPECT_DOUBLE_EQ(vb.Distance(at(9.0, 0.45)), 9.0);
  // 7.9 m away with the chassis low: the marker is 1.55 m higher, 3-D sqrt(7.9^2 + 1.55^2) =
  // 8.05 m: not yet; with the chassis 1 m up (a lifted vehicle, or one on a crest) 7.97 m: yes.
  EXPECT_NEAR(vt.Distance(at(7.9, 0.45)), std::hypot(7.9, 1.55), 1e-12);
  EXPECT_FALSE(vt.Reached(at(7.9, 0.45)));
  EXPECT_TRUE(vt.Reached(at(7.9, 1.0)));
  EXPECT_TRUE(vt.Reached(at(7.5, 0.45)));
  // 3-D: straight below the marker, exactly 8 m is not inside, 7.99 m is.
  EXPECT_FALSE(vt.Reached(Vec3(goal.x(), goal.y(), 5.0 - 8.0)));   // strictly inside only
  EXPECT_TRUE(vt.Reached(Vec3(goal.x(), goal.y(), 5.0 - 7.99)));
  EXPECT_TRUE(vb.Reached(Vec3(goal.x() + 10.0, goal.y(), -50.0)));  // vb: planar, <=
  // Both scale with the world: a 1/10 world's marker is 0.2 m up, its radius 0.8 m.
  const GoalRule small = GoalRule::Make(RuleSet::kVertiBench, goal, ground, 0.1, 10.0);
  EXPECT_DOUBLE_EQ(small.radius_m, 0.8);
  EXPECT_DOUBLE_EQ(small.marker_z_m, 3.2);
  EXPECT_FALSE(small.Reached(at(0.79, 0.045)));
  EXPECT_TRUE(small.Reached(at(0.75, 0.045)));
  EXPECT_DOUBLE_EQ(GoalRule::Make(RuleSet::kVb, goal, ground, 0.1, 10.0).radius_m, 1.0);
}

// The circle pictures draw: vb's planar radius; the original's 8 m sphere around the marker 2 m up,
// cut at the goal's ground height (sqrt(60) = 7.746 m), both scaled with the world.
TEST(OutcomeRulesTest, GoalCircleRadiusOfEachRuleSet) {
  EXPECT_DOUBLE_EQ(GoalCircleRadius_m(RuleSet::kVb, 1.0, 10.0), 10.0);
  EXPECT_DOUBLE_EQ(GoalCircleRadius_m(RuleSet::kVb, 0.1, 10.0), 1.0);
  EXPECT_NEAR(GoalCircleRadius_m(RuleSet::kVertiBench, 1.0, 10.0), 7.7460, 1e-4);
  EXPECT_NEAR(GoalCircleRadius_m(RuleSet::kVertiBench, 0.1, 10.0), 0.77460, 1e-5);
  // A point on the circle at ground height is exactly 8 m from the marker.
  const GoalRule vt = GoalRule::Make(RuleSet::kVertiBench, Vec2(0.0, 0.0), 3.0, 1.0, 10.0);
  const double r = GoalCircleRadius_m(RuleSet::kVertiBench, 1.0, 10.0);
  EXPECT_NEAR(vt.Distance(Vec3(r, 0.0, 3.0)), 8.0, 1e-12);
}

// The original's counter: 0.01 m per 5 ms step (2 m/s) at scale 1; a step at 1.5 m/s is slow, one
// at 2.5 m/s resets it; 3-D, so a vertical creep counts as movement.
TEST(OutcomeRulesTest, SlowStepCounterCountsConsecutiveSlowSteps) {
  const double dt = 0.005;
  EXPECT_EQ(VertiBenchSlowStep_m(dt, 1.0), 0.01);
  EXPECT_DOUBLE_EQ(VertiBenchSlowStep_m(dt, 0.1), 0.001);
  SlowStepCounter c(VertiBenchSlowStep_m(dt, 1.0));
  Vec3 p(1.0, 2.0, 3.0);
  c.Start(p);
  for (int i = 0; i < 2000; ++i) {
    p.x() += 1.5 * dt;
    c.Push(p);
  }
  EXPECT_EQ(c.slow_steps(), 2000);   // 10 s below 2 m/s
  p.x() += 2.5 * dt;
  c.Push(p);
  EXPECT_EQ(c.slow_steps(), 0);
  // 1.2 m/s forward and 1.6 m/s up: 2.0 m/s in 3-D is not slow (strictly below only) ...
  c.Push(p + Vec3(1.2 * dt, 0.0, 1.6 * dt) * 1.0001);
  EXPECT_EQ(c.slow_steps(), 0);
  // ... standing still is.
  for (int i = 0; i < 3; ++i) c.Push(p);
  EXPECT_EQ(c.slow_steps(), 2);   // the first of the three moves back from the 3-D step
}

// --- real episodes ------------------------------------------------------------------------

TrialResult RunPid(const terrain::TaskSpec& task, RuleSet rules_set, double speed_mps,
                double time_limit_s = 60.0) {
  EpisodeRules rules;
  rules.rule_set = rules_set;
  rules.target_speed_mps = speed_mps;
  rules.time_limit_s = time_limit_s;
  return RunTrial(task, test::Hmmwv(), TrialSpec(), rules);
}

// PID creeping at 1.5 m/s on flat ground, 40 m to the goal: vb's rules see it move 15 m per
// 10 s and let it arrive; the original's count every step below 2 m/s and call it stuck after
// 10 s of it, far from the goal.
TEST(OutcomeRulesEpisodeTest, ACreepAtOneAndAHalfMetresPerSecondIsStuckOnlyUnderVertiBench) {
  const terrain::TaskSpec task = test::PlaneTask();
  const TrialResult vb = RunPid(task, RuleSet::kVb, 1.5);
  EXPECT_EQ(vb.status, TrialStatus::kSuccess) << vb.message;
  EXPECT_EQ(vb.rule_set, RuleSet::kVb);
  EXPECT_GT(vb.traversal_time_s, 20.0);   // 30 m at <= 1.5 m/s
  const TrialResult vt = RunPid(task, RuleSet::kVertiBench, 1.5);
  EXPECT_EQ(vt.status, TrialStatus::kStuck) << vt.message;
  EXPECT_EQ(vt.rule_set, RuleSet::kVertiBench);
  EXPECT_NE(vt.message.find("below 2 m/s"), std::string::npos) << vt.message;
  // Ends 10 s after the last fast step: the landing of the 0.5 m start drop (~0.3 s).
  EXPECT_GT(vt.sim_time_s, 10.0);
  EXPECT_LT(vt.sim_time_s, 11.0);
  EXPECT_GT(vt.final_goal_distance_m, 20.0);
  EXPECT_GT(vt.path_length_m, 10.0);   // it was moving all the time
  // The same PID at 4 m/s is a success under either rules.
  EXPECT_EQ(RunPid(task, RuleSet::kVertiBench, 4.0, 30.0).status, TrialStatus::kSuccess);
}

// Stopped 9 m (planar) from the goal: vb's 10 m radius holds it at once; the original's 8 m to
// the marker does not, and a vehicle that does not move is stuck after 10 s.
TEST(OutcomeRulesEpisodeTest, AStopNineMetresFromTheGoalIsASuccessOnlyUnderVb) {
  terrain::TaskSpec task = test::PlaneTask();
  task.pairs[0].start_m = Vec2(11.0, 0.0);   // goal at (20, 0)
  for (RuleSet set : {RuleSet::kVb, RuleSet::kVertiBench}) {
    EpisodeRules rules;
    rules.rule_set = set;
    rules.time_limit_s = 15.0;
    Episode episode(task, test::Hmmwv(), rules);
    episode.Reset(TrialSpec());
    while (!episode.Done()) episode.Step({0.0, 0.0, 1.0});   // brakes on
    const TrialResult r = episode.Result();
    EXPECT_NEAR(r.final_goal_distance_m, 9.0, 0.05) << RuleSetName(set);
    if (set == RuleSet::kVb) {
      EXPECT_EQ(r.status, TrialStatus::kSuccess) << r.message;
      EXPECT_DOUBLE_EQ(r.sim_time_s, 0.005);   // the first step
    } else {
      EXPECT_EQ(r.status, TrialStatus::kStuck) << r.message;
      EXPECT_NEAR(r.sim_time_s, 10.3, 0.3);   // 10 s after the start drop landed
    }
  }
}

// PID at 4 m/s straight at the goal: under verti_bench the trial succeeds only once the 3-D
// distance to the marker 2 m above the ground is below 8 m, i.e. ~7.85 m planar for the
// HMMWV's reference point (wheel-centre height, ~0.45 m up): 7.9 m planar is not enough.
TEST(OutcomeRulesEpisodeTest, TheMarkersHeightDecidesTheRadius) {
  const terrain::TaskSpec task = test::PlaneTask();
  const TrialResult vb = RunPid(task, RuleSet::kVb, 4.0, 30.0);
  const TrialResult vt = RunPid(task, RuleSet::kVertiBench, 4.0, 30.0);
  ASSERT_EQ(vb.status, TrialStatus::kSuccess) << vb.message;
  ASSERT_EQ(vt.status, TrialStatus::kSuccess) << vt.message;
  EXPECT_NEAR(vb.final_goal_distance_m, 10.0, 0.03);
  EXPECT_LT(vt.final_goal_distance_m, 7.9);
  EXPECT_GT(vt.final_goal_distance_m, 7.75);
  const Vec3 end = vt.trajectory.back().position_W;
  const Vec3 before = vt.trajectory[vt.trajectory.size() - 2].position_W;
  const Vec3 marker(20.0, 0.0, 2.0);
  EXPECT_LT((marker - end).norm(), 8.0);
  EXPECT_GE((marker - before).norm(), 8.0);
  EXPECT_NEAR(end.z(), 0.45, 0.05);   // the reference point's height on flat ground
  // 2.15 m further at ~4 m/s: about half a second later.
  EXPECT_NEAR(vt.traversal_time_s - vb.traversal_time_s, 2.15 / 4.0, 0.05);
  EXPECT_NE(vt.message.find("goal marker"), std::string::npos) << vt.message;
}

// Digests of vb-rules results are those of before the option; verti_bench results differ.
TEST(OutcomeRulesEpisodeTest, TheRuleSetIsPartOfTheDigestOnlyWhenNotVb) {
  TrialResult r;
  const std::string base = TrialDigest(r);
  r.rule_set = RuleSet::kVertiBench;
  EXPECT_NE(TrialDigest(r), base);
  EpisodeRules bad;
  bad.rule_set = static_cast<RuleSet>(7);
  try {
    Episode e(test::PlaneTask(), test::Hmmwv(), bad);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "rule_set");
  }
}

}  // namespace
}  // namespace vb::runner
