// vb_view's server: routes and trial bundles (good and bad trials), the loopback-only socket,
// and a teleoperated drive end to end over a real WebSocket connection.
#include "view/view_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include "io/result_io.h"
#include "io/task_io.h"
#include "support/cli.h"
#include "support/worlds.h"
#include "view/http.h"
#include "view/websocket.h"

namespace vb::view {
namespace {

namespace fs = std::filesystem;

const std::string kSource = VB_SOURCE_DIR;

fs::path TempDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("vb_view_test_" + name + "_" +
                                                    std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void WriteText(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

HttpRequest Get(const std::string& target) {
  HttpRequest r;
  std::string error;
  const HttpParse p =
      ParseHttpRequest("GET " + target + " HTTP/1.1\r\nHost: x\r\n\r\n", &r, &error);
  EXPECT_EQ(p, HttpParse::kRequest) << error;
  return r;
}

int Status(const std::string& response) { return std::stoi(response.substr(9, 3)); }
std::string Body(const std::string& response) {
  return response.substr(response.find("\r\n\r\n") + 4);
}

// A short real trial of env042 pair 1, written as vb_run writes it, in `dir`.
std::string WriteTrial(const fs::path& dir,
                       const std::string& task_file = kSource + "/tasks/env042.yaml",
                       runner::RuleSet rule_set = runner::RuleSet::kVb) {
  const terrain::TaskSpec task = io::LoadTask(task_file);
  runner::EpisodeRules rules;
  rules.rule_set = rule_set;
  rules.time_limit_s = 1.0;
  rules.trajectory_every_n_steps = 10;
  runner::TrialSpec spec;
  spec.pair_index = 1;
  const runner::TrialResult r = runner::RunTrial(task, test::Hmmwv(), spec, rules);
  const std::string stem = io::TrialFileStem(r);
  io::WriteTrialJson(r, (dir / (stem + ".json")).string(), io::MakeProvenance(task, spec));
  io::WriteTrajectoryCsv(r, (dir / (stem + "_traj.csv")).string());
  return stem;
}

class ViewServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = TempDir("routes");
    fs::create_directories(root_ / "web");
    WriteText(root_ / "web" / "index.html", "<html>viewer</html>");
    fs::create_directories(root_ / "results");
    stem_ = WriteTrial(root_ / "results");
    config_.port = 0;
    config_.web_root = (root_ / "web").string();
    config_.files_root = (root_ / "results").string();
    config_.bundle.data_dir = kSource + "/data";
    config_.bundle.tasks_dir = kSource + "/tasks";
  }
  void TearDown() override { fs::remove_all(root_); }
  std::string Respond(const std::string& target) {
    ViewServer server(config_);
    return server.Respond(Get(target));
  }
  fs::path root_;
  std::string stem_;
  ServerConfig config_;
};

TEST_F(ViewServerTest, ServesThePageAndTheResultsReadOnly) {
  std::string r = Respond("/viewer/index.html");
  EXPECT_EQ(Status(r), 200);
  EXPECT_EQ(Body(r), "<html>viewer</html>");
  EXPECT_NE(r.find("text/html"), std::string::npos);
  r = Respond("/files/" + stem_ + "_traj.csv");
  EXPECT_EQ(Status(r), 200);
  EXPECT_EQ(Body(r).rfind("t_s,x_m,y_m,z_m", 0), 0u);
  EXPECT_EQ(Status(Respond("/files/../web/index.html")), 404);
  EXPECT_EQ(Status(Respond("/files/%2e%2e/web/index.html")), 404);
  EXPECT_EQ(Status(Respond("/viewer/missing.js")), 404);
  EXPECT_EQ(Status(Respond("/nowhere")), 404);
  EXPECT_EQ(Status(Respond("/api/scene")), 404);   // no teleoperation in this server
  EXPECT_EQ(Status(Respond("/ws")), 400);          // not an upgrade
  ViewServer server(config_);
  HttpRequest post = Get("/viewer/index.html");
  post.method = "POST";
  EXPECT_EQ(Status(server.Respond(post)), 405);
  config_.start_location = "/viewer/index.html?result=a.json";
  r = Respond("/");
  EXPECT_EQ(Status(r), 302);
  EXPECT_NE(r.find("Location: /viewer/index.html?result=a.json\r\n"), std::string::npos);
}

TEST_F(ViewServerTest, TrialBundleCarriesSceneAndTrialFiles) {
  const std::string r = Respond("/api/trial?result=" + stem_ + ".json");
  ASSERT_EQ(Status(r), 200) << Body(r).substr(0, 500);
  const std::string b = Body(r);
  EXPECT_EQ(b.rfind("{\"format\": \"vb-viewer\", \"version\": 1, \"pair\": 1,", 0), 0u);
  EXPECT_NE(b.find("\"name\": \"env042\""), std::string::npos);
  EXPECT_NE(b.find("\"heights\": {\"rows\": 129, \"cols\": 129, \"values_m\": ["),
            std::string::npos);
  EXPECT_NE(b.find("\"semantics\": {\"rows\": 16, \"cols\": 16"), std::string::npos);
  EXPECT_NE(b.find("{\"kind\": \"rock\", \"min_m\": ["), std::string::npos);
  EXPECT_NE(b.find("\"goal_radius_m\": 10"), std::string::npos);
  EXPECT_NE(b.find("\"wheel_radius_m\": 0.467"), std::string::npos);
  EXPECT_NE(b.find("\"trajectory_csv\": \"t_s,x_m,"), std::string::npos);
  EXPECT_NE(b.find("\"trajectory_error\": null"), std::string::npos);
  // 129 x 129 heights, each once.
  const size_t start = b.find("\"values_m\": [") + 13;
  const std::string values = b.substr(start, b.find(']', start) - start);
  EXPECT_EQ(std::count(values.begin(), values.end(), ',') + 1, 129 * 129);
}

TEST(TrialBundleTest, JsonTextEscapesAsJsonString) {
  std::string all;
  for (int c = 1; c < 256; ++c) all += static_cast<char>(c);
  all += std::string("\0tail\"quoted\"\\", 16);
  EXPECT_EQ(JsonText(all), io::JsonString(all));
  EXPECT_EQ(JsonText(""), "\"\"");
  EXPECT_EQ(JsonText("t_s,x_m\n0,1\n"), "\"t_s,x_m\\n0,1\\n\"");
}

TEST_F(ViewServerTest, MissingTrajectoryIsReportedToThePage) {
  fs::remove(root_ / "results" / (stem_ + "_traj.csv"));
  const std::string r = Respond("/api/trial?result=" + stem_ + ".json");
  ASSERT_EQ(Status(r), 200);
  EXPECT_NE(Body(r).find("\"trajectory_csv\": null, \"trajectory_error\": \"cannot read "),
            std::string::npos);
}

TEST_F(ViewServerTest, BadTrialsGiveErrorsNamingTheFile) {
  EXPECT_EQ(Status(Respond("/api/trial")), 400);
  EXPECT_EQ(Status(Respond("/api/trial?result=../results/" + stem_ + ".json")), 400);
  std::string r = Respond("/api/trial?result=nothing.json");
  EXPECT_EQ(Status(r), 404);
  EXPECT_NE(Body(r).find("nothing.json does not exist"), std::string::npos);

  WriteText(root_ / "results" / "broken.json", "{\"task\": \"env042\", \"pair\": ");
  r = Respond("/api/trial?result=broken.json");
  EXPECT_EQ(Status(r), 422);
  EXPECT_NE(Body(r).find("broken.json"), std::string::npos);

  // The record names a vehicle that does not exist.
  const fs::path json = root_ / "results" / (stem_ + ".json");
  std::string text = testing::ReadFileBytes(json);
  std::string edited = text;
  edited.replace(edited.find("\"vehicle\": \"hmmwv\""), 18, "\"vehicle\": \"tank\"");
  WriteText(root_ / "results" / "tank.json", edited);
  r = Respond("/api/trial?result=tank.json");
  EXPECT_EQ(Status(r), 422);
  EXPECT_NE(Body(r).find("unknown vehicle 'tank'"), std::string::npos) << Body(r);
}

TEST_F(ViewServerTest, TaskThatDoesNotMatchIsRefused) {
  // Another environment.
  config_.bundle.task_file = kSource + "/tasks/env000.yaml";
  std::string r = Respond("/api/trial?result=" + stem_ + ".json");
  EXPECT_EQ(Status(r), 422);
  EXPECT_NE(Body(r).find("task 'env000' does not match the trial's task 'env042'"),
            std::string::npos)
      << Body(r);
  // The same environment, edited (one rock moved): its hash differs from the record's.
  terrain::TaskSpec task = io::LoadTask(kSource + "/tasks/env042.yaml");
  ASSERT_FALSE(task.rocks.empty());
  task.rocks[0].x_m += 1.0;
  task.height_image = fs::absolute(fs::path(kSource) / "tasks" / task.height_image).string();
  const fs::path edited = root_ / "env042.yaml";
  io::SaveTask(task, edited.string());
  config_.bundle.task_file = edited.string();
  r = Respond("/api/trial?result=" + stem_ + ".json");
  EXPECT_EQ(Status(r), 422);
  EXPECT_NE(Body(r).find("does not match the trial: its FNV-1a is"), std::string::npos) << Body(r);
}

TEST_F(ViewServerTest, CachedWorldIsReloadedWhenItsFileChanges) {
  // A trial of a private copy of env042, then the copy edited under a running cache.
  terrain::TaskSpec task = io::LoadTask(kSource + "/tasks/env042.yaml");
  task.height_image = fs::absolute(fs::path(kSource) / "tasks" / task.height_image).string();
  const fs::path copy = root_ / "env042.yaml";
  io::SaveTask(task, copy.string());
  const std::string stem = WriteTrial(root_, copy.string());
  SceneCache cache;
  BundleOptions options = config_.bundle;
  options.cache = &cache;
  const std::string record = (root_ / (stem + ".json")).string();
  const std::string first = TrialBundleJson(record, options);
  EXPECT_EQ(TrialBundleJson(record, options), first);   // from the cache, identical
  BundleOptions uncached = options;
  uncached.cache = nullptr;
  EXPECT_EQ(TrialBundleJson(record, uncached), first);
  task.rocks[0].x_m += 1.0;
  io::SaveTask(task, copy.string());
  try {
    TrialBundleJson(record, options);
    FAIL() << "an edited world must not be served from the cache";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("does not match the trial"), std::string::npos)
        << e.what();
  }
}

// The page draws the goal circle of the trial's rules: vb's 10 m, or the original's 8 m sphere
// around the marker cut at the ground (7.75 m) for a verti_bench record.
TEST_F(ViewServerTest, TheTrialCarriesTheGoalCircleOfItsRules) {
  const std::string vb_bundle =
      TrialBundleJson((root_ / "results" / (stem_ + ".json")).string(), config_.bundle);
  EXPECT_NE(vb_bundle.find("\"goal_radius_m\": 10,"), std::string::npos);   // task and trial
  fs::create_directories(root_ / "original");
  const std::string stem = WriteTrial(root_ / "original", kSource + "/tasks/env042.yaml",
                                      runner::RuleSet::kVertiBench);
  const std::string bundle =
      TrialBundleJson((root_ / "original" / (stem + ".json")).string(), config_.bundle);
  const size_t trial = bundle.find("\n\"trial\": ");
  ASSERT_NE(trial, std::string::npos);
  EXPECT_NE(bundle.find("\"goal_radius_m\": 10,"), std::string::npos);   // the task's (vb's)
  EXPECT_NE(bundle.find("\"goal_radius_m\": 7.74596669241483", trial), std::string::npos)
      << bundle.substr(trial, 200);
}

TEST_F(ViewServerTest, RecordedTaskSetPathIsFoundBesideTheResultsNotInTheCheckout) {
  // A private version of env042 in its own task set mine/tasks/, results in mine/results/: the
  // record names "tasks/env042.yaml"; the checkout's tasks/env042.yaml (the configured task
  // set) has the same name and path but other bytes, and must not be taken.
  terrain::TaskSpec task = io::LoadTask(kSource + "/tasks/env042.yaml");
  task.rocks[0].x_m += 1.0;
  task.height_image = fs::absolute(fs::path(kSource) / "tasks" / task.height_image).string();
  fs::create_directories(root_ / "mine" / "tasks");
  fs::create_directories(root_ / "mine" / "results");
  const fs::path copy = root_ / "mine" / "tasks" / "env042.yaml";
  io::SaveTask(task, copy.string());
  const std::string stem = WriteTrial(root_ / "mine" / "results", copy.string());
  const std::string record = (root_ / "mine" / "results" / (stem + ".json")).string();
  EXPECT_NE(testing::ReadFileBytes(record).find("\"task_file\": \"tasks/env042.yaml\""),
            std::string::npos);
  const std::string bundle = TrialBundleJson(record, config_.bundle);
  EXPECT_NE(bundle.find("\"file\": " + io::JsonString(copy.string())), std::string::npos)
      << bundle.substr(0, 300);
  // Moved away from its task set, and the configured set has only the other version: refused.
  fs::rename(record, root_ / (stem + ".json"));
  fs::rename(root_ / "mine" / "results" / (stem + "_traj.csv"), root_ / (stem + "_traj.csv"));
  try {
    TrialBundleJson((root_ / (stem + ".json")).string(), config_.bundle);
    FAIL() << "the checkout's env042 must not stand in for the private version";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("does not match the trial"), std::string::npos)
        << e.what();
  }
  // Given its task set, it is found again.
  BundleOptions given = config_.bundle;
  given.tasks_dir = (root_ / "mine" / "tasks").string();
  EXPECT_NE(TrialBundleJson((root_ / (stem + ".json")).string(), given)
                .find("\"file\": " + io::JsonString(copy.string())),
            std::string::npos);
}

TEST_F(ViewServerTest, NoSymbolicLinkLeadsOutOfTheServedDirectory) {
  // W02 of the probe at 8ff4def: a link in the results directory served /etc/passwd.
  fs::create_symlink("/etc/passwd", root_ / "results" / "passwd.txt");
  fs::create_symlink(root_ / "web", root_ / "results" / "web_dir");
  std::string r = Respond("/files/passwd.txt");
  EXPECT_EQ(Status(r), 403) << r;
  EXPECT_NE(Body(r).find("outside the served directory"), std::string::npos) << r;
  EXPECT_EQ(Status(Respond("/files/web_dir/index.html")), 403);
  EXPECT_EQ(Status(Respond("/api/trial?result=passwd.txt")), 403);
  // A link that stays inside is served.
  fs::create_symlink(root_ / "results" / (stem_ + "_traj.csv"), root_ / "results" / "same.csv");
  EXPECT_EQ(Status(Respond("/files/same.csv")), 200);
}

TEST_F(ViewServerTest, HugeFilesAreRefusedNotReadWhole) {
  // W06 of the probe at 8ff4def: a sparse 64 GiB trajectory ended the server with bad_alloc.
  const fs::path traj = root_ / "results" / (stem_ + "_traj.csv");
  fs::resize_file(traj, 64ull << 30);
  const std::string r = Respond("/api/trial?result=" + stem_ + ".json");
  EXPECT_EQ(Status(r), 200) << r.substr(0, 300);
  EXPECT_NE(Body(r).find("\"trajectory_csv\": null"), std::string::npos);
  EXPECT_NE(Body(r).find("bytes, more than the"), std::string::npos);
  EXPECT_EQ(Status(Respond("/files/" + stem_ + "_traj.csv")), 413);
}

TEST_F(ViewServerTest, ListensOnLoopbackOnly) {
  ViewServer server(config_);
  ASSERT_GT(server.port(), 0);
  // The kernel's table of listening TCP sockets: local address 127.0.0.1 (0100007F) at our port.
  std::ifstream tcp("/proc/net/tcp");
  std::string line;
  char want[32];
  std::snprintf(want, sizeof(want), "0100007F:%04X 00000000:0000 0A", server.port());
  char any[32];
  std::snprintf(any, sizeof(any), "00000000:%04X", server.port());
  bool found = false;
  while (std::getline(tcp, line)) {
    found = found || line.find(want) != std::string::npos;
    EXPECT_EQ(line.find(any), std::string::npos) << "listening on all interfaces: " << line;
  }
  EXPECT_TRUE(found) << "no listening socket on 127.0.0.1:" << server.port();
}

// The Host header a browser sends for the server's own page.
std::string LocalHost(int port) { return "127.0.0.1:" + std::to_string(port); }

// A minimal blocking client for the end-to-end test.
class Client {
 public:
  explicit Client(int port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = htons(static_cast<uint16_t>(port));
    connected_ = ::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof(a)) == 0;
    timeval tv{5, 0};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof(tv));
  }
  ~Client() { ::close(fd_); }
  bool connected() const { return connected_; }
  void Send(const std::string& bytes) { ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL); }
  // Reads until `marker` is in the buffer (or 5 s without data); returns everything read.
  std::string ReadUntil(const std::string& marker) {
    char buf[8192];
    while (buffer_.find(marker) == std::string::npos) {
      const ssize_t n = ::recv(fd_, buf, sizeof(buf), 0);
      if (n <= 0) break;
      buffer_.append(buf, static_cast<size_t>(n));
    }
    return buffer_;
  }

 private:
  int fd_ = -1;
  bool connected_ = false;
  std::string buffer_;
};

TEST(ViewServerIdleTest, SilentClientIsDisconnectedAndOthersAreServed) {
  ServerConfig config;
  config.port = 0;
  config.http_idle_limit_s = 0.3;
  ViewServer server(config);
  std::thread thread([&] { server.Run(); });
  Client silent(server.port());
  Client partial(server.port());
  ASSERT_TRUE(silent.connected() && partial.connected());
  partial.Send("GET /api/scene HTTP/1.1\r\n");   // never finished
  {
    Client other(server.port());   // served while the two hang around
    other.Send("GET /nowhere HTTP/1.1\r\nHost: " + LocalHost(server.port()) + "\r\n\r\n");
    EXPECT_NE(other.ReadUntil("}").find("404 Not Found"), std::string::npos);
  }
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(silent.ReadUntil("never"), "");     // closed by the server: recv returns 0
  EXPECT_EQ(partial.ReadUntil("never"), "");
  const double waited =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(waited, 4.0);   // well before the client's own 5 s receive timeout
  server.Stop();
  thread.join();
}

// A teleoperation session of the HMMWV on `task`, and a server configuration driving it.
TeleopSession HmmwvSession(const terrain::TaskSpec& task) {
  TeleopOptions options;
  options.vehicle = "hmmwv";
  return TeleopSession(task, test::Hmmwv(), nullptr, options);
}
ServerConfig TeleopConfig(TeleopSession* session) {
  ServerConfig config;
  config.port = 0;
  config.teleop = session;
  config.teleop_scene_json = "{\"scene\": true}";
  return config;
}

TEST(ViewServerHostTest, ForeignHostsAndOriginsAre403OnEveryRequestAndUpgrade) {
  const terrain::TaskSpec task = test::PlaneTask();
  TeleopSession session = HmmwvSession(task);
  ServerConfig config = TeleopConfig(&session);
  ViewServer server(config);
  std::thread thread([&] { server.Run(); });
  const std::string upgrade = "Upgrade: websocket\r\nConnection: Upgrade\r\n"
                              "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n";
  for (const std::string& head :
       {std::string("GET /api/scene HTTP/1.1\r\nHost: attacker.example\r\n\r\n"),
        std::string("GET /api/scene HTTP/1.1\r\n\r\n"),
        "GET /ws HTTP/1.1\r\nHost: " + LocalHost(server.port()) +
            "\r\nOrigin: http://attacker.example\r\n" + upgrade + "\r\n",
        "GET /ws HTTP/1.1\r\nHost: attacker.example:" + std::to_string(server.port()) + "\r\n" +
            upgrade + "\r\n"}) {
    Client c(server.port());
    c.Send(head);
    const std::string reply = c.ReadUntil("}");
    EXPECT_NE(reply.find("403 Forbidden"), std::string::npos) << head << " -> " << reply;
  }
  // The page's own origin drives (the seat is free: the refused upgrades took nothing).
  Client ws(server.port());
  ws.Send("GET /ws HTTP/1.1\r\nHost: " + LocalHost(server.port()) + "\r\nOrigin: http://" +
          LocalHost(server.port()) + "\r\n" + upgrade + "\r\n");
  EXPECT_NE(ws.ReadUntil("\r\n\r\n").find("101 Switching Protocols"), std::string::npos);
  server.Stop();
  thread.join();
}

TEST(ViewServerTeleopTest, DriveOverAWebSocketIsRecorded) {
  const terrain::TaskSpec task = test::PlaneTask();
  TeleopSession session = HmmwvSession(task);
  ServerConfig config = TeleopConfig(&session);
  config.exit_after_drives = 1;
  runner::TrialResult recorded;
  config.record_drive = [&](runner::TrialResult&& r) {
    recorded = std::move(r);
    return std::string("drive_001/x.json");
  };
  ViewServer server(config);
  std::thread thread([&] { server.Run(); });

  {
    Client http(server.port());
    ASSERT_TRUE(http.connected());
    http.Send("GET /api/scene HTTP/1.1\r\nHost: " + LocalHost(server.port()) + "\r\n\r\n");
    EXPECT_NE(http.ReadUntil("{\"scene\": true}").find("{\"scene\": true}"), std::string::npos);
  }
  Client ws(server.port());
  ASSERT_TRUE(ws.connected());
  ws.Send("GET /ws HTTP/1.1\r\nHost: " + LocalHost(server.port()) + "\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
          "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n");
  const std::string hello = ws.ReadUntil("\r\n\r\n");
  ASSERT_NE(hello.find("101 Switching Protocols"), std::string::npos) << hello;
  EXPECT_NE(hello.find("Sec-WebSocket-Accept: s3pPLMBiTxaQ9kYGzzhZRbK+xOo="), std::string::npos);
  {
    // A second page cannot take over the wheel.
    Client second(server.port());
    second.Send("GET /ws HTTP/1.1\r\nHost: " + LocalHost(server.port()) + "\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                "Sec-WebSocket-Key: AAAAAAAAAAAAAAAAAAAAAA==\r\n\r\n");
    EXPECT_NE(second.ReadUntil("\r\n\r\n").find("409 Conflict"), std::string::npos);
  }
  ws.Send(EncodeClientFrame(WsOpcode::kText, "start", 0xA1B2C3D4u));
  ws.Send(EncodeClientFrame(WsOpcode::kText, "command 1 0 0", 0x01020304u));
  ws.Send(EncodeClientFrame(WsOpcode::kText, "command 7 0 0", 0x01020304u));   // rejected
  std::this_thread::sleep_for(std::chrono::milliseconds(800));
  ws.Send(EncodeClientFrame(WsOpcode::kText, "stop", 0x0F0F0F0Fu));
  const std::string frames = ws.ReadUntil("\"type\": \"recorded\"");
  thread.join();

  EXPECT_NE(frames.find("\"type\": \"state\""), std::string::npos);
  EXPECT_NE(frames.find("throttle 7 is outside [0, 1]"), std::string::npos);
  EXPECT_NE(frames.find("\"result\": \"drive_001/x.json\""), std::string::npos);
  ASSERT_FALSE(recorded.trajectory.empty());
  // Real time: about 0.8 s of simulation for 0.8 s of wall time (a loaded machine may lag, never
  // lead), with full throttle held from the first steps on.
  EXPECT_GT(recorded.sim_time_s, 0.5);
  EXPECT_LT(recorded.sim_time_s, 3.0);
  EXPECT_EQ(recorded.trajectory.back().throttle, 1.0);
  EXPECT_EQ(recorded.spec.system, "teleop");
}

}  // namespace
}  // namespace vb::view
