#include "vb/batch/index.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <map>
#include <utility>
#include <algorithm>

#include "vb/engine/error.h"
#include "vb/engine/file_name.h"
#include "vb/engine/runner/outcome_rules.h"
#include "vb/engine/text_format.h"

namespace vb::batch {
namespace {

const char* const kColumns[] = {
    "matrix_index", "task",       "pair",          "seed",       "vehicle",
    "system",       "perception", "scale",      "elevation",     "terrain",    "density",
    "status",       "traversal_time_s", "sim_time_s", "final_goal_distance_m",
    "mean_abs_roll_deg", "mean_abs_pitch_deg", "task_fnv1a64", "vb_version", "git_commit",
    "host",         "wall_time_s", "task_file",    "message",  "rules"};
constexpr size_t kNumColumns = sizeof(kColumns) / sizeof(kColumns[0]);
// "rules" is written only when a row was decided by other rules than vb's, so indexes of
// default runs keep their format; "perception" and "rules" may be missing when read.
constexpr size_t kRulesColumn = kNumColumns - 1;
bool OptionalColumn(size_t i) {
  return std::string(kColumns[i]) == "perception" || i == kRulesColumn;
}
// Longest task, vehicle or system name in a row (terrain::TaskLimits::kMaxNameLength).
constexpr size_t kMaxNameLength = 128;

std::string Num(double x) { return std::isfinite(x) ? FormatExact(x) : std::string(); }

std::string Field(const std::string& s) { return CsvField(s); }

// Splits CSV text into records of fields (RFC 4180 quoting; newlines allowed inside quotes).
// Each record remembers its 1-based starting line.
struct Record {
  int line = 0;
  std::vector<std::string> fields;
};
std::vector<Record> SplitCsv(const std::string& text, const std::string& source) {
  std::vector<Record> records;
  Record rec;
  std::string field;
  bool quoted = false, field_started = false;
  int line = 1;
  rec.line = 1;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"') {
        if (i + 1 < text.size() && text[i + 1] == '"') {
          field += '"';
          ++i;
        } else {
          quoted = false;
        }
      } else {
        if (c == '\n') ++line;
        field += c;
      }
    } else if (c == '"' && field.empty() && !field_started) {
      quoted = true;
      field_started = true;
    } else if (c == ',') {
      rec.fields.push_back(field);
      field.clear();
      field_started = false;
    } else if (c == '\n' || c == '\r') {
      if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      rec.fields.push_back(field);
      records.push_back(rec);
      rec = Record();
      field.clear();
      field_started = false;
      rec.line = ++line;
    } else {
      field += c;
      field_started = true;
    }
  }
  if (quoted) throw InputError(source, line, "", "unterminated quoted field");
  if (field_started || !field.empty() || !rec.fields.empty()) {
    rec.fields.push_back(field);
    records.push_back(rec);
  }
  return records;
}

// An empty field is "no value" (NaN); otherwise a finite number >= 0 (every number of the index
// is a time, a distance, a mean of absolute angles or a scale): the writer prints nothing else,
// so "nan", "inf" or "-3" mean an edited or corrupt index, which would silently skew the report.
double ParseDouble(const std::string& s, const std::string& source, int line, const char* key) {
  if (s.empty()) return std::numeric_limits<double>::quiet_NaN();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (*end != '\0' || errno != 0 || !std::isfinite(v)) {
    throw InputError(source, line, key, "'" + s + "' is not a finite number");
  }
  if (v < 0.0) throw InputError(source, line, key, "'" + s + "' is negative");
  return v;
}

uint64_t ParseU64(const std::string& s, const std::string& source, int line, const char* key) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0' || errno != 0 || s[0] == '-') {
    throw InputError(source, line, key, "'" + s + "' is not a non-negative integer");
  }
  return v;
}

}  // namespace

bool IsRunnerStatus(const std::string& s) {
  return s == "success" || s == "rollover" || s == "stuck" || s == "timeout" || s == "sim_error" ||
         s == "out_of_bounds";
}
bool IsKnownStatus(const std::string& s) {
  return IsRunnerStatus(s) || s == "error" || s == "crashed";
}

std::string RowStem(const TrialRow& r) {
  return r.task + "_p" + std::to_string(r.pair) + "_s" + std::to_string(r.seed) + "_" +
         r.vehicle + "_" + r.system + PerceptionStemSuffix(r.perception);
}

std::string PerceptionStemSuffix(const std::string& perception) {
  return perception.empty() || perception == "none" ? std::string() : "_perc-" + perception;
}

std::string IndexCsv(const std::vector<TrialRow>& rows) {
  const bool with_rules = std::any_of(rows.begin(), rows.end(),
                                      [](const TrialRow& r) { return r.rules != "vb"; });
  std::string text;
  for (size_t i = 0; i < kNumColumns; ++i) {
    if (i == kRulesColumn && !with_rules) continue;
    text += std::string(i ? "," : "") + kColumns[i];
  }
  text += "\n";
  for (const TrialRow& r : rows) {
    text += std::to_string(r.matrix_index) + "," + Field(r.task) + "," + std::to_string(r.pair) +
            "," + std::to_string(r.seed) + "," + Field(r.vehicle) + "," + Field(r.system) + "," +
            Field(r.perception) + "," + Num(r.scale) + "," + Field(r.elevation) + "," + Field(r.terrain) + "," +
            Field(r.density) + "," + Field(r.status) + "," + Num(r.traversal_time_s) + "," +
            Num(r.sim_time_s) + "," + Num(r.final_goal_distance_m) + "," +
            Num(r.mean_abs_roll_deg) + "," + Num(r.mean_abs_pitch_deg) + "," +
            Field(r.task_fnv1a64) + "," + Field(r.vb_version) + "," + Field(r.git_commit) + "," +
            Field(r.host) + "," + Num(r.wall_time_s) + "," + Field(r.task_file) + "," +
            Field(r.message) + (with_rules ? "," + Field(r.rules) : std::string()) + "\n";
  }
  return text;
}

std::vector<TrialRow> ParseIndexCsv(const std::string& text, const std::string& source) {
  const std::vector<Record> records = SplitCsv(text, source);
  if (records.empty()) throw InputError(source, 1, "", "empty index (no header)");
  const Record& header = records.front();
  // Columns by name, in the order of kColumns; "perception" may be missing (indexes written
  // before perception models existed: ground truth), "rules" too (vb's rules).
  size_t col[kNumColumns];
  for (size_t i = 0; i < kNumColumns; ++i) col[i] = SIZE_MAX;
  for (size_t j = 0; j < header.fields.size(); ++j) {
    size_t i = 0;
    while (i < kNumColumns && header.fields[j] != kColumns[i]) ++i;
    if (i == kNumColumns) {
      throw InputError(source, 1, header.fields[j], "unexpected column");
    }
    if (col[i] != SIZE_MAX) throw InputError(source, 1, header.fields[j], "duplicate column");
    col[i] = j;
  }
  for (size_t i = 0; i < kNumColumns; ++i) {
    if (col[i] == SIZE_MAX && !OptionalColumn(i)) {
      throw InputError(source, 1, kColumns[i], "missing column");
    }
  }
  const size_t width = header.fields.size();
  std::vector<TrialRow> rows;
  std::map<std::string, int> first_line;   // trial stem -> line of its row
  for (size_t i = 1; i < records.size(); ++i) {
    const Record& rec = records[i];
    if (rec.fields.size() == 1 && rec.fields[0].empty()) continue;  // blank line
    if (rec.fields.size() != width) {
      throw InputError(source, rec.line, "", "row has " + std::to_string(rec.fields.size()) +
                                                 " fields, expected " + std::to_string(width));
    }
    const int ln = rec.line;
    // Field of column kColumns[c] (the default of a missing optional column).
    static const std::string kNone = "none", kVbRules = "vb";
    auto f = [&](size_t c) -> const std::string& {
      if (col[c] == SIZE_MAX) return c == kRulesColumn ? kVbRules : kNone;
      return rec.fields[col[c]];
    };
    TrialRow r;
    r.matrix_index = ParseU64(f(0), source, ln, "matrix_index");
    r.task = f(1);
    r.pair = static_cast<int>(ParseU64(f(2), source, ln, "pair"));
    r.seed = ParseU64(f(3), source, ln, "seed");
    r.vehicle = f(4);
    r.system = f(5);
    r.perception = f(6);
    r.scale = ParseDouble(f(7), source, ln, "scale");
    r.elevation = f(8);
    r.terrain = f(9);
    r.density = f(10);
    r.status = f(11);
    if (!IsKnownStatus(r.status)) {
      throw InputError(source, ln, "status", "unknown status '" + r.status + "'");
    }
    r.traversal_time_s = ParseDouble(f(12), source, ln, "traversal_time_s");
    r.sim_time_s = ParseDouble(f(13), source, ln, "sim_time_s");
    r.final_goal_distance_m = ParseDouble(f(14), source, ln, "final_goal_distance_m");
    r.mean_abs_roll_deg = ParseDouble(f(15), source, ln, "mean_abs_roll_deg");
    r.mean_abs_pitch_deg = ParseDouble(f(16), source, ln, "mean_abs_pitch_deg");
    r.task_fnv1a64 = f(17);
    r.vb_version = f(18);
    r.git_commit = f(19);
    r.host = f(20);
    r.wall_time_s = ParseDouble(f(21), source, ln, "wall_time_s");
    r.task_file = f(22);
    r.message = f(23);
    r.rules = f(kRulesColumn);
    runner::ParseRuleSet("rules", r.rules, source, ln);
    // The names become file names (trials/<stem>.json, report/topdown/<stem>.png): an edited
    // index must not send vb_report or a merge outside its directories.
    const std::pair<const char*, const std::string*> names[] = {
        {"task", &r.task}, {"vehicle", &r.vehicle}, {"system", &r.system},
        {"perception", &r.perception}};
    for (const auto& [key, value] : names) {
      const std::string problem = FileNameComponentProblem(*value, kMaxNameLength);
      if (!problem.empty()) throw InputError(source, ln, key, "'" + *value + "': " + problem);
    }
    // One row per trial: a duplicated row would be counted twice in every statistic.
    const auto [it, inserted] = first_line.emplace(RowStem(r), ln);
    if (!inserted) {
      throw InputError(source, ln, "", "trial " + it->first + " is listed twice (first at line " +
                                           std::to_string(it->second) + ")");
    }
    rows.push_back(std::move(r));
  }
  return rows;
}

std::string StableFields(const TrialRow& r) {
  TrialRow copy = r;
  copy.host.clear();
  copy.wall_time_s = 0.0;
  copy.task_file.clear();  // the same task may be reached by another relative path
  return IndexCsv({copy});
}

}  // namespace vb::batch
