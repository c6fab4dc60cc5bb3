// Canonical text of a TrialResult for its digest (result_digest.h).
#include "vb/engine/runner/result_digest.h"

#include <cstdio>

#include "vb/engine/text_format.h"

namespace vb::runner {

namespace {

class Fnv1a64 {
 public:
  void Add(const std::string& s) {
    for (unsigned char c : s) {
      hash_ ^= c;
      hash_ *= 0x100000001b3ull;
    }
    hash_ ^= 0xff;  // field separator: "ab","c" and "a","bc" differ
    hash_ *= 0x100000001b3ull;
  }
  void Add(double x) { Add(FormatExact(x)); }
  void Add(long long x) { Add(std::to_string(x)); }
  void Add(const SignalStats& s) {
    Add(s.mean);
    Add(s.var);
    Add(s.max);
  }
  std::string Hex() const {
    char buf[17];
    std::snprintf(buf, sizeof(buf), "%016llx", static_cast<unsigned long long>(hash_));
    return buf;
  }

 private:
  uint64_t hash_ = 0xcbf29ce484222325ull;
};

}  // namespace

std::string TrialDigest(const TrialResult& r) {
  Fnv1a64 h;
  h.Add(r.task_name);
  h.Add(static_cast<long long>(r.spec.pair_index));
  h.Add(std::to_string(r.spec.seed));
  h.Add(r.spec.system);
  h.Add(r.spec.vehicle);
  h.Add(std::string(TrialStatusName(r.status)));
  h.Add(r.message);
  // Only under other rules than vb's: digests of default trials stay as they were.
  if (r.rule_set != RuleSet::kVb) h.Add("rules=" + std::string(RuleSetName(r.rule_set)));
  h.Add(r.sim_time_s);
  h.Add(r.traversal_time_s);
  h.Add(r.final_goal_distance_m);
  h.Add(r.path_length_m);
  h.Add(static_cast<long long>(r.obstacle_contacts));
  h.Add(static_cast<long long>(r.tipped));
  for (const SignalStats* s : {&r.roll_deg, &r.pitch_deg, &r.abs_roll_deg, &r.abs_pitch_deg,
                               &r.throttle, &r.steering, &r.abs_steering}) {
    h.Add(*s);
  }
  h.Add(static_cast<long long>(r.trajectory.size()));
  for (const TrajectorySample& s : r.trajectory) {
    h.Add(s.time_s);
    for (int i = 0; i < 3; ++i) h.Add(s.position_W[i]);
    for (int i = 0; i < 3; ++i) h.Add(s.velocity_W[i]);
    h.Add(s.speed_mps);
    h.Add(s.rpy.roll_rad);
    h.Add(s.rpy.pitch_rad);
    h.Add(s.rpy.yaw_rad);
    h.Add(s.throttle);
    h.Add(s.steering);
    h.Add(s.braking);
    h.Add(static_cast<long long>(s.gear));
    for (int c : s.wheel_surface) h.Add(static_cast<long long>(c));
    for (double z : s.wheel_sinkage_m) h.Add(z);
  }
  return h.Hex();
}

}  // namespace vb::runner
