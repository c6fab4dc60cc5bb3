// The privileged expert (oracle.h): its rollouts never disturb the real episode (a replay of the
// commands it applied, with no planner at all, gives the same bits; every committed segment ends
// exactly where the scored rollout, restored from a snapshot, predicted), it is deterministic,
// with only the PID's candidate it is the PID bit for bit, and its budget names are validated.
#include "vb/engine/runner/oracle.h"

#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "vb/controllers/pid_controller.h"
#include "vb/engine/error.h"
#include "vb/engine/runner/episode.h"
#include "vb/engine/runner/result_digest.h"
#include "vb/engine/runner/systems.h"

namespace vb::runner {
namespace {

struct World {
  terrain::TaskSpec task;
  vehicles::VehicleParams vehicle;
  std::optional<soil::SoilConfig> soil;
  explicit World(const std::string& name)
      : task(io::LoadTask(VB_SOURCE_DIR "/tasks/" + name + ".yaml")),
        vehicle(io::LoadVehicle(VB_SOURCE_DIR "/data/vehicles/hmmwv.yaml")),
        soil(io::LoadSoilIfNeeded(task, VB_SOURCE_DIR "/data/soils/verti_bench.yaml")) {}
  const soil::SoilConfig* soil_ptr() const { return soil ? &*soil : nullptr; }
};

EpisodeRules ShortRules(double time_limit_s) {
  EpisodeRules rules;
  rules.time_limit_s = time_limit_s;
  return rules;
}

struct OracleRun {
  std::string digest;
  TrialResult result;
  OracleStats stats;
  std::vector<controllers::Command> commands;
};

// Drives pair `pair` of `w` with an oracle of `params` as RunTrial does, keeping the commands.
OracleRun RunOracle(const World& w, int pair, const EpisodeRules& rules,
                    const OracleParams& params) {
  Episode episode(w.task, w.vehicle, rules, w.soil_ptr());
  OracleController oracle(&episode, params);
  episode.SetObservationConfig(oracle.observation_config());
  TrialSpec spec;
  spec.pair_index = pair;
  spec.system = "oracle";
  episode.Reset(spec);
  oracle.Reset(episode.context());
  OracleRun run;
  while (!episode.Done()) {
    run.commands.push_back(oracle.Update(episode.Observe()));
    episode.Step(run.commands.back());
  }
  run.result = episode.TakeResult();
  run.digest = TrialDigest(run.result);
  run.stats = oracle.stats();
  return run;
}

// The same commands applied open loop to a fresh episode that never branched.
std::string Replay(const World& w, int pair, const EpisodeRules& rules,
                   const std::vector<controllers::Command>& commands) {
  Episode episode(w.task, w.vehicle, rules, w.soil_ptr());
  episode.SetObservationConfig(controllers::PidController().observation_config());
  TrialSpec spec;
  spec.pair_index = pair;
  spec.system = "oracle";
  episode.Reset(spec);
  for (const controllers::Command& c : commands) {
    if (episode.Done()) break;
    episode.Step(c);
  }
  EXPECT_TRUE(episode.Done());
  return TrialDigest(episode.TakeResult());
}

void ExpectRolloutsLeaveNoTrace(const World& w, int pair, double time_limit_s) {
  const EpisodeRules rules = ShortRules(time_limit_s);
  const OracleRun a = RunOracle(w, pair, rules, OracleParams());
  // It searched (not only early accepts) and chose more than the PID's action at times.
  EXPECT_GT(a.stats.replans, 3);
  EXPECT_GT(a.stats.rollouts, a.stats.replans);
  // Every committed segment ended bit for bit where its rollout (restored from a snapshot of
  // the real episode into the planning episode) said it would.
  EXPECT_GT(a.stats.predictions_checked, 3);
  EXPECT_EQ(a.stats.prediction_mismatches, 0);
  // The real episode was never disturbed: replaying the applied commands without any rollout
  // gives the same trial, and the whole oracle trial reruns bit for bit.
  EXPECT_EQ(Replay(w, pair, rules, a.commands), a.digest);
  const OracleRun b = RunOracle(w, pair, rules, OracleParams());
  EXPECT_EQ(b.digest, a.digest);
  EXPECT_EQ(b.stats.rollout_steps, a.stats.rollout_steps);
}

TEST(OracleTest, RigidHighWorldRolloutsLeaveNoTraceAndRerunBitForBit) {
  // env002 pair 0 (high, rigid, sparse): the PID gets stuck on a slope at 12 s.
  ExpectRolloutsLeaveNoTrace(World("env002"), 0, 16.0);
}

TEST(OracleTest, DeformableWorldRolloutsLeaveNoTraceAndRerunBitForBit) {
  // env061 pair 0 (mid, deformable, dense): the soil's ruts are part of every snapshot.
  ExpectRolloutsLeaveNoTrace(World("env061"), 0, 12.0);
}

TEST(OracleTest, WithOnlyThePidCandidateItIsThePid) {
  const World w("env042");
  const EpisodeRules rules = ShortRules(20.0);
  OracleParams only_pid;
  only_pid.steering.clear();
  only_pid.speeds_mps = {4.0};
  const OracleRun o = RunOracle(w, 1, rules, only_pid);
  TrialSpec spec;
  spec.pair_index = 1;
  spec.system = "oracle";   // the digest covers the spec: same name as the oracle run
  Episode episode(w.task, w.vehicle, rules, w.soil_ptr());
  std::unique_ptr<controllers::Controller> pid = controllers::MakeController("pid");
  episode.SetObservationConfig(pid->observation_config());
  episode.Reset(spec);
  pid->Reset(episode.context());
  while (!episode.Done()) episode.Step(pid->Update(episode.Observe()));
  EXPECT_EQ(TrialDigest(episode.TakeResult()), o.digest);
  EXPECT_EQ(o.stats.rollouts, o.stats.replans);
}

TEST(OracleTest, RunTrialRunsTheOracleByName) {
  const World w("env042");
  TrialSpec spec;
  spec.system = "oracle-h2-r0.5-n3-e0";
  const TrialResult a = RunTrial(w.task, w.vehicle, spec, ShortRules(3.0), w.soil_ptr());
  const TrialResult b = RunTrial(w.task, w.vehicle, spec, ShortRules(3.0), w.soil_ptr());
  EXPECT_EQ(TrialDigest(a), TrialDigest(b));
  EXPECT_DOUBLE_EQ(a.sim_time_s, 3.0);
}

TEST(OracleTest, BudgetNames) {
  const OracleParams d = ParseOracleName("oracle");
  EXPECT_DOUBLE_EQ(d.horizon_s, 3.0);
  EXPECT_DOUBLE_EQ(d.replan_period_s, 1.0);
  EXPECT_EQ(d.steering.size(), 5u);
  const OracleParams p = ParseOracleName("oracle-h4-r0.5-n3-e0");
  EXPECT_DOUBLE_EQ(p.horizon_s, 4.0);
  EXPECT_DOUBLE_EQ(p.replan_period_s, 0.5);
  ASSERT_EQ(p.steering.size(), 3u);
  EXPECT_DOUBLE_EQ(p.steering[0], -1.0);
  EXPECT_DOUBLE_EQ(p.steering[1], 0.0);
  EXPECT_DOUBLE_EQ(p.steering[2], 1.0);
  EXPECT_DOUBLE_EQ(p.early_accept_fraction, 0.0);
  EXPECT_TRUE(ParseOracleName("oracle-n0").steering.empty());
  for (const char* bad : {"oracle-", "oracle-h", "oracle-hx", "oracle-h-1", "oracle-q3",
                          "oracle-n2", "oracle-e2", "oracle-h1-r2", "oracle-h0", "oraclex"}) {
    EXPECT_THROW(ParseOracleName(bad), InputError) << bad;
  }
  EXPECT_NO_THROW(ValidateSystemName("oracle-h2"));
  EXPECT_THROW(ValidateSystemName("oracle-h2x"), InputError);
  EXPECT_THROW(ValidateSystemName("nope"), InputError);
  // A replanning period that is not a whole number of control periods is bad input at Reset.
  const World w("env042");
  TrialSpec spec;
  spec.system = "oracle-r0.0031";
  EXPECT_THROW(RunTrial(w.task, w.vehicle, spec, ShortRules(1.0), w.soil_ptr()), InputError);
}

}  // namespace
}  // namespace vb::runner
