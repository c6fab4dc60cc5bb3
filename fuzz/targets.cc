#include "targets.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdlib>
#include <exception>
#include <fstream>
#include <new>
#include <string>

#include <sys/stat.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "frame.h"
#include "io/batch_io.h"
#include "io/mesh_loader.h"
#include "io/original_io.h"
#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "vb/batch/index.h"
#include "server.h"
#include "vb/engine/error.h"
#include "view/http.h"
#include "view/websocket.h"

namespace vb::fuzz {
namespace {

// The bytes as a file without touching the disk: an anonymous memory file, named by its
// /proc/self/fd path (a regular file to stat and open), for loaders that take a path.
class MemoryFile {
 public:
  explicit MemoryFile(const std::string& bytes) {
    fd_ = ::memfd_create("vb_fuzz", MFD_CLOEXEC);
    if (fd_ < 0) return;
    size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
      if (n <= 0) break;
      done += static_cast<size_t>(n);
    }
    path_ = "/proc/self/fd/" + std::to_string(fd_);
  }
  ~MemoryFile() {
    if (fd_ >= 0) ::close(fd_);
  }
  MemoryFile(const MemoryFile&) = delete;
  MemoryFile& operator=(const MemoryFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  int fd_ = -1;
  std::string path_;
};

// Runs `parse`, mapping the contract to a verdict.
template <typename Parse>
std::string Check(Parse parse) {
  try {
    parse();
  } catch (const InputError&) {
    return "";   // refused with a located message: what a loader is for
  } catch (const std::bad_alloc&) {
    return "std::bad_alloc escaped (an unbounded allocation)";
  } catch (const std::exception& e) {
    return std::string("exception other than InputError escaped: ") + e.what();
  } catch (...) {
    return "a non-standard exception escaped";
  }
  return "";
}

// Task text located in the source tree's tasks/ folder, so the seeds' relative height-image
// paths (../data/worlds/envNNN.png) resolve and the image decoder is fuzzed too.
std::string TaskYaml(const std::string& bytes) {
  return Check([&] { io::LoadTaskText(bytes, VB_SOURCE_DIR "/tasks/fuzz_input.yaml"); });
}

std::string VehicleYaml(const std::string& bytes) {
  const MemoryFile f(bytes);
  return Check([&] { io::LoadVehicle(f.path()); });
}

std::string SoilYaml(const std::string& bytes) {
  const MemoryFile f(bytes);
  return Check([&] { io::LoadSoil(f.path()); });
}

// The importer's config reader, with the real world image of sample 42 (its checks against the
// image run too).
std::string OriginalConfig(const std::string& bytes) {
  const MemoryFile f(bytes);
  return Check([&] {
    io::LoadOriginalWorld(f.path(), VB_SOURCE_DIR "/../shared/verti_bench_samples/world42.bmp", "");
  });
}

std::string LabelsNpy(const std::string& bytes) {
  const MemoryFile f(bytes);
  return Check([&] {
    int rows = 0, cols = 0;
    io::ReadNpyInt32(f.path(), &rows, &cols);
  });
}

std::string TrialJson(const std::string& bytes) {
  const MemoryFile f(bytes);
  return Check([&] {
    const batch::TrialRow row = io::ReadTrialJson(f.path());
    io::TrajectoryProblem(f.path(), row);
  });
}

std::string BatchJson(const std::string& bytes) {
  const MemoryFile f(bytes);
  return Check([&] { io::ReadBatchJson(f.path()); });
}

std::string IndexCsv(const std::string& bytes) {
  return Check([&] { batch::ParseIndexCsv(bytes, "index.csv"); });
}

// The vb_gym protocol's frame reader on a stream of bytes: it must return kOk, kEof or
// kFramingError for anything a client sends, frame after frame.
std::string GymFrames(const std::string& bytes) {
  const MemoryFile f(bytes);
  return Check([&] {
    const int fd = ::open(f.path().c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return;
    gym::Frame frame;
    std::string error;
    for (int k = 0; k < 64 && gym::ReadFrame(fd, &frame, &error) == gym::ReadStatus::kOk; ++k) {
    }
    ::close(fd);
  });
}

// The vb_gym server on a stream of frames: every request frame gets one reply, and every reply is
// a JSON object of strict UTF-8 (nlohmann's parser refuses anything else) with a "type": deep
// nesting, bytes that are not UTF-8 and absurd values included (NEW-1, NEW-2). A fresh,
// unconfigured server per input; requests that would write files (write_result, write_index)
// are skipped, so the fuzzer never writes where a request points.
std::string GymRequests(const std::string& bytes) {
  const MemoryFile f(bytes);
  std::string finding;
  const std::string verdict = Check([&] {
    const int fd = ::open(f.path().c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return;
    gym::Server server(VB_SOURCE_DIR "/data");
    gym::Frame frame;
    std::string error, reply;
    std::vector<uint8_t> payload;
    for (int k = 0; k < 16 && gym::ReadFrame(fd, &frame, &error) == gym::ReadStatus::kOk; ++k) {
      if (frame.header.find("write_") != std::string::npos) continue;
      bool keep_going = true;
      try {
        keep_going = server.Handle(frame, &reply, &payload);
      } catch (const std::exception& e) {
        finding = std::string("Handle threw: ") + e.what();
        break;
      }
      try {
        const nlohmann::json j = nlohmann::json::parse(reply);
        if (!j.is_object() || !j.contains("type")) finding = "a reply without a type: " + reply;
      } catch (const nlohmann::json::exception& e) {
        finding = std::string("a reply that is not strict JSON (") + e.what() + ")";
      }
      if (!finding.empty() || !keep_going) break;
    }
    ::close(fd);
  });
  return finding.empty() ? verdict : finding;
}

// vb_view's request handling without sockets: the HTTP head parser, the Host/Origin check, the
// path mapping, and the WebSocket frame decoder on whatever follows the head. No exception may
// escape, and a mapped path never holds a ".." segment (NEW-10's surfaces).
std::string HttpRequestBytes(const std::string& bytes) {
  std::string finding;
  const std::string verdict = Check([&] {
    view::HttpRequest request;
    std::string error;
    if (view::ParseHttpRequest(bytes, &request, &error) == view::HttpParse::kRequest) {
      view::HostOriginProblem(request, 8765);
      for (const char* prefix : {"/files/", "/viewer/", "/"}) {
        const std::string rel = view::SafeRelativePath(request.path, prefix);
        if (("/" + rel + "/").find("/../") != std::string::npos) {
          finding = "SafeRelativePath let '..' through: " + rel;
        }
      }
      std::string rest = bytes.substr(bytes.find("\r\n\r\n") + 4);
      for (int k = 0; k < 64 && !rest.empty(); ++k) {
        view::WsFrame frame;
        size_t used = 0;
        if (view::DecodeClientFrame(rest, &frame, &used, &error) != view::WsDecode::kFrame) break;
        if (used == 0 || used > rest.size()) {
          finding = "DecodeClientFrame consumed " + std::to_string(used) + " of " +
                    std::to_string(rest.size()) + " bytes";
          break;
        }
        rest.erase(0, used);
      }
    }
  });
  return finding.empty() ? verdict : finding;
}

// The mesh loader on a file of any format assimp knows, with hostile neighbours: FIFOs named as
// an OBJ's material library and a glTF's buffers would be (cube.mtl, buf.bin), and a file
// outside the mesh's directory (NEW-12). The first byte picks the extension. A hang is a finding
// (libFuzzer's -timeout), so is any escape but InputError.
std::filesystem::path MeshDirRoot() {
  return std::filesystem::temp_directory_path() / ("vb_fuzz_mesh_" + std::to_string(::getpid()));
}
void RemoveMeshDir() {
  std::error_code ec;
  std::filesystem::remove_all(MeshDirRoot(), ec);
}

std::string MeshFile(const std::string& bytes) {
  namespace fs = std::filesystem;
  static const fs::path dir = [] {
    const fs::path d = MeshDirRoot() / "meshes";
    fs::create_directories(d);
    for (const char* fifo : {"cube.mtl", "buf.bin", "a.png"}) ::mkfifo((d / fifo).c_str(), 0600);
    std::ofstream(d.parent_path() / "outside.bin") << std::string(48, '\0');
    std::atexit(RemoveMeshDir);
    return d;
  }();
  static const char* const kExtensions[] = {".obj", ".gltf", ".stl", ".ply", ".glb", ".off"};
  const std::string ext = bytes.empty() ? ".obj" : kExtensions[static_cast<uint8_t>(bytes[0]) % 6];
  const std::string path = (dir / ("mesh" + ext)).string();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!bytes.empty()) out.write(bytes.data() + 1, static_cast<std::streamsize>(bytes.size() - 1));
  }
  return Check([&] { io::LoadMeshVertices(path, "fuzz_task.yaml", 1, "obstacles.shapes.rock.mesh"); });
}

}  // namespace

const std::vector<Target>& Targets() {
  static const std::vector<Target> kTargets = {
      {"task_yaml", &TaskYaml, {"tasks/env000.yaml", "tasks/env042.yaml", "tasks/env061.yaml",
                                "tasks/env095.yaml"}},
      {"vehicle_yaml", &VehicleYaml, {"data/vehicles/*.yaml"}},
      {"soil_yaml", &SoilYaml, {"data/soils/*.yaml"}},
      {"original_config", &OriginalConfig, {"../shared/verti_bench_samples/config*.yaml"}},
      {"labels_npy", &LabelsNpy, {"../shared/verti_bench_samples/labels42_low.npy"}},
      {"trial_json", &TrialJson, {}},
      {"batch_json", &BatchJson, {}},
      {"index_csv", &IndexCsv, {}},
      {"gym_frame", &GymFrames, {}},
      {"gym_request", &GymRequests, {}},
      {"http_request", &HttpRequestBytes, {}},
      {"mesh_file", &MeshFile, {}},
  };
  return kTargets;
}

const Target* FindTarget(const std::string& name) {
  for (const Target& t : Targets()) {
    if (name == t.name) return &t;
  }
  return nullptr;
}

}  // namespace vb::fuzz
