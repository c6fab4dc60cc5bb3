// Result writers. Text is assembled in memory and then written in one go to a temporary file
// beside the target, which is renamed over it: rename() within a directory is atomic on POSIX.
#include "io/result_io.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/build_info.h"
#include "io/task_ref.h"
#include "vb/batch/index.h"
#include "vb/engine/error.h"
#include "vb/engine/text_format.h"

namespace vb::io {

namespace {

constexpr double kRadToDeg = 180.0 / kPi;

std::string Number(double x) { return FormatExact(x); }

void WriteAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr) {
    throw IoError(path, std::string("cannot write: ") + std::strerror(errno));
  }
  const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  const bool flushed = std::fflush(f) == 0 && ::fsync(::fileno(f)) == 0;
  const int saved_errno = errno;
  std::fclose(f);
  if (!written || !flushed || std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = written && flushed ? errno : saved_errno;
    std::remove(tmp.c_str());
    throw IoError(path, std::string("cannot write: ") + std::strerror(err));
  }
}

// Whole file as bytes; empty if it cannot be opened.
std::string ReadBytes(const std::string& path, bool* ok) {
  std::ifstream in(path, std::ios::binary);
  *ok = static_cast<bool>(in);
  if (!in) return "";
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string StatsJson(const runner::SignalStats& s) {
  return "{\"mean\": " + JsonNumber(s.mean) + ", \"var\": " + JsonNumber(s.var) +
         ", \"max\": " + JsonNumber(s.max) + "}";
}

// Minimal pretty printer for a flat object: one "key": value per line, in insertion order.
class JsonObject {
 public:
  explicit JsonObject(int indent) : indent_(indent) {}
  void Raw(const std::string& key, const std::string& json_value) {
    fields_.push_back(std::string(indent_ + 2, ' ') + JsonString(key) + ": " + json_value);
  }
  void Str(const std::string& key, const std::string& v) { Raw(key, JsonString(v)); }
  void Num(const std::string& key, double v) { Raw(key, JsonNumber(v)); }
  void Int(const std::string& key, long long v) { Raw(key, std::to_string(v)); }
  void UInt(const std::string& key, uint64_t v) { Raw(key, std::to_string(v)); }
  std::string Text() const {
    std::string out = "{\n";
    for (size_t i = 0; i < fields_.size(); ++i) {
      out += fields_[i] + (i + 1 < fields_.size() ? ",\n" : "\n");
    }
    return out + std::string(indent_, ' ') + "}";
  }

 private:
  int indent_;
  std::vector<std::string> fields_;
};

}  // namespace

namespace {

// Length of the well-formed UTF-8 sequence starting at s[i] (RFC 3629: no overlongs, no
// surrogates, at most U+10FFFF), or 0 if the bytes there are not one.
size_t Utf8SequenceLength(const std::string& s, size_t i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  size_t n = 0;
  unsigned char lo = 0x80, hi = 0xBF;   // allowed range of the second byte
  if (c >= 0xC2 && c <= 0xDF) {
    n = 2;
  } else if (c >= 0xE0 && c <= 0xEF) {
    n = 3;
    if (c == 0xE0) lo = 0xA0;
    if (c == 0xED) hi = 0x9F;
  } else if (c >= 0xF0 && c <= 0xF4) {
    n = 4;
    if (c == 0xF0) lo = 0x90;
    if (c == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (i + n > s.size() || byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (size_t k = 2; k < n; ++k) {
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  }
  return n;
}

}  // namespace

std::string JsonString(const std::string& s) {
  std::string out = "\"";
  for (size_t i = 0; i < s.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c >= 0x80) {
      // JSON text is UTF-8 (RFC 8259 §8.1): a byte that is not part of a well-formed sequence
      // (a Latin-1 file name, say) becomes U+FFFD so the record stays readable (DEF-7).
      const size_t n = Utf8SequenceLength(s, i);
      if (n == 0) {
        out += "\\ufffd";
      } else {
        out.append(s, i, n);
        i += n - 1;
      }
      continue;
    }
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof(buf), "\\u%04x", c);
          out += buf;
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  return out + "\"";
}

std::string JsonNumber(double x) { return std::isfinite(x) ? Number(x) : "null"; }

uint64_t Fnv1a64(const std::string& bytes, uint64_t hash) {
  for (unsigned char c : bytes) {
    hash ^= c;
    hash *= 0x100000001b3ull;
  }
  return hash;
}

std::string FileFnv1a64Hex(const std::string& path) {
  bool ok = false;
  const std::string bytes = ReadBytes(path, &ok);
  if (!ok) throw InputError(path, 0, "", "cannot read the file to hash it");
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016" PRIx64, Fnv1a64(bytes));
  return hex;
}

void RecordParameterFiles(const std::string& vehicle_file, const std::string& soil_name,
                          const std::string& soil_file, Provenance* p) {
  p->vehicle_fnv1a64 = FileFnv1a64Hex(vehicle_file);
  p->soil = soil_file.empty() ? "" : soil_name;
  p->soil_fnv1a64 = soil_file.empty() ? "" : FileFnv1a64Hex(soil_file);
}

std::string TaskFnv1a64(const terrain::TaskSpec& task) {
  bool ok = false;
  const std::string task_bytes = ReadBytes(task.source_file, &ok);
  if (!ok) throw InputError(task.source_file, 0, "", "cannot read the task file to hash it");
  uint64_t hash = Fnv1a64(task_bytes);
  if (!task.height_image.empty()) {
    const std::filesystem::path image =
        std::filesystem::path(task.source_file).parent_path() / task.height_image;
    hash = Fnv1a64(ReadBytes(image.string(), &ok), hash);
  }
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016" PRIx64, hash);
  return hex;
}

Provenance MakeProvenance(const terrain::TaskSpec& task, const runner::TrialSpec& spec,
                          const std::string& task_fnv1a64) {
  Provenance p;
  p.vb_version = VB_VERSION;
  p.git_commit = BuildGitCommit();
  p.task_file = TaskSetPath(task.source_file);   // the same on every machine (io/task_ref.h)
  p.vehicle = spec.vehicle;
  p.system = spec.system;
  p.seed = spec.seed;

  p.task_fnv1a64 = task_fnv1a64.empty() ? TaskFnv1a64(task) : task_fnv1a64;

  char host[256] = {0};
  if (::gethostname(host, sizeof(host) - 1) == 0) p.host = host;
  return p;
}

std::string TrialFileStem(const runner::TrialResult& r) {
  return r.task_name + "_p" + std::to_string(r.spec.pair_index) + "_s" +
         std::to_string(r.spec.seed) + "_" + r.spec.vehicle + "_" + r.spec.system +
         batch::PerceptionStemSuffix(r.perception);
}

void WriteTrialJson(const runner::TrialResult& r, const std::string& path,
                    const Provenance& provenance) {
  const bool success = r.status == runner::TrialStatus::kSuccess;
  const std::string status(runner::TrialStatusName(r.status));

  JsonObject prov(2);
  prov.Str("vb_version", provenance.vb_version);
  prov.Str("git_commit", provenance.git_commit);
  prov.Str("task_file", provenance.task_file);
  prov.Str("task_fnv1a64", provenance.task_fnv1a64);
  prov.Str("vehicle", provenance.vehicle);
  prov.Str("vehicle_fnv1a64", provenance.vehicle_fnv1a64);
  prov.Str("soil", provenance.soil);
  prov.Str("soil_fnv1a64", provenance.soil_fnv1a64);
  prov.Str("system", provenance.system);
  if (provenance.perception != "none") {
    prov.Str("perception", provenance.perception);
    prov.Str("perception_fnv1a64", provenance.perception_fnv1a64);
  }
  prov.UInt("seed", provenance.seed);
  prov.Str("host", provenance.host);
  if (!provenance.operator_name.empty()) prov.Str("operator", provenance.operator_name);

  JsonObject o(0);
  o.Str("task", r.task_name);
  o.Int("pair", r.spec.pair_index);
  o.UInt("seed", r.spec.seed);
  o.Str("vehicle", r.spec.vehicle);
  o.Str("system", r.spec.system);
  if (r.perception != "none") {  // ground-truth records keep their format
    o.Str("perception", r.perception);
    o.Int("missed_obstacles", r.missed_obstacles);
    o.Int("phantom_rocks", r.phantom_rocks);
  }
  // Only when not the benchmark's 4 m/s: default records keep their format.
  if (r.target_speed_mps != runner::kDefaultTargetSpeed_mps) {
    o.Num("target_speed_mps", r.target_speed_mps);
  }
  // Only under other rules than vb's (the original's): default records keep their format, and
  // reports never count the two together (the index and the report's labels carry it too).
  if (r.rule_set != runner::RuleSet::kVb) o.Str("rules", std::string(runner::RuleSetName(r.rule_set)));
  o.Str("status", status);
  o.Raw("failure_type", success ? "null" : JsonString(status));
  o.Str("message", r.message);
  o.Raw("traversal_time_s", success ? JsonNumber(r.traversal_time_s) : "null");
  o.Num("sim_time_s", r.sim_time_s);
  o.Num("final_goal_distance_m", r.final_goal_distance_m);
  o.Num("path_length_m", r.path_length_m);
  o.Int("obstacle_contacts", r.obstacle_contacts);
  o.Raw("tipped", r.tipped ? "true" : "false");
  o.Raw("roll_deg", StatsJson(r.roll_deg));
  o.Raw("pitch_deg", StatsJson(r.pitch_deg));
  o.Raw("abs_roll_deg", StatsJson(r.abs_roll_deg));
  o.Raw("abs_pitch_deg", StatsJson(r.abs_pitch_deg));
  o.Raw("throttle", StatsJson(r.throttle));
  o.Raw("steering", StatsJson(r.steering));
  o.Raw("abs_steering", StatsJson(r.abs_steering));
  o.Int("trajectory_samples", static_cast<long long>(r.trajectory.size()));
  o.Num("wall_time_s", r.wall_time_s);
  o.Num("real_time_factor", r.real_time_factor);
  o.Raw("provenance", prov.Text());
  WriteAtomically(path, o.Text() + "\n");
}

void WriteTrajectoryCsv(const runner::TrialResult& r, const std::string& path) {
  const size_t wheels = r.trajectory.empty() ? 0 : r.trajectory.front().wheel_surface.size();
  std::string text =
      "t_s,x_m,y_m,z_m,vx_mps,vy_mps,vz_mps,speed_mps,roll_deg,pitch_deg,yaw_deg,throttle,"
      "steering,braking,gear";
  for (size_t i = 0; i < wheels; ++i) text += ",surface_w" + std::to_string(i);
  for (size_t i = 0; i < wheels; ++i) text += ",sinkage_w" + std::to_string(i) + "_m";
  text += "\n";
  text.reserve(text.size() + r.trajectory.size() * (15 * 24 + wheels * 26));   // ~upper bound
  for (const runner::TrajectorySample& s : r.trajectory) {
    const double values[] = {s.time_s,         s.position_W.x(), s.position_W.y(),
                             s.position_W.z(), s.velocity_W.x(), s.velocity_W.y(),
                             s.velocity_W.z(), s.speed_mps,      s.rpy.roll_rad * kRadToDeg,
                             s.rpy.pitch_rad * kRadToDeg,        s.rpy.yaw_rad * kRadToDeg,
                             s.throttle,       s.steering,       s.braking};
    // Appended in place (AppendExact: FormatExact's bytes without a string per number).
    for (double v : values) {
      AppendExact(v, &text);
      text += ',';
    }
    text += std::to_string(s.gear);
    for (size_t i = 0; i < wheels; ++i) {
      text += ',';
      text += std::to_string(i < s.wheel_surface.size() ? s.wheel_surface[i] : -1);
    }
    for (size_t i = 0; i < wheels; ++i) {
      text += ',';
      AppendExact(i < s.wheel_sinkage_m.size() ? s.wheel_sinkage_m[i] : 0.0, &text);
    }
    text += '\n';
  }
  WriteAtomically(path, text);
}

void WriteTrialFiles(const runner::TrialResult& result, const std::string& stem_path,
                     const Provenance& provenance) {
  WriteTrajectoryCsv(result, stem_path + "_traj.csv");
  WriteTrialJson(result, stem_path + ".json", provenance);
}

void WriteSummaryCsv(const std::vector<runner::TrialResult>& results, const std::string& path) {
  // A "rules" column only when a trial was decided by other rules than vb's, as in vb_batch's
  // index: default summaries keep their format, and another rule set's rows are never unnamed.
  const bool with_rules =
      std::any_of(results.begin(), results.end(), [](const runner::TrialResult& r) {
        return r.rule_set != runner::RuleSet::kVb;
      });
  std::string text =
      "task,pair,seed,vehicle,system,status,traversal_time_s,sim_time_s,final_goal_distance_m,"
      "path_length_m,obstacle_contacts,mean_abs_roll_deg,var_abs_roll_deg,max_abs_roll_deg,"
      "mean_abs_pitch_deg,var_abs_pitch_deg,max_abs_pitch_deg,mean_throttle,mean_abs_steering,"
      "wall_time_s,real_time_factor,message";
  text += with_rules ? ",rules\n" : "\n";
  for (const runner::TrialResult& r : results) {
    const bool success = r.status == runner::TrialStatus::kSuccess;
    text += CsvField(r.task_name) + "," + std::to_string(r.spec.pair_index) + "," +
            std::to_string(r.spec.seed) + "," + CsvField(r.spec.vehicle) + "," +
            CsvField(r.spec.system) + "," + std::string(runner::TrialStatusName(r.status)) + "," +
            (success ? Number(r.traversal_time_s) : "") + "," + Number(r.sim_time_s) + "," +
            Number(r.final_goal_distance_m) + "," + Number(r.path_length_m) + "," +
            std::to_string(r.obstacle_contacts) + "," + Number(r.abs_roll_deg.mean) + "," +
            Number(r.abs_roll_deg.var) + "," + Number(r.abs_roll_deg.max) + "," +
            Number(r.abs_pitch_deg.mean) + "," + Number(r.abs_pitch_deg.var) + "," +
            Number(r.abs_pitch_deg.max) + "," + Number(r.throttle.mean) + "," +
            Number(r.abs_steering.mean) + "," + Number(r.wall_time_s) + "," +
            Number(r.real_time_factor) + "," + CsvField(r.message) +
            (with_rules ? "," + std::string(runner::RuleSetName(r.rule_set)) : std::string()) +
            "\n";
  }
  WriteAtomically(path, text);
}

}  // namespace vb::io
