// vb_view: the 3-D viewer's local server (docs/viewer.md). Replays a trial, browses a results
// directory, or lets a person drive a task (teleoperation) and records the drive as a trial.
// Thin: flags -> load -> view::ViewServer; the page itself is web/viewer/.
#include <algorithm>
#include <cctype>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "io/cli_args.h"
#include "io/data_dir.h"
#include "io/result_io.h"
#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "vb/engine/error.h"
#include "view/http.h"
#include "view/teleop_session.h"
#include "view/trial_bundle.h"
#include "view/view_server.h"

namespace {

namespace fs = std::filesystem;

constexpr const char* kUsage = R"(usage: vb_view RESULT.json [options]
       vb_view serve DIR [options]
       vb_view teleop TASK --vehicle NAME [options]

A local server for the 3-D viewer (web/viewer), listening on 127.0.0.1 only; open the printed
URL in a browser (--open does it). Nothing is fetched from the network.

  vb_view RESULT.json   replay one trial: RESULT.json and its <stem>_traj.csv (vb_run, vb_batch)
  vb_view serve DIR     browse a results directory: DIR/report/trials.html (vb_report) links
                        every trial to the viewer
  vb_view teleop TASK   drive TASK with the keyboard or a gamepad in the page, at real time; each
                        drive is recorded as a trial (system "teleop") in DIR/drive_<N>/

options:
  --port P           port on 127.0.0.1 (default 8765; 0: any free port)
  --open             open the URL with xdg-open
  --task FILE        (replay) the trial's task file, instead of its recorded path
  --tasks DIR        (replay, serve) the task set the trials ran on, to find their task files
                     (default: share/vb/tasks next to this program's bin/, vb's shipped tasks)
  --vehicle NAME     (teleop) vehicle $VB_DATA_DIR/vehicles/NAME.yaml (required)
  --pair K           (teleop) start/goal pair (default 0)
  --seed S           (teleop) trial seed (default 0)
  --soil NAME        (teleop) soil parameters for mud, sand, snow (default verti_bench)
  --out DIR          (teleop) where drives are recorded (default results/teleop)
  --operator NAME    (teleop) who drives, recorded in each drive's provenance ("operator")
  --exit-after N     (teleop) exit after N recorded drives (default: run until interrupted)
  --help             this text
  --version          the version and git commit of this build

The first line printed is "vb_view: serving http://127.0.0.1:PORT/..." once the server listens.
exit codes: 0 stopped (Ctrl-C, SIGTERM, --exit-after), 1 internal error, 2 bad input.
)";

struct Options {
  std::string mode;        // "replay", "serve", "teleop"
  std::string input;
  int port = 8765;
  bool open = false;
  std::string task_file;
  std::string tasks_dir;
  std::string vehicle;
  int pair = 0;
  uint64_t seed = 0;
  std::string soil = "verti_bench";
  std::string out_dir = "results/teleop";
  std::string operator_name;
  int exit_after = 0;
  bool help = false;
  bool version = false;
};

Options ParseArgs(int argc, char** argv) {
  Options o;
  vb::io::ArgReader args(argc, argv);
  while (args.Next()) {
    const std::string& a = args.arg();
    if (a == "--help" || a == "-h") {
      o.help = true;
    } else if (a == "--version") {
      o.version = true;
    } else if (a == "--port") {
      o.port = static_cast<int>(args.U64Value(0, 65535));
    } else if (a == "--open") {
      o.open = true;
    } else if (a == "--task") {
      o.task_file = args.Value();
    } else if (a == "--tasks") {
      o.tasks_dir = args.Value();
    } else if (a == "--vehicle") {
      o.vehicle = args.Value();
    } else if (a == "--pair") {
      o.pair = static_cast<int>(args.U64Value(0, 1000000));
    } else if (a == "--seed") {
      o.seed = args.U64Value();
    } else if (a == "--soil") {
      o.soil = args.Value();
    } else if (a == "--out") {
      o.out_dir = args.Value();
    } else if (a == "--operator") {
      o.operator_name = args.Value();
    } else if (a == "--exit-after") {
      o.exit_after = static_cast<int>(args.U64Value(1, 1000000));
    } else if (args.IsFlag()) {
      args.Unknown();
    } else if (o.mode.empty() && (a == "serve" || a == "teleop")) {
      o.mode = a;
    } else if (o.input.empty()) {
      o.input = a;
    } else {
      throw vb::InputError("", 0, a, "unexpected argument (see --help)");
    }
  }
  if (o.help || o.version) return o;
  if (o.mode.empty()) o.mode = "replay";
  if (o.input.empty()) {
    const char* what = o.mode == "replay" ? "RESULT.json" : o.mode == "serve" ? "DIR" : "TASK";
    throw vb::InputError("", 0, what, "missing (see --help)");
  }
  if (o.mode == "teleop" && o.vehicle.empty()) {
    throw vb::InputError("", 0, "--vehicle", "required for teleop (see --help)");
  }
  return o;
}

vb::view::ViewServer* g_server = nullptr;
extern "C" void OnSignal(int) {
  if (g_server != nullptr) g_server->Stop();
}

// Percent-encodes a path for a query value (keeps '/', letters, digits and -._~).
std::string QueryEncode(const std::string& s) {
  std::string out;
  for (unsigned char c : s) {
    if (std::isalnum(c) || c == '/' || c == '-' || c == '.' || c == '_' || c == '~') {
      out.push_back(static_cast<char>(c));
    } else {
      char buf[4];
      std::snprintf(buf, sizeof(buf), "%%%02X", c);
      out += buf;
    }
  }
  return out;
}

int Serve(vb::view::ServerConfig& config, const Options& o) {
  vb::view::ViewServer server(config);
  g_server = &server;
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  const std::string page =
      config.start_location.empty() ? "/viewer/index.html" : config.start_location;
  const std::string url = "http://127.0.0.1:" + std::to_string(server.port()) + page;
  std::printf("vb_view: serving %s\n", url.c_str());
  std::fflush(stdout);
  if (o.open) {
    const std::string cmd = "xdg-open '" + url + "' >/dev/null 2>&1 &";
    if (std::system(cmd.c_str()) != 0) std::fprintf(stderr, "vb_view: could not run xdg-open\n");
  }
  server.Run();
  g_server = nullptr;
  return 0;
}

int Run(const Options& o) {
  const std::string data_dir = vb::io::DataDir();
  vb::view::ServerConfig config;
  config.port = o.port;
  config.web_root = vb::io::WebDir();
  config.bundle.data_dir = data_dir;
  config.bundle.tasks_dir = o.tasks_dir.empty() ? vb::io::TasksDir() : o.tasks_dir;
  config.bundle.task_file = o.task_file;
  vb::view::SceneCache cache;
  config.bundle.cache = &cache;

  if (o.mode == "replay") {
    std::error_code ec;
    if (!fs::is_regular_file(o.input, ec)) {
      throw vb::InputError(o.input, 0, "", "no such trial record");
    }
    // Check the trial here too, so that a bad one fails on the command line, not only in the page.
    vb::view::TrialBundleJson(o.input, config.bundle);
    const fs::path result(o.input);
    config.files_root = result.parent_path().empty() ? "." : result.parent_path().string();
    config.start_location =
        "/viewer/index.html?result=" + QueryEncode(result.filename().string());
    return Serve(config, o);
  }
  if (o.mode == "serve") {
    std::error_code ec;
    if (!fs::is_directory(o.input, ec)) throw vb::InputError(o.input, 0, "", "no such directory");
    config.files_root = o.input;
    if (fs::is_regular_file(fs::path(o.input) / "report" / "trials.html", ec)) {
      config.start_location = "/files/report/trials.html";
    }
    return Serve(config, o);
  }

  // Teleoperation.
  const vb::terrain::TaskSpec task = vb::io::LoadTask(o.input);
  const std::string vehicle_file =
      vb::io::ListedDataFile(data_dir, "vehicles", o.vehicle, "--vehicle");
  const std::string soil_file = vb::io::ListedDataFile(data_dir, "soils", o.soil, "--soil");
  const vb::vehicles::VehicleParams params = vb::io::LoadVehicle(vehicle_file);
  const std::optional<vb::soil::SoilConfig> soil = vb::io::LoadSoilIfNeeded(task, soil_file);
  vb::view::TeleopOptions teleop_options;
  teleop_options.pair = o.pair;
  teleop_options.seed = o.seed;
  teleop_options.vehicle = o.vehicle;
  vb::view::TeleopSession session(task, params, soil ? &*soil : nullptr, teleop_options);

  std::error_code ec;
  fs::create_directories(o.out_dir, ec);
  if (ec) throw vb::InputError(o.out_dir, 0, "--out", "cannot create directory: " + ec.message());
  config.files_root = o.out_dir;
  config.teleop = &session;
  config.teleop_scene_json = vb::view::SceneBundleJson(task, params, o.pair);
  config.start_location = "/viewer/index.html?teleop=1";
  config.exit_after_drives = o.exit_after;
  config.record_drive = [&](vb::runner::TrialResult&& result) {
    char dir_name[32];
    std::snprintf(dir_name, sizeof(dir_name), "drive_%03d", session.drives_started());
    const fs::path dir = fs::path(o.out_dir) / dir_name;
    std::error_code mk;
    fs::create_directories(dir, mk);
    if (mk) {
      throw vb::InputError(dir.string(), 0, "--out", "cannot create directory: " + mk.message());
    }
    vb::io::Provenance provenance = vb::io::MakeProvenance(task, result.spec);
    vb::io::RecordParameterFiles(vehicle_file, o.soil, soil ? soil_file : "", &provenance);
    provenance.operator_name = o.operator_name;
    const std::string stem = vb::io::TrialFileStem(result);
    vb::io::WriteTrialFiles(result, (dir / stem).string(), provenance);
    return std::string(dir_name) + "/" + stem + ".json";
  };
  return Serve(config, o);
}

}  // namespace

int main(int argc, char** argv) {
  return vb::io::ToolMain("vb_view", [&] {
    const Options o = ParseArgs(argc, argv);
    if (o.help) return vb::io::PrintUsage(kUsage);
    if (o.version) return vb::io::PrintVersion("vb_view");
    return Run(o);
  });
}
