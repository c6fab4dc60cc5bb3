// A cheap lower bound on std::pow(z, n) for a fixed exponent n > 0, for tests of the form
// "sigma > k z^n" (the Bekker yield test of the SCM solver) that are mostly decided far from the
// boundary: where sigma <= k * PowLowerBound(z) the test is false without evaluating pow, and the
// answer is the one the full evaluation gives (bit-identical results).
//
// z = m 2^e with m in [1, 2): z^n >= (2^e)^n (m_b)^n for the lower edge m_b = 1 + b / 256 of
// m's bin. The two tables hold pow() at the exact points 2^e and m_b (each within an ulp of the
// true power) times (1 - 1e-12), which covers their rounding, the product's and pow's own error
// (< 1 ulp) thousands of times over; the bound is within a factor (1 + 1/256)^n of z^n. With
// k >= 0, rounding is monotone, so sigma <= k * bound(z) implies sigma <= k * std::pow(z, n).
// NaN (no bound: evaluate pow) outside [2^-40, 2^8), for z <= 0, subnormal or not finite, and
// for every z when n is not a positive finite number.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

namespace vb::soil {

class PowLowerBound {
 public:
  void Init(double n) {
    enabled_ = n > 0.0 && std::isfinite(n);
    if (!enabled_) return;
    for (int e = kMinExp; e < kMaxExp; ++e) {
      by_exponent_[e - kMinExp] = std::pow(std::ldexp(1.0, e), n);
    }
    for (int b = 0; b < kBins; ++b) {
      by_mantissa_[b] = std::pow(1.0 + static_cast<double>(b) / kBins, n) * (1.0 - 1e-12);
    }
  }
  double operator()(double z) const {
    uint64_t bits = 0;
    std::memcpy(&bits, &z, sizeof bits);
    const int e = static_cast<int>(bits >> 52) - 1023;  // sign bit set: far above kMaxExp
    if (!enabled_ || e < kMinExp || e >= kMaxExp) return std::nan("");
    const auto b = static_cast<size_t>((bits >> (52 - kBinBits)) & (kBins - 1));
    return by_exponent_[static_cast<size_t>(e - kMinExp)] * by_mantissa_[b];
  }

 private:
  static constexpr int kMinExp = -40, kMaxExp = 8;  // z from ~1e-12 to 256
  static constexpr int kBinBits = 8, kBins = 1 << kBinBits;
  bool enabled_ = false;
  double by_exponent_[kMaxExp - kMinExp] = {};
  double by_mantissa_[kBins] = {};
};

}  // namespace vb::soil
