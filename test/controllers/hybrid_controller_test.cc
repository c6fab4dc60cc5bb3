// The hybrid baselines' controllers (hybrid_controller.h) with the committed weights: registry
// and errors, determinism, the planners steer towards the local goal and around an obstacle,
// MPPI-6's rate limit, and the cost terms (hybrid_cost.h) on hand-made batches.
#include "vb/controllers/hybrid_controller.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/model_store.h"
#include "support/worlds.h"
#include "vb/engine/error.h"
#include "vb/terrain/gt_maps.h"

// Heap allocations of this test binary so far (counted in mppi_core_test.cc).
long VbTestAllocations();

namespace vb::controllers {
namespace {

const io::DataDirModelStore& Store() {
  static const io::DataDirModelStore store(std::string(VB_SOURCE_DIR) + "/data");
  return store;
}

EpisodeContext ContextOf(const terrain::TaskSpec& task, const terrain::GroundTruthMaps& maps,
                         uint64_t seed = 7) {
  EpisodeContext c;
  c.task = &task;
  c.maps = &maps;
  c.control_period_s = 0.005;
  c.seed = seed;
  return c;
}

Observation ObsAt(double t, const Vec2& goal) {
  Observation o;
  o.time_s = t;
  o.position_W = Vec3(0.0, 0.0, 0.0);
  o.local_goal_m = goal;
  o.forward_speed_mps = 4.0;
  return o;
}

TEST(HybridControllerTest, RegistryNamesAndNeedsAStore) {
  for (const char* name : {"wmvct", "mppi6", "tal", "tnt"}) {
    const std::vector<std::string> names = ControllerNames();
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
    EXPECT_THROW(MakeController(name), InputError) << name;
    std::unique_ptr<Controller> c = MakeController(name, &Store());
    ASSERT_NE(c, nullptr) << name;
    EXPECT_EQ(c->name(), name);
  }
}

TEST(HybridControllerTest, SteersTowardsTheGoalDeterministically) {
  const terrain::TaskSpec task = test::PlaneTask(128.0);
  const terrain::GroundTruthMaps maps(task);
  for (const char* name : {"wmvct", "mppi6", "tal", "tnt"}) {
    std::unique_ptr<Controller> a = MakeController(name, &Store());
    std::unique_ptr<Controller> b = MakeController(name, &Store());
    a->Reset(ContextOf(task, maps));
    b->Reset(ContextOf(task, maps));
    double steer_a = 0.0;
    // goal 10 m ahead, 6 m to the left; 0.4 s of control (MPPI-6's rate limit needs time)
    for (int i = 0; i < 80; ++i) {
      const Observation o = ObsAt(0.005 * i, Vec2(8.0, 6.0));
      steer_a = a->Update(o).steering;
      EXPECT_EQ(steer_a, b->Update(o).steering) << name << " step " << i;
    }
    EXPECT_GT(steer_a, 0.1) << name;   // + = left
    std::unique_ptr<Controller> c = a->Clone();
    const Observation o = ObsAt(0.4, Vec2(8.0, 6.0));
    EXPECT_EQ(c->Update(o).steering, a->Update(o).steering) << name;
  }
}

TEST(HybridControllerTest, AnUpdateAllocatesNothingAfterTheFirst) {
  // the hot-loop rule: the scratch (batch matrices, terrain features, TNT's map) is sized by the
  // first update; the later ones, rollouts and network evaluations included, allocate nothing
  const terrain::TaskSpec task = test::PlaneTask(128.0);
  const terrain::GroundTruthMaps maps(task);
  for (const char* name : {"wmvct", "mppi6", "tal", "tnt"}) {
    std::unique_ptr<Controller> c = MakeController(name, &Store());
    c->Reset(ContextOf(task, maps));
    c->Update(ObsAt(0.0, Vec2(8.0, 6.0)));
    const long before = VbTestAllocations();
    for (int i = 1; i <= 3; ++i) c->Update(ObsAt(0.05 * i, Vec2(8.0, 6.0)));
    EXPECT_EQ(VbTestAllocations(), before) << name;
  }
}

TEST(HybridControllerTest, Mppi6RateLimitsItsSteering) {
  const terrain::TaskSpec task = test::PlaneTask(128.0);
  const terrain::GroundTruthMaps maps(task);
  std::unique_ptr<Controller> c = MakeController("mppi6", &Store());
  c->Reset(ContextOf(task, maps));
  double prev = 0.0;
  for (int i = 0; i < 40; ++i) {
    const double s = c->Update(ObsAt(0.005 * i, Vec2(0.0, 10.0))).steering;
    EXPECT_LE(std::abs(s - prev), 0.05 + 1e-12);
    prev = s;
  }
}

TEST(HybridCostTest, TermsOnAHandMadeBatch) {
  // three states: at the goal, 3 m off, 6 m off; with attitude (0.05, 0.2, 0.4) rad roll
  HybridCostParams p;
  p.goal_weight = 10.0;
  p.roll_weight = 2.0;
  HybridCost cost(p, nullptr, 128.0, 128.0, nullptr);
  cost.set_goal(Vec2(10.0, 0.0), Vec2(0.0, 0.0));
  PlannerState s[3];
  s[0].x_m = 10.0;
  s[1].x_m = 7.0;
  s[2].x_m = 4.0;
  s[0].roll_rad = 0.05;
  s[1].roll_rad = -0.2;
  s[2].roll_rad = 0.4;
  MppiControl u[3] = {};
  double c[3];
  cost.Evaluate(0, s, u, 3, c);
  // d^2 = 0, 9, 36 -> 0, 0.25, 1; |roll| 0.05 (< 0.17: 0), 0.2 -> (0.2-0.05)/0.35, 0.4 -> 1
  EXPECT_NEAR(c[0], 0.0, 1e-12);
  EXPECT_NEAR(c[1], 2.5 + 2.0 * 0.15 / 0.35, 1e-12);
  EXPECT_NEAR(c[2], 10.0 + 2.0, 1e-12);
  // MPPI-6: raw d^2, |bearing - yaw| / d^2(start), raw |roll| (the original: signed)
  HybridCostParams m;
  m.goal_raw_weight = 1.0;
  m.heading_weight = 30.0;
  m.roll_weight = 1.0;
  m.attitude_normalised = false;
  HybridCost c6(m, nullptr, 128.0, 128.0, nullptr);
  c6.set_goal(Vec2(10.0, 0.0), Vec2(0.0, 0.0));
  s[1].yaw_rad = 0.5;
  c6.Evaluate(0, s, u, 3, c);
  EXPECT_NEAR(c[1], 9.0 + 30.0 * 0.5 / 100.0 + 0.2, 1e-12);
  m.signed_attitude = true;
  HybridCost signed_cost(m, nullptr, 128.0, 128.0, nullptr);
  signed_cost.set_goal(Vec2(10.0, 0.0), Vec2(0.0, 0.0));
  signed_cost.Evaluate(0, s, u, 3, c);
  EXPECT_NEAR(c[1], 9.0 + 30.0 * 0.5 / 100.0 - 0.2, 1e-12);   // the original rewards roll < 0
}

}  // namespace
}  // namespace vb::controllers
