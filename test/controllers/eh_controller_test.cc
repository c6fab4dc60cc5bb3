// EH baseline on hand-made terrains with known answers: the region at the vehicle's height wins
// (ties: the flatter), contour following on a side slope, the steering blend and its sign, the
// original's left-lying regions, and the 0.4 m sampling against the original's 0.1 m one on a
// benchmark world.
#include "vb/controllers/eh_controller.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "io/task_io.h"
#include "support/worlds.h"
#include "vb/engine/rng.h"
#include "vb/terrain/gt_maps.h"

namespace vb::controllers {
namespace {

using test::WorldOf;

EpisodeContext ContextOf(const terrain::GroundTruthMaps& maps) {
  EpisodeContext c;
  c.maps = &maps;
  c.control_period_s = 0.005;
  return c;
}

TEST(EhControllerTest, PicksTheRegionAtTheVehiclesHeightAndTheFlatterOnATie) {
  // Flat ground with 2 m boxes over the regions ahead-left and ahead (vehicle at the origin
  // heading east; region centres (6.4, 12.8), (6.4, 6.4), (6.4, 0), (6.4, -6.4), (6.4, -12.8)).
  const terrain::TaskSpec task = WorldOf([](double x, double y) {
    return (x > 4.5 && x < 12.0 && y > -3.0) ? 2.0 : 0.0;
  });
  const terrain::GroundTruthMaps maps(task);
  EhController eh;
  eh.Reset(ContextOf(maps));
  const EhDecision d = eh.Decide(Vec2(0.0, 0.0), 0.0);
  EXPECT_NEAR(d.under_mean_m, 0.0, 1e-12);
  EXPECT_GT(d.mean_m[0], 1.2);
  EXPECT_GT(d.mean_m[1], 1.2);
  EXPECT_GT(d.mean_m[2], 0.5);
  // regions 3 and 4 are both at height 0 and flat: a tie, broken towards the first
  EXPECT_EQ(d.chosen, 3);
  EXPECT_NEAR(d.target_m.x(), 6.4, 1e-12);
  EXPECT_NEAR(d.target_m.y(), -6.4, 1e-12);
  EXPECT_NEAR(d.terrain_error_rad, -kPi / 4, 1e-12);

  // Now region 3 is about as high on average but rough (a +-0.5 m zigzag): the flat region 4
  // wins (on the mean difference if the zigzag's samples do not average to exactly 0, else on
  // the variance).
  const terrain::TaskSpec rough = WorldOf([](double x, double y) {
    if (x > 4.5 && x < 12.0 && y > -3.0) return 2.0;
    if (x > 4.5 && x < 12.0 && y > -9.0) {
      return (static_cast<int>(std::floor(x)) % 2 == 0) ? 0.5 : -0.5;
    }
    return 0.0;
  });
  const terrain::GroundTruthMaps rough_maps(rough);
  eh.Reset(ContextOf(rough_maps));
  const EhDecision e = eh.Decide(Vec2(0.0, 0.0), 0.0);
  EXPECT_GT(e.var_m2[3], 0.01);
  EXPECT_NEAR(e.var_m2[4], 0.0, 1e-12);
  EXPECT_EQ(e.chosen, 4);
}

TEST(EhControllerTest, ChoiceRuleIsMeanDifferenceThenVariance) {
  const double mean[5] = {1.0, 0.3, -0.3, 0.3, 2.0};
  const double var[5] = {0.0, 0.2, 0.3, 0.2, 0.0};
  EXPECT_EQ(EhChooseRegion(mean, var, 5, 0.0), 1);    // |0.3| three ways: 1 and 3 tie on var too
  EXPECT_EQ(EhChooseRegion(mean, var, 5, 1.9), 4);
  const double var2[5] = {0.0, 0.2, 0.05, 0.2, 0.0};
  EXPECT_EQ(EhChooseRegion(mean, var2, 5, 0.0), 2);   // the flattest of the three at |0.3|
  EXPECT_EQ(EhChooseRegion(mean, var2, 5, 0.29), 1);  // nearer in mean beats flatter
}

TEST(EhControllerTest, FollowsTheContourOfASideSlope) {
  // z = 0.3 y (rising to the north). Heading east the region straight ahead is at the vehicle's
  // height; heading north-east the one ahead-right is (6.4 ahead and 6.4 right of a 45 deg
  // heading is due east); heading south-east the one ahead-left.
  const terrain::TaskSpec task = WorldOf([](double, double y) { return 0.3 * y; });
  const terrain::GroundTruthMaps maps(task);
  EhController eh;
  eh.Reset(ContextOf(maps));
  EXPECT_EQ(eh.Decide(Vec2(0, 0), 0.0).chosen, 2);
  EXPECT_EQ(eh.Decide(Vec2(0, 0), kPi / 4).chosen, 3);
  EXPECT_EQ(eh.Decide(Vec2(0, 0), -kPi / 4).chosen, 1);
  const EhDecision d = eh.Decide(Vec2(0, 0), kPi / 4);
  EXPECT_NEAR(d.mean_m[3], d.under_mean_m, 1e-9);   // exactly level on a plane
}

TEST(EhControllerTest, SteeringBlendsTerrainAndPathErrorsWithThePidRateLimit) {
  const terrain::TaskSpec task = WorldOf([](double, double y) { return 0.3 * y; });
  const terrain::GroundTruthMaps maps(task);
  EhController eh;
  eh.Reset(ContextOf(maps));
  Observation o;
  o.rpy.yaw_rad = kPi / 4;        // terrain target ahead-right: error -45 deg
  o.heading_error_rad = 0.1;      // path slightly left
  o.forward_speed_mps = 4.0;
  // 0.2 * (-pi/4) + 0.8 * 0.1 = -0.077: the first step is rate-limited to -0.05
  Command c = eh.Update(o);
  EXPECT_DOUBLE_EQ(c.steering, -0.05);
  c = eh.Update(o);
  EXPECT_NEAR(c.steering, 0.2 * (-kPi / 4) + 0.8 * 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(c.throttle, 0.0);   // at the target speed: neither throttle nor brake
}

TEST(EhControllerTest, OriginalRegionsLieToTheLeft) {
  // z = x: the intent's regions are all 6.4 m ahead (mean 6.4); the original's sit 6.4 m to the
  // left at 12.8, 6.4, 0, -6.4, -12.8 m ahead.
  const terrain::TaskSpec task = WorldOf([](double x, double) { return x; });
  const terrain::GroundTruthMaps maps(task);
  EhController intent;
  intent.Reset(ContextOf(maps));
  EhParams p;
  p.original_left_regions = true;
  EhController original(p);
  original.Reset(ContextOf(maps));
  const EhDecision a = intent.Decide(Vec2(0, 0), 0.0);
  const EhDecision b = original.Decide(Vec2(0, 0), 0.0);
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR(a.mean_m[i], 6.4, 1e-9) << i;
    EXPECT_NEAR(b.mean_m[i], (2 - i) * 6.4, 1e-9) << i;
  }
  EXPECT_EQ(b.chosen, 2);   // the one level with the vehicle: aimed at as if it were ahead
  EXPECT_NEAR(b.terrain_error_rad, 0.0, 1e-12);
}

TEST(EhControllerTest, CoarseSamplingMatchesTheOriginalsOnABenchmarkWorld) {
  // The original averages 64 x 64 samples of a 0.1 m map; vb 16 x 16 (0.4 m). On a high-
  // elevation world (env008) at 40 poses the region means agree to 2 cm and the variances to
  // 5 % of the variance + 1 cm^2.
  const terrain::TaskSpec task = io::LoadTask(std::string(VB_SOURCE_DIR) + "/tasks/env008.yaml");
  const terrain::GroundTruthMaps maps(task);
  EhController coarse;
  coarse.Reset(ContextOf(maps));
  EhParams p;
  p.sample_spacing_m = 0.1;
  EhController fine(p);
  fine.Reset(ContextOf(maps));
  Rng rng(3);
  for (int i = 0; i < 40; ++i) {
    const Vec2 pos(rng.Uniform(-40, 40), rng.Uniform(-40, 40));
    const double yaw = rng.Uniform(-kPi, kPi);
    const EhDecision a = coarse.Decide(pos, yaw);
    const EhDecision b = fine.Decide(pos, yaw);
    EXPECT_NEAR(a.under_mean_m, b.under_mean_m, 0.02);
    for (int r = 0; r < 5; ++r) {
      EXPECT_NEAR(a.mean_m[r], b.mean_m[r], 0.02) << i << " " << r;
      EXPECT_NEAR(a.var_m2[r], b.var_m2[r], 0.05 * b.var_m2[r] + 1e-4) << i << " " << r;
    }
  }
}

}  // namespace
}  // namespace vb::controllers
