// Soil benchmark: the HMMWV with the PID system across a deformable world (default
// tasks/env061.yaml, mid elevation, mud/snow/sand), the episode loop of the runner (controller ->
// vehicle -> soil EndStep -> physics step; success within 10 m of the goal, stuck when it moved
// <= 1 m in 10 s, 60 s limit), with the soil solver wrapped in a timer. Prints per pair the
// real-time factor, the soil solver's share and cost per step, and the peak memory (getrusage).
//
// usage: vb_bench_soil_episode [TASK] [--spacing M] [--pairs N] [--soil FILE]
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "vb/controllers/controller.h"
#include "vb/engine/physics_world.h"
#include "vb/soil/scm_soil.h"
#include "vb/terrain/grid_planner.h"
#include "vb/terrain/terrain.h"
#include "vb/terrain/terrain_physics.h"
#include "vb/vehicles/vehicle.h"

namespace {

using Clock = std::chrono::steady_clock;

// Times every call into the solver.
class TimedSoil : public vb::soil::SoilContact {
 public:
  explicit TimedSoil(vb::soil::ScmSoil* soil) : soil_(soil) {}
  vb::soil::WheelSoilOutput WheelContact(const vb::soil::WheelSoilInput& w, double dt) override {
    const auto t0 = Clock::now();
    const vb::soil::WheelSoilOutput out = soil_->WheelContact(w, dt);
    seconds_ += std::chrono::duration<double>(Clock::now() - t0).count();
    return out;
  }
  void EndStep(double dt) override {
    const auto t0 = Clock::now();
    soil_->EndStep(dt);
    seconds_ += std::chrono::duration<double>(Clock::now() - t0).count();
  }
  double seconds() const { return seconds_; }

 private:
  vb::soil::ScmSoil* soil_;
  double seconds_ = 0.0;
};

double CpuSeconds() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_utime.tv_sec + ru.ru_stime.tv_sec + 1e-6 * (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

struct PairResult {
  const char* outcome = "timeout";
  double sim_s = 0.0, wall_s = 0.0, cpu_s = 0.0, soil_s = 0.0;
  long steps = 0;
  double max_sinkage_m = 0.0;
  vb::soil::ScmStats stats;
};

PairResult RunPair(const vb::terrain::TaskSpec& task, const vb::vehicles::VehicleParams& params,
                   const vb::soil::SoilConfig& soil_config, int pair_index) {
  using namespace vb;
  const auto wall0 = Clock::now();
  const double cpu0 = CpuSeconds();
  const terrain::StartGoalPair& pair = task.pairs[static_cast<size_t>(pair_index)];
  const terrain::Terrain ground(task);
  engine::PhysicsWorld world;
  terrain::AddTerrainToPhysics(task, ground, &world);
  const terrain::OccupancyGrid inflated =
      terrain::Inflate(terrain::RasterizeObstacles(task), static_cast<int>(4.0 * task.scale));
  // Start pose as the runner: facing the goal, 0.5 m above the highest ground under the wheels.
  const Vec2 d = pair.goal_m - pair.start_m;
  const double yaw = std::atan2(d.y(), d.x());
  const Eigen::Rotation2Dd rot(yaw);
  double ground_z = ground.Height(pair.start_m.x(), pair.start_m.y());
  for (const vehicles::AxleParams& axle : params.axles) {
    for (double side : {1.0, -1.0}) {
      const Vec2 p = pair.start_m + rot * Vec2(axle.x_m, side * axle.half_track_m);
      ground_z = std::max(ground_z, ground.Height(p.x(), p.y()));
    }
  }
  Pose start;
  start.position = Vec3(pair.start_m.x(), pair.start_m.y(),
                        ground_z + params.wheel.radius_m - params.axles[0].z_m + 0.5);
  start.rotation = FromYaw(yaw);
  vehicles::Vehicle vehicle(params, ground, start, &world);
  soil::ScmSoil scm(ground, soil_config);
  TimedSoil soil(&scm);
  vehicle.SetSoil(&soil);
  std::unique_ptr<controllers::Controller> controller = controllers::MakeController("pid");
  controllers::EpisodeContext ctx;
  ctx.task = &task;
  ctx.inflated_obstacles = &inflated;
  ctx.goal_m = pair.goal_m;
  ctx.scale = task.scale;
  controller->Reset(ctx);

  PairResult r;
  const double dt = 0.005;
  const long window = 2000;  // 10 s
  std::vector<Vec2> history;
  for (long k = 0; k < 12000; ++k) {
    const vehicles::VehicleState& s0 = vehicle.state();
    controllers::Observation obs;
    obs.time_s = k * dt;
    obs.position_W = s0.pose_W.position;
    obs.rpy = s0.rpy;
    obs.velocity_W = s0.velocity_W;
    obs.forward_speed_mps = s0.forward_speed_mps;
    const controllers::Command cmd = controller->Update(obs);
    vehicles::DriverInputs in;
    in.throttle = cmd.throttle;
    in.steering = cmd.steering;
    in.braking = cmd.braking;
    vehicle.SetInputs(in);
    vehicle.Synchronize(dt);
    soil.EndStep(dt);
    world.Step(dt);
    vehicle.UpdateState();
    r.steps = k + 1;
    const vehicles::VehicleState& s = vehicle.state();
    for (const vehicles::WheelState& w : s.wheels) r.max_sinkage_m = std::max(r.max_sinkage_m, w.sinkage_m);
    const Vec2 xy = s.pose_W.position.head<2>();
    history.push_back(xy);
    if (!s.pose_W.position.allFinite()) {
      r.outcome = "sim_error";
      break;
    }
    if ((pair.goal_m - xy).norm() <= 10.0 * task.scale) {
      r.outcome = "success";
      break;
    }
    if (static_cast<long>(history.size()) > window &&
        (xy - history[history.size() - 1 - window]).norm() <= 1.0 * task.scale) {
      r.outcome = "stuck";
      break;
    }
  }
  r.sim_s = r.steps * dt;
  r.wall_s = std::chrono::duration<double>(Clock::now() - wall0).count();
  r.cpu_s = CpuSeconds() - cpu0;
  r.soil_s = soil.seconds();
  r.stats = scm.stats();
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  std::string task_path = VB_SOURCE_DIR "/tasks/env061.yaml";
  std::string soil_path = VB_SOURCE_DIR "/data/soils/verti_bench.yaml";
  double spacing = 0.0;
  int pairs = -1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--spacing" && i + 1 < argc) {
      spacing = std::atof(argv[++i]);
    } else if (a == "--pairs" && i + 1 < argc) {
      pairs = std::atoi(argv[++i]);
    } else if (a == "--soil" && i + 1 < argc) {
      soil_path = argv[++i];
    } else {
      task_path = a;
    }
  }
  try {
    const vb::terrain::TaskSpec task = vb::io::LoadTask(task_path);
    const vb::vehicles::VehicleParams params =
        vb::io::LoadVehicle(VB_SOURCE_DIR "/data/vehicles/hmmwv.yaml");
    vb::soil::SoilConfig soil = vb::io::LoadSoil(soil_path);
    if (spacing > 0.0) soil.grid_spacing_m = spacing;
    const int n = pairs > 0 ? std::min<int>(pairs, static_cast<int>(task.pairs.size()))
                            : static_cast<int>(task.pairs.size());
    std::printf("task %s, soil %s, grid %.3f m, HMMWV + PID, step 5 ms\n", task_path.c_str(),
                soil_path.c_str(), soil.grid_spacing_m);
    std::printf("(RTF = sim / wall; RTF_cpu = sim / process CPU time, insensitive to a loaded "
                "machine; soil_%% and soil_us are wall-clock)\n");
    std::printf("pair outcome     sim_s  wall_s    RTF  RTF_cpu  soil_%%  soil_us/step  nodes/step  "
                "max_sink_m  tiles  soil_MB\n");
    double sim = 0, wall = 0, cpu = 0, soil_s = 0;
    long steps = 0;
    for (int k = 0; k < n; ++k) {
      const PairResult r = RunPair(task, params, soil, k);
      std::printf("%4d %-9s %6.2f %7.3f %6.1f %8.1f %6.1f %13.1f %11.1f %11.3f %6ld %8.1f\n", k,
                  r.outcome, r.sim_s, r.wall_s, r.sim_s / r.wall_s, r.sim_s / r.cpu_s,
                  100.0 * r.soil_s / r.wall_s,
                  1e6 * r.soil_s / r.steps,
                  static_cast<double>(r.stats.contact_nodes) / r.steps, r.max_sinkage_m,
                  r.stats.tiles, r.stats.memory_bytes / 1048576.0);
      std::fflush(stdout);
      sim += r.sim_s;
      wall += r.wall_s;
      cpu += r.cpu_s;
      soil_s += r.soil_s;
      steps += r.steps;
    }
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    std::printf("all: sim %.1f s, wall %.2f s, RTF %.1f, RTF_cpu %.1f, soil %.1f %% of wall, "
                "%.1f us/step; peak RSS %.1f MB\n",
                sim, wall, sim / wall, sim / cpu, 100.0 * soil_s / wall, 1e6 * soil_s / steps,
                ru.ru_maxrss / 1024.0);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vb_bench_soil_episode: %s\n", e.what());
    return 2;
  }
  return 0;
}
