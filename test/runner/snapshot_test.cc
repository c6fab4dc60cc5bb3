// Snapshot / restore of a running episode: branch at t = 10 s, run the branches with the same
// controller (cloned at the branch point), and compare bit for bit, on a rigid world with
// obstacle and body contacts and on a deformable world; restoring into the same episode and into
// another episode of the same task both work.
#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <string>

#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "vb/engine/runner/episode.h"
#include "support/worlds.h"
#include "vb/engine/runner/result_digest.h"

namespace vb::runner {
namespace {

struct World {
  terrain::TaskSpec task;
  vehicles::VehicleParams vehicle;
  std::optional<soil::SoilConfig> soil;
  explicit World(const std::string& name)
      : World(io::LoadTask(VB_SOURCE_DIR "/tasks/" + name + ".yaml")) {}
  explicit World(const terrain::TaskSpec& t)
      : task(t),
        vehicle(io::LoadVehicle(VB_SOURCE_DIR "/data/vehicles/hmmwv.yaml")),
        soil(io::LoadSoilIfNeeded(task, VB_SOURCE_DIR "/data/soils/verti_bench.yaml")) {}
  const soil::SoilConfig* soil_ptr() const { return soil ? &*soil : nullptr; }
};

// Steps `episode` with `controller` until it is done or reaches t_end.
void Drive(Episode* episode, controllers::Controller* controller, double t_end) {
  while (!episode->Done() && episode->time_s() < t_end - 1e-9) {
    episode->Step(controller->Update(episode->Observe()));
  }
}

// Branches a PID trial at t_branch and checks both continuations against the original.
void ExpectBranchesIdentical(const World& w, int pair, double t_branch) {
  TrialSpec spec;
  spec.pair_index = pair;
  Episode a(w.task, w.vehicle, EpisodeRules(), w.soil_ptr());
  std::unique_ptr<controllers::Controller> pid = controllers::MakeController("pid");
  a.SetObservationConfig(pid->observation_config());
  a.Reset(spec);
  pid->Reset(a.context());
  Drive(&a, pid.get(), t_branch);
  ASSERT_FALSE(a.Done()) << "the trial ended before the branch point";
  const EpisodeSnapshot snapshot = a.Snapshot();
  EXPECT_DOUBLE_EQ(snapshot.time_s(), t_branch);
  const std::unique_ptr<controllers::Controller> pid_at_branch = pid->Clone();

  Drive(&a, pid.get(), 60.0);
  const std::string original = TrialDigest(a.Result());

  // Restored into another episode of the same task (never reset: Restore builds its world).
  Episode b(w.task, w.vehicle, EpisodeRules(), w.soil_ptr());
  b.SetObservationConfig(pid->observation_config());
  b.Restore(snapshot);
  std::unique_ptr<controllers::Controller> pid_b = pid_at_branch->Clone();
  Drive(&b, pid_b.get(), 60.0);
  EXPECT_EQ(TrialDigest(b.Result()), original) << "restore into another episode";

  // Restored into the episode the snapshot came from, after it had run to the end.
  a.Restore(snapshot);
  EXPECT_FALSE(a.Done());
  std::unique_ptr<controllers::Controller> pid_a = pid_at_branch->Clone();
  Drive(&a, pid_a.get(), 60.0);
  EXPECT_EQ(TrialDigest(a.Result()), original) << "restore into the same episode";
}

TEST(SnapshotTest, RigidHighDenseWorldBranchesBitForBit) {
  // env008 (rigid, high, dense): steep faces, body and obstacle contacts
  ExpectBranchesIdentical(World("env008"), 3, 10.0);
}

TEST(SnapshotTest, BranchingWhilePushingAgainstRocksIsBitForBit) {
  // A wall of rocks across a flat world: at t = 9 s the vehicle is pressing its belly and wheels
  // against them (obstacle contacts in the state being branched).
  terrain::TaskSpec task = test::PlaneTask(128.0);
  for (double y = -62.0; y <= 62.0; y += 4.0) task.rocks.push_back({0.0, y, 1.0});
  const World w(task);
  ExpectBranchesIdentical(w, 0, 9.0);
  const TrialResult r = RunTrial(w.task, w.vehicle, TrialSpec());
  EXPECT_GE(r.obstacle_contacts, 1);
}

TEST(SnapshotTest, DeformableWorldBranchesBitForBit) {
  // env061 (deformable, mid): the soil's ruts and bulldozed rims are part of the state
  ExpectBranchesIdentical(World("env061"), 0, 10.0);
}

TEST(SnapshotTest, BranchesWithDifferentCommandsDivergeAndRestoreUndoesThem) {
  const World w("env042");
  Episode e(w.task, w.vehicle);
  e.Reset(TrialSpec());
  for (int i = 0; i < 400; ++i) e.Step({1.0, 0.0, 0.0});
  const EpisodeSnapshot s = e.Snapshot();
  for (int i = 0; i < 200; ++i) e.Step({1.0, 1.0, 0.0});   // full left
  const Vec3 left = e.vehicle_state().pose_W.position;
  e.Restore(s);
  EXPECT_DOUBLE_EQ(e.time_s(), 2.0);
  for (int i = 0; i < 200; ++i) e.Step({1.0, -1.0, 0.0});  // full right
  const Vec3 right = e.vehicle_state().pose_W.position;
  EXPECT_GT((left - right).norm(), 2.0);
  e.Restore(s);
  for (int i = 0; i < 200; ++i) e.Step({1.0, 1.0, 0.0});
  EXPECT_EQ(e.vehicle_state().pose_W.position, left);
}

}  // namespace
}  // namespace vb::runner
