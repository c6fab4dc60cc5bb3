// What vb_view spends on one /api/trial answer (docs/viewer.md), stage by stage: reading the
// record, loading and hashing the task, the scene JSON (terrain, obstacles, paths), the vehicle,
// and passing the trajectory through as a JSON string. Medians of N runs.
//
//   build/bench/vb_bench_viewer_bundle RESULT.json [N]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "io/batch_io.h"
#include "io/result_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "view/scene_json.h"
#include "view/trial_bundle.h"

namespace {

double MedianMs(int n, const std::function<void()>& fn) {
  std::vector<double> t;
  for (int i = 0; i < n; ++i) {
    const auto a = std::chrono::steady_clock::now();
    fn();
    t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a)
                    .count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s RESULT.json [N]\n", argv[0]);
    return 2;
  }
  const std::string result = argv[1];
  const int n = argc > 2 ? std::max(1, std::atoi(argv[2])) : 20;
  vb::view::BundleOptions options;
  options.data_dir = VB_SOURCE_DIR "/data";
  options.tasks_dir = VB_SOURCE_DIR "/tasks";
  const vb::batch::TrialRow row = vb::io::ReadTrialJson(result);
  const std::string task_path = std::string(VB_SOURCE_DIR) + "/tasks/" + row.task + ".yaml";
  const vb::terrain::TaskSpec task = vb::io::LoadTask(task_path);
  std::ifstream in(vb::view::TrajectoryPathFor(result), std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string csv = ss.str();
  size_t bytes = 0;

  std::printf("command: %s %s %d\n", argv[0], result.c_str(), n);
  std::printf("median of %d runs, ms:\n", n);
  std::printf("  read record (JSON)            %8.2f\n",
              MedianMs(n, [&] { vb::io::ReadTrialJson(result); }));
  std::printf("  load task (YAML + PNG)        %8.2f\n",
              MedianMs(n, [&] { vb::io::LoadTask(task_path); }));
  std::printf("  hash task + image (FNV-1a)    %8.2f\n",
              MedianMs(n, [&] { vb::io::MakeProvenance(task, vb::runner::TrialSpec()); }));
  std::printf("  scene JSON (terrain, boxes)   %8.2f\n", MedianMs(n, [&] {
                bytes = vb::view::TaskSceneJson(task, 10.0).size();
              }));
  std::printf("  vehicle (load + JSON)         %8.2f\n", MedianMs(n, [&] {
                vb::view::VehicleSceneJson(
                    vb::io::LoadVehicle(options.data_dir + "/vehicles/" + row.vehicle + ".yaml"));
              }));
  std::printf("  trajectory as JSON string     %8.2f  (%zu bytes of CSV)\n",
              MedianMs(n, [&] { vb::view::JsonText(csv); }), csv.size());
  const double whole_ms = MedianMs(n, [&] {
    bytes = vb::view::TrialBundleJson(result, options).size();
  });
  std::printf("  whole bundle                  %8.2f  (%zu bytes)\n", whole_ms, bytes);
  vb::view::SceneCache cache;
  options.cache = &cache;
  std::printf("  whole bundle, world cached    %8.2f  (vb_view's case after the first request)\n",
              MedianMs(n, [&] { vb::view::TrialBundleJson(result, options); }));
  return 0;
}
