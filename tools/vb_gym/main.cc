// vb_gym: hosts one gym environment per process and serves the versioned frame protocol of
// docs/gym_protocol.md on stdin/stdout (the Python package in python/ is its client). Thin on
// purpose: frames in, Server::Handle, frames out.
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "frame.h"
#include "io/cli_args.h"
#include "io/data_dir.h"
#include "io/result_io.h"
#include "server.h"
#include "vb/engine/error.h"

namespace {

constexpr const char* kUsage = R"(usage: vb_gym [--help] [--version]

Hosts one environment (tasks, vehicle, one running episode) and serves the vb gym protocol,
version 1 (docs/gym_protocol.md), on stdin/stdout: length-prefixed frames of a JSON header and
raw little-endian arrays. Requests: hello, configure, reset, step, result, write_result,
write_index, close.
Meant to be started by a client (the Python package vb_gym, python/), not by hand.

Every request gets one reply; a bad request gets an error frame naming what is wrong and the
server stays usable. Diagnostics go to stderr, never to stdout.

The process ends when the client sends close (exit 0), closes its end of the pipe (exit 0), or
sends a frame that breaks the framing (an error frame, then exit 2): lengths above the limits
(header 1 MiB, payload 256 MiB), a stream closed inside a frame, or a frame whose first byte
arrived more than 60 s before its last. A header nested deeper than 32 levels, bytes that are
not UTF-8, and a write that fails (a full disk) are error replies; the server stays usable.

environment:
  VB_DATA_DIR   directory of vehicles/ and soils/ (default: share/vb/data next to this
                program's bin/)

exit codes: 0 client closed, 1 internal error, 2 bad arguments or broken framing
)";

}  // namespace

int main(int argc, char** argv) {
  return vb::io::ToolMain("vb_gym", [&] {
    vb::io::ArgReader args(argc, argv);
    while (args.Next()) {
      if (args.Is("--help") || args.Is("-h")) return vb::io::PrintUsage(kUsage);
      if (args.Is("--version")) return vb::io::PrintVersion("vb_gym");
      args.Unknown();
    }
    if (!vb::gym::HostIsLittleEndian()) {
      std::fprintf(stderr, "vb_gym: error: the protocol's arrays are little-endian; this host "
                           "is not\n");
      return 1;
    }
    // A client that goes away makes write() fail with EPIPE (handled) instead of killing us.
    ::signal(SIGPIPE, SIG_IGN);
    // The protocol owns the original stdout; anything else printing to fd 1 goes to stderr, so
    // it can never corrupt a frame.
    const int out_fd = ::dup(STDOUT_FILENO);
    if (out_fd < 0 || ::dup2(STDERR_FILENO, STDOUT_FILENO) < 0) {
      std::fprintf(stderr, "vb_gym: error: cannot set up stdout\n");
      return 1;
    }
    vb::gym::Server server(vb::io::DataDir());
    vb::gym::Frame request;
    std::string reply;
    std::vector<uint8_t> payload;
    while (true) {
      std::string error;
      const vb::gym::ReadStatus status = vb::gym::ReadFrame(STDIN_FILENO, &request, &error);
      if (status == vb::gym::ReadStatus::kEof) return 0;
      if (status == vb::gym::ReadStatus::kFramingError) {
        const std::string header =
            "{\"type\":\"error\",\"op\":\"?\",\"kind\":\"framing\",\"message\":" +
            vb::io::JsonString(error) + "}";
        vb::gym::WriteFrame(out_fd, header, {});
        std::fprintf(stderr, "vb_gym: error: %s\n", error.c_str());
        return 2;
      }
      const bool keep_going = server.Handle(request, &reply, &payload);
      if (reply.size() > vb::gym::kMaxHeaderBytes || payload.size() > vb::gym::kMaxPayloadBytes) {
        // The client's reader would refuse it (and a uint32 length must not wrap): say so.
        reply = "{\"type\":\"error\",\"op\":\"?\",\"kind\":\"request\",\"message\":"
                "\"the reply would exceed the protocol's frame limits (a header of " +
                std::to_string(reply.size()) + " bytes); ask for less at a time\"}";
        payload.clear();
      }
      if (!vb::gym::WriteFrame(out_fd, reply, payload)) return 0;   // the client has gone
      if (!keep_going) return 0;
    }
  });
}
