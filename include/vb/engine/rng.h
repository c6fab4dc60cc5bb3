// Deterministic, platform-independent random numbers. std::*_distribution are implementation
// defined (libstdc++ and libc++ differ), so vb draws through these functions only.
#pragma once

#include <cmath>
#include <cstdint>

namespace vb {

// SplitMix64 stream: tiny state, passes BigCrush, identical on every platform.
class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(seed) {}

  uint64_t NextU64() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1) with 53 random bits.
  double Uniform() { return static_cast<double>(NextU64() >> 11) * 0x1.0p-53; }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  // Uniform integer in [lo, hi] (inclusive); modulo bias below 2^-40 for ranges we use.
  int UniformInt(int lo, int hi) {
    return lo + static_cast<int>(NextU64() % static_cast<uint64_t>(hi - lo + 1));
  }
  // Standard normal by Box-Muller (uses two uniforms per call; no cached spare, so the stream
  // position depends only on the number of calls).
  double Normal(double mean = 0.0, double std_dev = 1.0) {
    double u1 = Uniform();
    const double u2 = Uniform();
    if (u1 < 1e-300) u1 = 1e-300;
    return mean + std_dev * std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }

 private:
  uint64_t state_;
};

}  // namespace vb
