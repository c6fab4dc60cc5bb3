#include "view/view_server.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "io/result_io.h"
#include "vb/engine/error.h"
#include "view/http.h"
#include "view/websocket.h"

namespace vb::view {

namespace fs = std::filesystem;

namespace {

double NowSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

bool ReadFile(const std::string& path, std::string* text) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream ss;
  ss << in.rdbuf();
  *text = ss.str();
  return true;
}

std::string StaticFile(const std::string& root, const std::string& rel, int cache_seconds = 0) {
  if (rel.empty() || root.empty()) return HttpJsonError(404, "not found");
  const ServedFile f =
      ResolveServedFile(root, (fs::path(root) / rel).string(), kMaxServedFileBytes);
  if (f.status != 200) return HttpJsonError(f.status, rel + " " + f.problem);
  std::string body;
  if (!ReadFile(f.resolved, &body)) return HttpJsonError(404, "not found");
  return HttpResponse(200, ContentType(rel), body, cache_seconds);
}

// The vendored three.js never changes under its versioned folder: let the browser keep it (and
// its compiled code) for a day instead of parsing 0.7 MB on every page load.
constexpr int kVendorCacheSeconds = 86400;

std::string Route(const ServerConfig& cfg, const HttpRequest& request) {
  if (request.method != "GET") return HttpJsonError(405, "only GET is served");
  const std::string& path = request.path;
  if (path == "/") {
    const std::string location =
        cfg.start_location.empty() ? "/viewer/index.html" : cfg.start_location;
    std::string r = "HTTP/1.1 302 Found\r\nLocation: " + location +
                    "\r\nContent-Length: 0\r\nConnection: close\r\n\r\n";
    return r;
  }
  if (path.rfind("/viewer/", 0) == 0) {
    const std::string rel = SafeRelativePath(path, "/viewer/");
    return StaticFile(cfg.web_root, rel,
                      rel.rfind("vendor/", 0) == 0 ? kVendorCacheSeconds : 0);
  }
  if (path.rfind("/files/", 0) == 0) {
    return StaticFile(cfg.files_root, SafeRelativePath(path, "/files/"));
  }
  if (path == "/api/trial") {
    const auto it = request.query.find("result");
    if (it == request.query.end()) {
      return HttpJsonError(400, "/api/trial needs ?result=<trial JSON under the results root>");
    }
    const std::string rel = SafeRelativePath("/" + it->second, "/");
    if (rel.empty()) {
      return HttpJsonError(400, "result '" + it->second +
                                    "' is not a relative path inside the results root");
    }
    const std::string file = (fs::path(cfg.files_root) / rel).string();
    const ServedFile f = ResolveServedFile(cfg.files_root, file, kMaxServedFileBytes);
    if (f.status != 200) return HttpJsonError(f.status, "trial record " + file + " " + f.problem);
    try {
      return HttpResponse(200, "application/json; charset=utf-8",
                          TrialBundleJson(file, cfg.bundle));
    } catch (const InputError& e) {
      return HttpJsonError(422, e.what());
    }
  }
  if (path == "/api/scene") {
    if (cfg.teleop == nullptr) return HttpJsonError(404, "no teleoperation in this server");
    return HttpResponse(200, "application/json; charset=utf-8", cfg.teleop_scene_json);
  }
  if (path == "/ws") return HttpJsonError(400, "/ws expects a WebSocket upgrade");
  return HttpJsonError(404, "not found: " + path);
}

struct Connection {
  int fd = -1;
  double opened_s = 0.0;
  std::string in;
  std::string out;
  bool websocket = false;
  bool close_after_write = false;
};

}  // namespace

struct ViewServer::Impl {
  ServerConfig config;
  int listen_fd = -1;
  int port = 0;
  std::atomic<bool> stop{false};
  std::vector<Connection> connections;
  int driver_fd = -1;          // the WebSocket connection that drives the teleop session
  int drives_recorded = 0;
  double next_state_s = 0.0;
  double accept_paused_until_s = 0.0;   // accept back-off (EMFILE)

  void Accept();
  void ReadFrom(Connection& c);
  void HandleHttp(Connection& c);
  void HandleWebSocket(Connection& c);
  void SendWs(Connection& c, const std::string& text) {
    c.out += EncodeServerFrame(WsOpcode::kText, text);
  }
  Connection* Driver() {
    for (Connection& c : connections) {
      if (c.fd == driver_fd && c.websocket) return &c;
    }
    return nullptr;
  }
  void Tick();
};

ViewServer::ViewServer(const ServerConfig& config) : impl_(std::make_unique<Impl>()) {
  impl_->config = config;
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) throw InputError("", 0, "--port", std::string("socket: ") + std::strerror(errno));
  const int one = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);   // 127.0.0.1 only, by design
  addr.sin_port = htons(static_cast<uint16_t>(config.port));
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0 || ::listen(fd, 16) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd);
    throw InputError("", 0, "--port",
                     "cannot listen on 127.0.0.1:" + std::to_string(config.port) + ": " + why);
  }
  socklen_t len = sizeof(addr);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
  impl_->listen_fd = fd;
  impl_->port = ntohs(addr.sin_port);
}

ViewServer::~ViewServer() {
  for (Connection& c : impl_->connections) ::close(c.fd);
  if (impl_->listen_fd >= 0) ::close(impl_->listen_fd);
}

int ViewServer::port() const { return impl_->port; }
void ViewServer::Stop() { impl_->stop = true; }

std::string ViewServer::Respond(const HttpRequest& request) const {
  return Route(impl_->config, request);
}

void ViewServer::Impl::Accept() {
  while (connections.size() < kMaxConnections) {
    const int fd = ::accept(listen_fd, nullptr, nullptr);
    if (fd < 0) {
      // Out of descriptors: the pending connection stays in the queue and the listening socket
      // stays readable, so polling it again at once would spin (W08 of the probe at 8ff4def).
      // Wait a little instead; connections that close free descriptors meanwhile.
      if (errno == EMFILE || errno == ENFILE || errno == ENOBUFS || errno == ENOMEM) {
        accept_paused_until_s = NowSeconds() + kAcceptBackoff_s;
      }
      return;
    }
    ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
    Connection c;
    c.fd = fd;
    c.opened_s = NowSeconds();
    connections.push_back(std::move(c));
  }
}

void ViewServer::Impl::HandleHttp(Connection& c) {
  HttpRequest request;
  std::string error;
  const HttpParse parsed = ParseHttpRequest(c.in, &request, &error);
  if (parsed == HttpParse::kIncomplete) return;
  c.close_after_write = true;
  if (parsed == HttpParse::kBad) {
    c.out += HttpJsonError(400, error);
    c.in.clear();
    return;
  }
  // What follows the head: WebSocket frames after an upgrade, else never read (one request per
  // connection).
  c.in.erase(0, c.in.find("\r\n\r\n") + 4);
  // Every request and every WebSocket upgrade: only this server's own pages (NEW-10).
  const std::string foreign = HostOriginProblem(request, port);
  if (!foreign.empty()) {
    c.in.clear();
    c.out += HttpJsonError(403, foreign);
    return;
  }
  const auto header = [&](const char* name) {
    const auto it = request.headers.find(name);
    return it == request.headers.end() ? std::string() : it->second;
  };
  if (request.method == "GET" && request.path == "/ws" && !header("sec-websocket-key").empty()) {
    if (config.teleop == nullptr) {
      c.out += HttpJsonError(404, "no teleoperation in this server");
      return;
    }
    if (Driver() != nullptr) {
      c.out += HttpJsonError(409, "another page is driving already");
      return;
    }
    c.out += "HTTP/1.1 101 Switching Protocols\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
             "Sec-WebSocket-Accept: " + WebSocketAccept(header("sec-websocket-key")) + "\r\n\r\n";
    c.websocket = true;
    c.close_after_write = false;
    driver_fd = c.fd;
    return;
  }
  c.in.clear();
  try {
    c.out += Route(config, request);
  } catch (const std::exception& e) {
    // One request's failure (out of memory for a bundle, say) is that request's 500, never the
    // server's end.
    c.out += HttpJsonError(500, std::string("internal error: ") + e.what());
  }
}

void ViewServer::Impl::HandleWebSocket(Connection& c) {
  while (true) {
    WsFrame frame;
    size_t used = 0;
    std::string error;
    const WsDecode d = DecodeClientFrame(c.in, &frame, &used, &error);
    if (d == WsDecode::kIncomplete) return;
    if (d == WsDecode::kBad) {
      c.out += EncodeServerFrame(WsOpcode::kClose, std::string("\x03\xea", 2) + error);
      c.close_after_write = true;
      c.in.clear();
      return;
    }
    c.in.erase(0, used);
    if (frame.opcode == WsOpcode::kClose) {
      c.out += EncodeServerFrame(WsOpcode::kClose, "");
      c.close_after_write = true;
      return;
    }
    if (frame.opcode == WsOpcode::kPing) {
      c.out += EncodeServerFrame(WsOpcode::kPong, frame.payload);
      continue;
    }
    if (frame.opcode != WsOpcode::kText || !frame.fin) {
      SendWs(c, "{\"type\": \"error\", \"message\": \"expected one unfragmented text frame\"}");
      continue;
    }
    const std::string problem = config.teleop->HandleMessage(frame.payload, NowSeconds());
    if (!problem.empty()) {
      SendWs(c, "{\"type\": \"error\", \"message\": " + io::JsonString(problem) + "}");
    }
  }
}

void ViewServer::Impl::Tick() {
  if (config.teleop == nullptr) return;
  TeleopSession& session = *config.teleop;
  const double now = NowSeconds();
  session.AdvanceTo(now);
  Connection* driver = Driver();
  if (driver != nullptr && now >= next_state_s) {
    SendWs(*driver, session.StateJson());
    next_state_s = now + config.state_period_s;
  }
  if (session.has_finished_drive()) {
    runner::TrialResult result = session.TakeFinishedDrive();
    const std::string status(runner::TrialStatusName(result.status));
    std::string message;
    try {
      const std::string rel = config.record_drive(std::move(result));
      message = "{\"type\": \"recorded\", \"status\": " + io::JsonString(status) +
                ", \"result\": " + io::JsonString(rel) + "}";
      ++drives_recorded;
      std::printf("vb_view: drive recorded: %s (%s)\n", rel.c_str(), status.c_str());
      std::fflush(stdout);
    } catch (const InputError& e) {
      message = "{\"type\": \"error\", \"message\": " + io::JsonString(e.what()) + "}";
      std::fprintf(stderr, "vb_view: error: %s\n", e.what());
    } catch (const IoError& e) {
      // A full disk loses this drive, not the session: the page is told, the operator can free
      // space and drive again (NEW-3 of the probe at 8ff4def).
      const std::string what = std::string("I/O error: ") + e.what() +
                               "; the drive was not recorded";
      message = "{\"type\": \"error\", \"message\": " + io::JsonString(what) + "}";
      std::fprintf(stderr, "vb_view: %s\n", what.c_str());
    }
    if (driver != nullptr) {
      SendWs(*driver, session.StateJson());
      SendWs(*driver, message);
    }
    if (config.exit_after_drives > 0 && drives_recorded >= config.exit_after_drives) stop = true;
  }
}

void ViewServer::Run() {
  Impl& m = *impl_;
  std::vector<pollfd> fds;
  char buf[16384];
  bool draining = false;
  while (true) {
    if (m.stop && !draining) {
      // Flush what is queued (the last state and "recorded" message), then leave.
      draining = true;
    }
    if (draining) {
      bool pending = false;
      for (const Connection& c : m.connections) pending = pending || !c.out.empty();
      if (!pending) break;
    }
    fds.clear();
    const bool accepting = m.connections.size() < kMaxConnections &&
                           NowSeconds() >= m.accept_paused_until_s;
    fds.push_back({m.listen_fd, static_cast<short>(accepting ? POLLIN : 0), 0});
    for (const Connection& c : m.connections) {
      fds.push_back({c.fd, static_cast<short>(POLLIN | (c.out.empty() ? 0 : POLLOUT)), 0});
    }
    const bool driving = m.config.teleop != nullptr && m.config.teleop->driving();
    const int timeout_ms = driving || draining || !accepting ? 2 : 100;
    ::poll(fds.data(), fds.size(), timeout_ms);
    if (fds[0].revents & POLLIN) m.Accept();
    for (size_t i = 1; i < fds.size(); ++i) {
      Connection& c = m.connections[i - 1];
      if (fds[i].revents & (POLLIN | POLLHUP | POLLERR)) {
        const ssize_t n = ::recv(c.fd, buf, sizeof(buf), 0);
        if (n <= 0) {
          if (n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK)) {
            c.close_after_write = true;
            c.out.clear();
          }
        } else if (c.websocket) {
          c.in.append(buf, static_cast<size_t>(n));
          m.HandleWebSocket(c);
        } else if (!c.close_after_write) {
          c.in.append(buf, static_cast<size_t>(n));
          m.HandleHttp(c);
        }
        // Else: bytes after an answered request are read and dropped, never kept (W07: a client
        // that sent 2 GiB after its request grew the server by as much).
      }
      if (!c.out.empty()) {
        const ssize_t n = ::send(c.fd, c.out.data(), c.out.size(), MSG_NOSIGNAL);
        if (n > 0) {
          c.out.erase(0, static_cast<size_t>(n));
        } else if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK) {
          c.out.clear();
          c.close_after_write = true;
        }
      }
    }
    // Close finished and idle connections.
    const double now = NowSeconds();
    for (size_t i = 0; i < m.connections.size();) {
      Connection& c = m.connections[i];
      if (!c.websocket && !c.close_after_write && now - c.opened_s > m.config.http_idle_limit_s) {
        c.close_after_write = true;
        c.out.clear();
      }
      // A response nobody takes, or a page that stopped reading its WebSocket: closed.
      const bool stuck = c.websocket ? c.out.size() > kMaxWebSocketBacklogBytes
                                     : now - c.opened_s > m.config.http_response_limit_s;
      if (stuck) {
        c.close_after_write = true;
        c.out.clear();
      }
      if (c.close_after_write && c.out.empty()) {
        if (c.fd == m.driver_fd) {
          // The driver left: end the drive so that it is recorded, not driven on blindly.
          m.driver_fd = -1;
          if (m.config.teleop != nullptr && m.config.teleop->driving()) {
            m.config.teleop->HandleMessage("stop", NowSeconds());
          }
        }
        ::close(c.fd);
        m.connections.erase(m.connections.begin() + static_cast<long>(i));
      } else {
        ++i;
      }
    }
    if (!draining) m.Tick();
  }
}

}  // namespace vb::view
