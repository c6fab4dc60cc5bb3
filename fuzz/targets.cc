#include "targets.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <exception>
#include <new>
#include <string>

#include "frame.h"
#include "io/batch_io.h"
#include "io/original_io.h"
#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "vb/batch/index.h"
#include "vb/engine/error.h"

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
