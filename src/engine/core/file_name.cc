#include "vb/engine/file_name.h"

namespace vb {

std::string FileNameComponentProblem(const std::string& name, size_t max_length) {
  if (name.empty()) return "name is empty";
  if (name.size() > max_length) {
    return "name is " + std::to_string(name.size()) + " characters long, at most " +
           std::to_string(max_length) + " are allowed";
  }
  for (char ch : name) {
    const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                    (ch >= '0' && ch <= '9') || ch == '_' || ch == '.' || ch == '-';
    if (!ok) {
      return "name may contain only letters, digits, '_', '.' and '-' (it becomes part of "
             "output file names)";
    }
  }
  if (name[0] == '.' || name[0] == '-') return "name must not start with '.' or '-'";
  return "";
}

}  // namespace vb
