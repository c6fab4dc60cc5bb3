#include "common.h"

#include <fstream>
#include <sstream>

#include "vb/engine/error.h"

namespace vb_report {

namespace fs = std::filesystem;

std::string ReadText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw vb::InputError(p.string(), 0, "", "cannot read");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<vb::batch::TrialRow> ReadIndex(const fs::path& dir) {
  const fs::path p = dir / "index.csv";
  return vb::batch::ParseIndexCsv(ReadText(p), p.string());
}

std::string Stem(const vb::batch::TrialRow& r) { return vb::batch::RowStem(r); }

}  // namespace vb_report
