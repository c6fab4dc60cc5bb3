// Imperfect perception (perception.h): each error has the configured statistics on a long
// sample; the presets load; `none` leaves the observation untouched; latency, mapping delay,
// determinism and snapshot/restore with errors on.
#include "vb/engine/runner/perception.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "io/perception_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "support/input_error.h"
#include "support/worlds.h"
#include "vb/engine/runner/episode.h"
#include "vb/engine/runner/result_digest.h"

namespace vb::runner {
namespace {

struct MeanSd {
  double mean = 0.0;
  double sd = 0.0;
};
MeanSd Stats(const std::vector<double>& v) {
  MeanSd s;
  for (double x : v) s.mean += x;
  s.mean /= static_cast<double>(v.size());
  for (double x : v) s.sd += (x - s.mean) * (x - s.mean);
  s.sd = std::sqrt(s.sd / static_cast<double>(v.size()));
  return s;
}

terrain::TaskSpec FlatTask() { return test::PlaneTask(128.0, 0.0, 0.0); }

TEST(PerceptionTest, NoneIsDisabledAndEveryPresetLoads) {
  EXPECT_FALSE(PerceptionParams().Enabled());
  for (const char* name : {"mild", "moderate", "severe"}) {
    const PerceptionParams p = io::ResolvePerception(name, VB_SOURCE_DIR "/data");
    EXPECT_EQ(p.name, name);
    EXPECT_TRUE(p.Enabled()) << name;
  }
  // Severity grows preset by preset in every kind of error.
  const PerceptionParams mild = io::ResolvePerception("mild", VB_SOURCE_DIR "/data");
  const PerceptionParams mod = io::ResolvePerception("moderate", VB_SOURCE_DIR "/data");
  const PerceptionParams sev = io::ResolvePerception("severe", VB_SOURCE_DIR "/data");
  EXPECT_LT(mild.position_bias_sd_m, mod.position_bias_sd_m);
  EXPECT_LT(mod.position_bias_sd_m, sev.position_bias_sd_m);
  EXPECT_LT(mild.elevation_noise_sd_m, mod.elevation_noise_sd_m);
  EXPECT_LT(mod.elevation_noise_sd_m, sev.elevation_noise_sd_m);
  EXPECT_LT(mild.semantics_confusion[2][2] - 1.0, 1e-12);
  EXPECT_GT(mild.semantics_confusion[2][2], mod.semantics_confusion[2][2]);
  EXPECT_GT(mod.semantics_confusion[2][2], sev.semantics_confusion[2][2]);
  EXPECT_LT(mild.latency_s, sev.latency_s);
}

TEST(PerceptionTest, BadPerceptionFilesNameFileLineAndKey) {
  const std::string dir = ::testing::TempDir();
  auto write = [&](const std::string& name, const std::string& text) {
    const std::string path = dir + "/" + name;
    std::FILE* f = std::fopen(path.c_str(), "w");
    std::fputs(text.c_str(), f);
    std::fclose(f);
    return path;
  };
  const std::string head = "format: vb-perception\nversion: 1\n";
  const std::string neg = write("neg.yaml", head + "pose:\n  position_noise_sd_m: -1.0\n");
  test::ExpectInputError([&] { io::LoadPerception(neg); }, neg, 4, "pose.position_noise_sd_m",
                         "must be in [0");
  const std::string unk = write("unk.yaml", head + "maps:\n  elevation_noise: 0.1\n");
  test::ExpectInputError([&] { io::LoadPerception(unk); }, unk, 4, "maps.elevation_noise",
                         "unknown key");
  const std::string both =
      write("both.yaml", head + "semantics:\n  error_rate: 0.1\n  confusion: []\n");
  test::ExpectInputError([&] { io::LoadPerception(both); }, both, 3, "semantics", "either");
  const std::string rows =
      write("rows.yaml", head + "semantics:\n  confusion: [[1,0,0,0,0,0,0,0,0,0]]\n");
  test::ExpectInputError([&] { io::LoadPerception(rows); }, rows, 4, "semantics.confusion", "");
  try {
    io::ResolvePerception("foggy", VB_SOURCE_DIR "/data");
    ADD_FAILURE() << "an unknown preset must be an error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "--perception");
    EXPECT_NE(std::string(e.what()).find("'foggy'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("moderate"), std::string::npos) << e.what();
  }
}

TEST(PerceptionTest, PoseBiasHasTheConfiguredSpreadAcrossTrials) {
  PerceptionParams p;
  p.name = "test";
  p.position_bias_sd_m = 0.5;
  p.yaw_bias_sd_rad = 0.02;
  const terrain::TaskSpec task = FlatTask();
  std::vector<double> x, yaw;
  for (uint64_t seed = 0; seed < 4000; ++seed) {
    PerceptionModel m(p, 0.005);
    m.Reset(seed, task);
    const PoseError e = m.AdvanceTo(1.0);
    x.push_back(e.position_m.x());
    yaw.push_back(e.yaw_rad);
    // Constant within a trial.
    const PoseError later = m.AdvanceTo(30.0);
    ASSERT_EQ(later.position_m.x(), e.position_m.x());
  }
  EXPECT_NEAR(Stats(x).mean, 0.0, 0.03);
  EXPECT_NEAR(Stats(x).sd, 0.5, 0.5 * 0.05);
  EXPECT_NEAR(Stats(yaw).sd, 0.02, 0.02 * 0.05);
}

TEST(PerceptionTest, DriftIsARandomWalkWithTheConfiguredIntensity) {
  PerceptionParams p;
  p.name = "test";
  p.position_drift_m_per_sqrt_s = 0.1;
  p.yaw_drift_rad_per_sqrt_s = 0.003;
  const terrain::TaskSpec task = FlatTask();
  std::vector<double> x10, x40, yaw40;
  for (uint64_t seed = 0; seed < 3000; ++seed) {
    PerceptionModel m(p, 0.005);
    m.Reset(seed, task);
    for (int k = 1; k <= 400; ++k) {  // observed every 0.1 s
      const PoseError e = m.AdvanceTo(0.1 * k);
      if (k == 100) x10.push_back(e.position_m.x());
      if (k == 400) {
        x40.push_back(e.position_m.x());
        yaw40.push_back(e.yaw_rad);
      }
    }
  }
  // sd = q sqrt(t): 0.316 m after 10 s, 0.632 m after 40 s.
  EXPECT_NEAR(Stats(x10).sd, 0.1 * std::sqrt(10.0), 0.316 * 0.05);
  EXPECT_NEAR(Stats(x40).sd, 0.1 * std::sqrt(40.0), 0.632 * 0.05);
  EXPECT_NEAR(Stats(yaw40).sd, 0.003 * std::sqrt(40.0), 0.019 * 0.05);
}

TEST(PerceptionTest, GaussMarkovNoiseHasItsStationarySpreadAndCorrelationTime) {
  PerceptionParams p;
  p.name = "test";
  p.position_noise_sd_m = 0.2;
  p.noise_correlation_s = 1.0;
  PerceptionModel m(p, 0.005);
  m.Reset(7, FlatTask());
  std::vector<double> x;
  const double dt = 0.05;
  for (int k = 1; k <= 400000; ++k) x.push_back(m.AdvanceTo(k * dt).position_m.x());
  const MeanSd s = Stats(x);
  EXPECT_NEAR(s.mean, 0.0, 0.01);
  EXPECT_NEAR(s.sd, 0.2, 0.2 * 0.03);
  // Autocorrelation at lag tau = 1 s is 1/e.
  const int lag = 20;
  double c = 0.0;
  for (size_t i = 0; i + lag < x.size(); ++i) c += (x[i] - s.mean) * (x[i + lag] - s.mean);
  c /= static_cast<double>(x.size() - lag) * s.sd * s.sd;
  EXPECT_NEAR(c, std::exp(-1.0), 0.03);

  // Without a correlation time the noise is white per observation.
  p.noise_correlation_s = 0.0;
  PerceptionModel w(p, 0.005);
  w.Reset(7, FlatTask());
  std::vector<double> y;
  for (int k = 1; k <= 100000; ++k) y.push_back(w.AdvanceTo(k * dt).position_m.x());
  const MeanSd sy = Stats(y);
  double c1 = 0.0;
  for (size_t i = 0; i + 1 < y.size(); ++i) c1 += (y[i] - sy.mean) * (y[i + 1] - sy.mean);
  c1 /= static_cast<double>(y.size() - 1) * sy.sd * sy.sd;
  EXPECT_NEAR(sy.sd, 0.2, 0.2 * 0.03);
  EXPECT_NEAR(c1, 0.0, 0.02);
}

TEST(PerceptionTest, VelocityNoisesAreWhiteWithTheConfiguredSpread) {
  PerceptionParams p;
  p.name = "test";
  p.velocity_noise_sd_mps = 0.1;
  p.angular_velocity_noise_sd_radps = 0.02;
  PerceptionModel m(p, 0.005);
  m.Reset(3, FlatTask());
  std::vector<double> v, w;
  for (int k = 0; k < 100000; ++k) {
    v.push_back(m.VelocityNoise().y());
    w.push_back(m.AngularVelocityNoise().z());
  }
  EXPECT_NEAR(Stats(v).sd, 0.1, 0.1 * 0.03);
  EXPECT_NEAR(Stats(w).sd, 0.02, 0.02 * 0.03);
  EXPECT_NEAR(Stats(v).mean, 0.0, 0.002);
}

TEST(PerceptionTest, ElevationErrorsAndHolesHaveTheConfiguredStatistics) {
  PerceptionParams p;
  p.name = "test";
  p.elevation_noise_sd_m = 0.1;
  p.elevation_hole_fraction = 0.2;
  p.elevation_hole_size_m = 1.0;
  PerceptionModel m(p, 0.005);
  m.Reset(11, FlatTask());
  std::vector<double> e;
  int holes = 0, n = 0;
  for (int i = 0; i < 400; ++i) {
    for (int j = 0; j < 400; ++j) {
      const Vec2 q(-60.0 + 0.3 * i + 0.05, -60.0 + 0.3 * j + 0.05);
      e.push_back(m.ElevationError(q));
      holes += m.IsHole(q) ? 1 : 0;
      ++n;
    }
  }
  EXPECT_NEAR(Stats(e).mean, 0.0, 0.002);
  EXPECT_NEAR(Stats(e).sd, 0.1, 0.1 * 0.02);
  EXPECT_NEAR(static_cast<double>(holes) / n, 0.2, 0.015);
  // The error is a field over world cells: the same point twice, and two points of one cell,
  // read the same; another trial's field differs.
  EXPECT_EQ(m.ElevationError(Vec2(1.01, 2.01)), m.ElevationError(Vec2(1.09, 2.09)));
  PerceptionModel other(p, 0.005);
  other.Reset(12, FlatTask());
  EXPECT_NE(m.ElevationError(Vec2(1.01, 2.01)), other.ElevationError(Vec2(1.01, 2.01)));
}

TEST(PerceptionTest, SemanticsFollowTheConfusionMatrix) {
  PerceptionParams p;
  p.name = "test";
  p.semantics_confusion = ConfusionFromErrorRate(0.3);
  for (int i = 0; i < terrain::kNumSurfaceClasses; ++i) {
    double sum = 0.0;
    for (double v : p.semantics_confusion[i]) sum += v;
    ASSERT_NEAR(sum, 1.0, 1e-12);
  }
  PerceptionModel m(p, 0.005);
  m.Reset(5, FlatTask());
  const int dirt = static_cast<int>(terrain::SurfaceClass::kDirt);
  std::vector<int> counts(terrain::kNumSurfaceClasses, 0);
  int n = 0;
  for (int i = 0; i < 500; ++i) {
    for (int j = 0; j < 500; ++j) {
      ++counts[static_cast<size_t>(m.PerceivedClass(dirt, Vec2(-60.0 + 0.2 * i + 0.05,
                                                                 -60.0 + 0.2 * j + 0.05)))];
      ++n;
    }
  }
  for (int c = 0; c < terrain::kNumSurfaceClasses; ++c) {
    EXPECT_NEAR(static_cast<double>(counts[static_cast<size_t>(c)]) / n,
                p.semantics_confusion[static_cast<size_t>(dirt)][static_cast<size_t>(c)], 0.006)
        << "class " << c;
  }
}

TEST(PerceptionTest, MissedAndPhantomObstaclesHaveTheConfiguredRates) {
  PerceptionParams p;
  p.name = "test";
  p.obstacle_miss_probability = 0.2;
  p.phantom_rocks_per_ha = 3.0;   // 128 x 128 m = 1.6384 ha: mean 4.9 phantoms
  terrain::TaskSpec task = FlatTask();
  for (int i = 0; i < 20; ++i) task.rocks.push_back({-50.0 + 5.0 * i, 30.0, 1.0});
  for (int i = 0; i < 30; ++i) task.trees.push_back({-50.0 + 3.0 * i, -30.0});
  double missed = 0.0, phantoms = 0.0;
  const int trials = 2000;
  for (int seed = 0; seed < trials; ++seed) {
    PerceptionModel m(p, 0.005);
    m.Reset(static_cast<uint64_t>(seed), task);
    missed += m.missed_obstacles();
    phantoms += m.phantom_rocks();
  }
  EXPECT_NEAR(missed / (trials * 50.0), 0.2, 0.01);
  EXPECT_NEAR(phantoms / trials, 3.0 * 1.6384, 0.15);

  // The perceived grids: every obstacle missed, none seen.
  p.obstacle_miss_probability = 1.0;
  p.phantom_rocks_per_ha = 0.0;
  PerceptionModel blind(p, 0.005);
  blind.Reset(0, task);
  int occupied = 0;
  for (uint8_t o : blind.perceived_bare().occupied) occupied += o;
  EXPECT_EQ(occupied, 0);
  EXPECT_EQ(blind.missed_obstacles(), 50);
}

// An episode with perception: the observation's pose is the true one plus the errors, and with
// latency it is the state of that long ago.
struct Flat {
  terrain::TaskSpec task = FlatTask();
  vehicles::VehicleParams vehicle = io::LoadVehicle(VB_SOURCE_DIR "/data/vehicles/hmmwv.yaml");
  Flat() {
    terrain::StartGoalPair pair;
    pair.start_m = Vec2(-40.0, 0.0);
    pair.goal_m = Vec2(40.0, 0.0);
    task.pairs = {pair};
  }
};

TEST(PerceptionTest, LatencyDelaysTheWholeObservationExactly) {
  const Flat w;
  EpisodeRules rules;
  rules.perception.name = "late";
  rules.perception.latency_s = 0.1;   // 20 physics steps
  Episode late(w.task, w.vehicle, rules);
  Episode truth(w.task, w.vehicle, EpisodeRules());
  TrialSpec spec;
  late.Reset(spec);
  truth.Reset(spec);
  std::vector<Vec3> true_positions = {truth.vehicle_state().pose_W.position};
  controllers::Command drive;
  drive.throttle = 0.5;
  for (int k = 1; k <= 300; ++k) {
    late.Step(drive);
    truth.Step(drive);
    true_positions.push_back(truth.vehicle_state().pose_W.position);
    const controllers::Observation& o = late.Observe();
    const size_t seen = static_cast<size_t>(std::max(0, k - 20));
    ASSERT_EQ(o.position_W, true_positions[seen]) << "step " << k;
    ASSERT_DOUBLE_EQ(o.time_s, 0.005 * static_cast<double>(seen));
  }
  // The physics is untouched by perception.
  EXPECT_EQ(late.vehicle_state().pose_W.position, truth.vehicle_state().pose_W.position);
}

TEST(PerceptionTest, EpisodesWithPerceptionAreDeterministicAndSnapshotBitExact) {
  const Flat w;
  EpisodeRules rules;
  rules.perception = io::ResolvePerception("severe", VB_SOURCE_DIR "/data");
  auto run = [&](uint64_t seed) {
    Episode e(w.task, w.vehicle, rules);
    std::unique_ptr<controllers::Controller> pid = controllers::MakeController("pid");
    e.SetObservationConfig(pid->observation_config());
    TrialSpec spec;
    spec.seed = seed;
    e.Reset(spec);
    pid->Reset(e.context());
    std::vector<double> xs;
    while (!e.Done() && e.time_s() < 8.0) {
      const controllers::Observation& o = e.Observe();
      xs.push_back(o.position_W.x());
      e.Step(pid->Update(o));
    }
    return xs;
  };
  EXPECT_EQ(run(1), run(1));
  EXPECT_NE(run(1), run(2));

  // Branch at 3 s: both continuations give the same result bits.
  Episode a(w.task, w.vehicle, rules);
  std::unique_ptr<controllers::Controller> pid = controllers::MakeController("pid");
  a.SetObservationConfig(pid->observation_config());
  TrialSpec spec;
  spec.seed = 9;
  a.Reset(spec);
  pid->Reset(a.context());
  while (a.time_s() < 3.0 - 1e-9) a.Step(pid->Update(a.Observe()));
  const EpisodeSnapshot snap = a.Snapshot();
  std::unique_ptr<controllers::Controller> pid_b = pid->Clone();
  while (!a.Done() && a.time_s() < 12.0 - 1e-9) a.Step(pid->Update(a.Observe()));
  Episode b(w.task, w.vehicle, rules);
  b.Restore(snap);
  while (!b.Done() && b.time_s() < 12.0 - 1e-9) b.Step(pid_b->Update(b.Observe()));
  EXPECT_EQ(TrialDigest(a.Result()), TrialDigest(b.Result()));
}

TEST(PerceptionTest, PoseErrorsShiftTheObservationNotThePhysics) {
  const Flat w;
  EpisodeRules rules;
  rules.perception.name = "biased";
  rules.perception.position_bias_sd_m = 1.0;
  Episode e(w.task, w.vehicle, rules);
  TrialSpec spec;
  spec.seed = 4;
  e.Reset(spec);
  const controllers::Observation& o = e.Observe();
  const Vec3 error = o.position_W - e.vehicle_state().pose_W.position;
  EXPECT_GT(error.head<2>().norm(), 1e-3);
  EXPECT_EQ(error.z(), 0.0);   // bias is horizontal
  // The goal distance is measured from the estimate.
  EXPECT_DOUBLE_EQ(o.goal_distance_m, (o.goal_m - o.position_W.head<2>()).norm());
}

}  // namespace
}  // namespace vb::runner
