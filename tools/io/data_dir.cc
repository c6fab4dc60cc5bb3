#include "io/data_dir.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "io/cli_args.h"
#include "vb/engine/error.h"
#include "vb/engine/file_name.h"

namespace vb::io {
namespace fs = std::filesystem;

namespace {

std::string Env(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr ? v : "";
}

// An empty, missing or unreadable vehicles/ directory: the reason, or "" if it is usable.
std::string DataProblem(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return "no such directory";
  const fs::path vehicles = dir / "vehicles";
  if (!fs::is_directory(vehicles, ec)) return "it has no vehicles/ directory";
  if (::access(vehicles.c_str(), R_OK | X_OK) != 0) return "its vehicles/ is not readable";
  fs::directory_iterator it(vehicles, ec);
  for (; !ec && it != fs::directory_iterator(); it.increment(ec)) {
    if (it->path().extension() == ".yaml") return "";
  }
  return "its vehicles/ holds no .yaml vehicle files";
}

}  // namespace

std::vector<std::string> YamlNamesIn(const std::string& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() == ".yaml" && it->is_regular_file(ec)) {
      names.push_back(it->path().stem().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::string ListedDataFile(const std::string& data_dir, const std::string& kind,
                           const std::string& name, const std::string& key,
                           const std::string& file) {
  const std::vector<std::string> names = YamlNamesIn(data_dir + "/" + kind);
  const std::string problem = FileNameComponentProblem(name, kMaxDataNameLength);
  if (!problem.empty() || std::find(names.begin(), names.end(), name) == names.end()) {
    std::string singular = kind;
    if (!singular.empty() && singular.back() == 's') singular.pop_back();
    throw InputError(file, 0, key,
                     "unknown " + singular + " '" + name + "' in " + data_dir + "/" + kind +
                         (problem.empty() ? "" : " (" + problem + ")") +
                         "; valid: " + JoinNames(names));
  }
  return data_dir + "/" + kind + "/" + name + ".yaml";
}

std::string ExecutableDir() {
  std::error_code ec;
  const fs::path exe = fs::canonical("/proc/self/exe", ec);
  return ec ? std::string() : exe.parent_path().string();
}

std::string ShareDir() {
  const std::string exe_dir = ExecutableDir();
  if (exe_dir.empty()) return "";
  return (fs::path(exe_dir).parent_path() / "share" / "vb").lexically_normal().string();
}

std::string DataDir() {
  const std::string env = Env("VB_DATA_DIR");
  std::string dir;
  std::string why;
  if (!env.empty()) {
    dir = env;
    why = "from the environment variable VB_DATA_DIR";
  } else {
    const std::string share = ShareDir();
    if (share.empty()) {
      throw InputError("VB_DATA_DIR", 0, "",
                       "the data directory: cannot locate this executable (/proc/self/exe) to "
                       "find share/vb/data next to it; set VB_DATA_DIR to the directory holding "
                       "vehicles/, soils/ and perception/");
    }
    dir = share + "/data";
    why = "share/vb/data next to this executable's bin/ (" + ExecutableDir() +
          "); VB_DATA_DIR is not set";
  }
  const std::string problem = DataProblem(dir);
  if (!problem.empty()) {
    throw InputError(dir, 0, "",
                     "not a usable vb data directory: " + problem + " (looked here " + why +
                         "). Point vb at its data with VB_DATA_DIR=DIR, DIR holding vehicles/, "
                         "soils/ and perception/: an install's <prefix>/share/vb/data or the "
                         "source tree's data/");
  }
  return dir;
}

std::string TasksDir() {
  const std::string share = ShareDir();
  return share.empty() ? "" : share + "/tasks";
}

std::string WebDir() {
  const std::string env = Env("VB_WEB_DIR");
  if (!env.empty()) return env;
  const std::string share = ShareDir();
  return share.empty() ? "" : share + "/web/viewer";
}

}  // namespace vb::io
