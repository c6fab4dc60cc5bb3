// vb_view's HTTP + WebSocket server: serves the viewer page (web/viewer), a results directory
// read-only, trial bundles for the page (/api/trial), and, for teleoperation, the scene
// (/api/scene) and a WebSocket (/ws) that drives a TeleopSession at real time. Listens on
// 127.0.0.1 only: the viewer is a local tool, and teleoperation must not be reachable from other
// machines. One thread: a poll() loop over the listening socket and the connections; the
// episode is stepped between polls.
//
// Routes (GET only; anything else is 405, unknown paths 404, bad requests 400):
//   /                      302 to start_location (a trial's replay, a trial list, teleoperation)
//   /viewer/<file>         the page's static files
//   /files/<file>          files under the results root (no "..", no absolute paths)
//   /api/trial?result=REL  trial bundle (trial_bundle.h) of REL under the results root;
//                          422 with {"error"} naming the file for a bad trial
//   /api/scene             teleoperation: the scene bundle of the driven task (404 otherwise)
//   /ws                    teleoperation: WebSocket (one driver at a time; 409 for a second)
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "view/teleop_session.h"
#include "view/trial_bundle.h"

namespace vb::view {

// The server's limits (docs/reliability.md "The servers' limits"): what one client can make it
// hold or spend. Beyond each, the client gets an error response or its connection is closed; the
// server goes on serving the others.
constexpr uint64_t kMaxServedFileBytes = 256ull << 20;  // a file under /files/ or /viewer/ (413)
constexpr size_t kMaxConnections = 64;          // open at once; more wait in the listen queue
constexpr size_t kMaxWebSocketBacklogBytes = 8u << 20;   // unsent messages to a page that does
                                                         // not read them: then it is closed
constexpr double kAcceptBackoff_s = 0.25;       // no accept() this long after EMFILE/ENFILE

struct ServerConfig {
  int port = 8765;                 // 0: any free port (the chosen one is printed and returned)
  std::string web_root;            // directory of index.html
  std::string files_root;          // results root for /files/ and /api/trial
  BundleOptions bundle;
  std::string start_location;      // where / redirects to (default: the page without a trial)
  // Teleoperation (optional): the session, its scene bundle, and what to do with an ended
  // drive: write it and return its record's path relative to files_root.
  TeleopSession* teleop = nullptr;
  std::string teleop_scene_json;
  std::function<std::string(runner::TrialResult&&)> record_drive;
  int exit_after_drives = 0;       // > 0: stop after that many recorded drives (tests)
  double state_period_s = 1.0 / 30.0;   // live state messages to the page
  // An HTTP connection without a whole request after this long is closed (a stuck or idle
  // client must not hold the server's attention forever). WebSocket connections are exempt.
  double http_idle_limit_s = 10.0;
  // An HTTP connection whose response is not taken within this long of its opening is closed (a
  // client that asks for a bundle and never reads it).
  double http_response_limit_s = 120.0;
};

class ViewServer {
 public:
  // Binds 127.0.0.1:port and listens; throws InputError naming the port if that fails.
  explicit ViewServer(const ServerConfig& config);
  ~ViewServer();
  ViewServer(const ViewServer&) = delete;
  ViewServer& operator=(const ViewServer&) = delete;

  int port() const;
  // Serves until Stop() (also from a signal handler) or exit_after_drives.
  void Run();
  void Stop();

  // The complete response to one request (no sockets involved): the static and API routes.
  // WebSocket upgrades are answered by Run(); here /ws gives 400 unless it is an upgrade.
  std::string Respond(const struct HttpRequest& request) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vb::view
