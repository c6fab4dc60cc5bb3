#include "vb/batch/matrix.h"

#include "vb/batch/index.h"

#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <set>

#include "vb/engine/error.h"

namespace vb::batch {
namespace {

uint64_t Fnv1a64(const std::string& bytes, uint64_t hash) {
  for (unsigned char c : bytes) {
    hash ^= c;
    hash *= 0x100000001b3ull;
  }
  return hash;
}

template <typename T>
void RequireUniqueNonEmpty(const std::vector<T>& v, const std::string& key) {
  if (v.empty()) throw InputError("", 0, key, "empty list");
  std::set<T> seen(v.begin(), v.end());
  if (seen.size() != v.size()) throw InputError("", 0, key, "list has duplicates");
}

}  // namespace

std::vector<TrialKey> ExpandMatrix(const MatrixSpec& spec) {
  if (spec.tasks.empty()) throw InputError("", 0, "environments", "no task files matched");
  std::set<std::string> names;
  for (const MatrixTask& t : spec.tasks) {
    if (!names.insert(t.name).second) {
      throw InputError(t.path, 0, "name",
                       "task name '" + t.name + "' appears twice in the matrix; trial files "
                       "are named by task name, so names must be unique");
    }
  }
  if (!spec.pairs.empty()) RequireUniqueNonEmpty(spec.pairs, "--pairs");
  RequireUniqueNonEmpty(spec.vehicles, "--vehicles");
  RequireUniqueNonEmpty(spec.systems, "--systems");
  RequireUniqueNonEmpty(spec.perceptions, "--perception");
  RequireUniqueNonEmpty(spec.seeds, "--seeds");

  std::vector<TrialKey> trials;
  for (size_t ti = 0; ti < spec.tasks.size(); ++ti) {
    const MatrixTask& t = spec.tasks[ti];
    std::vector<int> pairs = spec.pairs;
    if (pairs.empty()) {
      const int n = t.load_error.empty() ? t.num_pairs : kDefaultPairsPerTask;
      for (int k = 0; k < n; ++k) pairs.push_back(k);
    }
    for (int pair : pairs) {
      for (const std::string& vehicle : spec.vehicles) {
        for (const std::string& system : spec.systems) {
          for (const std::string& perception : spec.perceptions) {
            for (uint64_t seed : spec.seeds) {
              TrialKey key;
              key.matrix_index = trials.size();
              key.task_index = ti;
              key.pair = pair;
              key.vehicle = vehicle;
              key.system = system;
              key.perception = perception;
              key.seed = seed;
              trials.push_back(std::move(key));
            }
          }
        }
      }
    }
  }
  return trials;
}

std::string TrialStem(const MatrixSpec& spec, const TrialKey& key) {
  return spec.tasks[key.task_index].name + "_p" + std::to_string(key.pair) + "_s" +
         std::to_string(key.seed) + "_" + key.vehicle + "_" + key.system +
         PerceptionStemSuffix(key.perception);
}

Shard ParseShard(const std::string& text) {
  const size_t slash = text.find('/');
  auto number = [&](const std::string& s) -> long {
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(s.c_str(), &end, 10);
    if (s.empty() || *end != '\0' || errno != 0 || s[0] == '-' || s[0] == '+') return -1;
    return v;
  };
  if (slash == std::string::npos) {
    throw InputError("", 0, "--shard", "'" + text + "' is not of the form i/N");
  }
  const long i = number(text.substr(0, slash));
  const long n = number(text.substr(slash + 1));
  if (i < 0 || n < 1 || i >= n || n > 1000000) {
    throw InputError("", 0, "--shard", "'" + text + "': need 0 <= i < N (shards are 0-based)");
  }
  return Shard{static_cast<int>(i), static_cast<int>(n)};
}

std::vector<TrialKey> SelectShard(const std::vector<TrialKey>& trials, const Shard& shard) {
  std::vector<TrialKey> out;
  for (size_t i = static_cast<size_t>(shard.index); i < trials.size();
       i += static_cast<size_t>(shard.count)) {
    out.push_back(trials[i]);
  }
  return out;
}

std::string MatrixFingerprint(const MatrixSpec& spec, const std::vector<TrialKey>& trials) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (const MatrixTask& t : spec.tasks) h = Fnv1a64(t.name + "=" + t.task_fnv1a64 + ";", h);
  for (const TrialKey& k : trials) h = Fnv1a64(TrialStem(spec, k) + ";", h);
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016" PRIx64, h);
  return hex;
}

}  // namespace vb::batch
