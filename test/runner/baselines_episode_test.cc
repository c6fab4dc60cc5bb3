// The classical baselines with the real HMMWV on a synthetic world: a rock on the straight line
// between start and goal; EH and MPPI reach the goal around it without touching it, and MPPI's
// sampled trial reruns bit for bit.
#include <gtest/gtest.h>

#include "support/worlds.h"
#include "vb/engine/runner/episode.h"
#include "vb/engine/runner/result_digest.h"

namespace vb::runner {
namespace {

terrain::TaskSpec RockOnTheLine() {
  terrain::TaskSpec t = test::PlaneTask(128.0, 0.0, 0.0, 0.8, terrain::SurfaceClass::kDirt);
  terrain::RockSpec rock;   // 4.4 m box at the midpoint of the pair (-20, 0) -> (20, 0)
  t.rocks.push_back(rock);
  return t;
}

TEST(BaselinesEpisodeTest, EhAndMppiGoAroundARock) {
  const terrain::TaskSpec task = RockOnTheLine();
  for (const char* system : {"eh", "mppi", "mppi_original", "eh_original"}) {
    TrialSpec spec;
    spec.system = system;
    const TrialResult r = RunTrial(task, test::Hmmwv(), spec);
    EXPECT_EQ(r.status, TrialStatus::kSuccess) << system << ": " << r.message;
    EXPECT_EQ(r.obstacle_contacts, 0) << system;
    // around, not through: somewhere beside the rock the reference point is > 2.2 m off the line
    double offset_at_rock = 0.0;
    for (const TrajectorySample& s : r.trajectory) {
      if (std::abs(s.position_W.x()) < 1.0) {
        offset_at_rock = std::max(offset_at_rock, std::abs(s.position_W.y()));
      }
    }
    EXPECT_GT(offset_at_rock, 2.2 + 1.1) << system;   // half the rock + half the vehicle width
    EXPECT_LT(r.traversal_time_s, 20.0) << system;
  }
}

// pid_original plans as the original's code (terrain/original_planner.h): around the rock on a
// smoothed line of its own, not vb's optimal A* path.
TEST(BaselinesEpisodeTest, PidOriginalGoesAroundARockOnTheOriginalsPath) {
  const terrain::TaskSpec task = RockOnTheLine();
  TrialSpec spec;
  spec.system = "pid_original";
  const TrialResult r = RunTrial(task, test::Hmmwv(), spec);
  EXPECT_EQ(r.status, TrialStatus::kSuccess) << r.message;
  EXPECT_EQ(r.obstacle_contacts, 0);
  spec.system = "pid";
  EXPECT_NE(TrialDigest(RunTrial(task, test::Hmmwv(), spec)), TrialDigest(r));
}

TEST(BaselinesEpisodeTest, MppiTrialsRerunBitIdentically) {
  const terrain::TaskSpec task = RockOnTheLine();
  TrialSpec spec;
  spec.system = "mppi";
  spec.seed = 5;
  EpisodeRules rules;
  rules.time_limit_s = 6.0;
  const TrialResult a = RunTrial(task, test::Hmmwv(), spec, rules);
  const TrialResult b = RunTrial(task, test::Hmmwv(), spec, rules);
  EXPECT_EQ(TrialDigest(a), TrialDigest(b));
  spec.seed = 6;
  EXPECT_NE(TrialDigest(RunTrial(task, test::Hmmwv(), spec, rules)), TrialDigest(a));
}

}  // namespace
}  // namespace vb::runner
