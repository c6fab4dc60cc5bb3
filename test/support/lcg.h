// A deterministic uniform generator for property tests: a 64-bit linear congruential generator
// (Knuth's MMIX constants) mapped to [0, 1) by its top 53 bits. The same seed gives the same
// sequence with every compiler and standard library (std's distributions do not promise that).
#pragma once

#include <cstdint>

namespace vb::test {

class UniformLcg {
 public:
  explicit UniformLcg(std::uint64_t seed) : state_(seed) {}
  double operator()() {
    state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state_ >> 11) / 9007199254740992.0;
  }

 private:
  std::uint64_t state_;
};

}  // namespace vb::test
