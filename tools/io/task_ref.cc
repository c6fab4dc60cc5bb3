#include "io/task_ref.h"

#include <filesystem>
#include <system_error>

namespace vb::io {
namespace fs = std::filesystem;

std::string TaskSetPath(const std::string& task_file) {
  std::error_code ec;
  fs::path p = fs::absolute(task_file, ec);
  if (ec) p = task_file;
  p = p.lexically_normal();
  const fs::path set = p.parent_path().filename();
  if (set.empty()) return p.filename().string();
  return (set / p.filename()).string();
}

std::vector<std::string> TaskFileCandidates(const std::string& recorded,
                                            const std::string& record_path,
                                            const std::string& tasks_dir) {
  std::vector<std::string> out;
  if (recorded.empty()) return out;
  fs::path rec(recorded);
  if (rec.is_absolute()) {   // an older record: its path, then as "<task set>/<file>"
    out.push_back(recorded);
    rec = TaskSetPath(recorded);
  }
  if (!tasks_dir.empty()) out.push_back((fs::path(tasks_dir) / rec.filename()).string());
  std::error_code ec;
  fs::path dir = fs::absolute(record_path, ec);
  if (ec) return out;
  dir = dir.lexically_normal().parent_path();
  while (true) {
    out.push_back((dir / rec).lexically_normal().string());
    if (dir == dir.root_path() || dir.parent_path() == dir) break;
    dir = dir.parent_path();
  }
  return out;
}

}  // namespace vb::io
