#include "io/output_dir.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "io/yaml_strict.h"
#include "vb/engine/error.h"

namespace vb::io {

int PrepareOutputDir(const std::string& dir, const std::string& work_subdir,
                     const std::string& settings, const std::string& tool) {
  namespace fs = std::filesystem;
  const fs::path out = dir;
  std::error_code ec;
  fs::create_directories(out / work_subdir, ec);
  if (ec) throw InputError(dir, 0, "--out", "cannot create directory: " + ec.message());
  const std::string lock_path = (out / ".lock").string();
  const int lock_fd = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd < 0 || ::flock(lock_fd, LOCK_EX | LOCK_NB) != 0) {
    throw InputError(dir, 0, "--out", "another " + tool + " is running on this directory");
  }
  for (const fs::directory_entry& d : fs::directory_iterator(out / work_subdir)) {
    if (d.path().filename().string().find(".tmp.") != std::string::npos) fs::remove(d.path(), ec);
  }
  const fs::path settings_path = out / "settings.txt";
  if (fs::exists(settings_path)) {
    std::FILE* f = std::fopen(settings_path.c_str(), "rb");
    std::string old;
    char buf[4096];
    size_t n = 0;
    while (f != nullptr && (n = std::fread(buf, 1, sizeof(buf), f)) > 0) old.append(buf, n);
    if (f) std::fclose(f);
    while (!old.empty() && old.back() == '\n') old.pop_back();
    if (old != settings) {
      throw InputError(settings_path.string(), 1, "settings",
                       "results in this directory were made with '" + old + "', this run "
                       "uses '" + settings + "'; use another --out");
    }
  } else {
    WriteFileAtomic(settings_path.string(), settings + "\n");
  }
  return lock_fd;
}

}  // namespace vb::io
