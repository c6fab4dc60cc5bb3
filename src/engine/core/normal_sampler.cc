// Ziggurat for the standard normal (Marsaglia and Tsang 2000, 128 layers). Layer i covers
// [0, x_i] under the density f(x) = exp(-x^2/2); all layers have the same area v, the base layer
// includes the tail beyond r. A draw picks a layer and a signed point in it; if the point lies in
// the rectangle fully under the curve (the usual case) it is returned at once; otherwise the
// wedge is tested against f, and the base layer's overflow samples the tail exactly.
#include "vb/engine/normal_sampler.h"

#include <cmath>
#include <cstdint>

namespace vb {

namespace {

constexpr int kLayers = 128;
constexpr double kR = 3.442619855899;           // right edge of the top of the base layer
constexpr double kV = 9.91256303526217e-3;      // area of every layer (f unnormalised)
constexpr double kTwoPow31 = 2147483648.0;

struct Tables {
  uint32_t k[kLayers];   // |hz| < k[i]: the point is inside layer i's inner rectangle
  double w[kLayers];     // hz * w[i] is the point's x
  double f[kLayers];     // f(x_i)
  Tables() {
    double dn = kR;
    double tn = dn;
    const double q = kV / std::exp(-0.5 * dn * dn);
    k[0] = static_cast<uint32_t>((dn / q) * kTwoPow31);
    k[1] = 0;
    w[0] = q / kTwoPow31;
    w[kLayers - 1] = dn / kTwoPow31;
    f[0] = 1.0;
    f[kLayers - 1] = std::exp(-0.5 * dn * dn);
    for (int i = kLayers - 2; i >= 1; --i) {
      dn = std::sqrt(-2.0 * std::log(kV / dn + std::exp(-0.5 * dn * dn)));
      k[i + 1] = static_cast<uint32_t>((dn / tn) * kTwoPow31);
      tn = dn;
      f[i] = std::exp(-0.5 * dn * dn);
      w[i] = dn / kTwoPow31;
    }
  }
};

const Tables& Zig() {
  static const Tables tables;
  return tables;
}

// Uniform in (0, 1): never 0, so its log is finite.
double OpenUniform(Rng* rng) {
  return (static_cast<double>(rng->NextU64() >> 11) + 0.5) * 0x1.0p-53;
}

}  // namespace

double NormalSampler::Draw(Rng* rng) {
  const Tables& t = Zig();
  for (;;) {
    // The upper 32 bits are the signed point, the lowest 7 bits the layer (independent bits).
    const uint64_t u = rng->NextU64();
    const int32_t hz = static_cast<int32_t>(static_cast<uint32_t>(u >> 32));
    const int iz = static_cast<int>(u & (kLayers - 1));
    const uint32_t abs_hz = hz < 0 ? static_cast<uint32_t>(-(static_cast<int64_t>(hz)))
                                   : static_cast<uint32_t>(hz);
    const double x = hz * t.w[iz];
    if (abs_hz < t.k[iz]) return x;
    if (iz == 0) {
      // tail beyond r (Marsaglia's exponential method)
      double xt, y;
      do {
        xt = -std::log(OpenUniform(rng)) / kR;
        y = -std::log(OpenUniform(rng));
      } while (y + y < xt * xt);
      return hz > 0 ? kR + xt : -kR - xt;
    }
    // wedge between the inner rectangle and the curve
    if (t.f[iz] + OpenUniform(rng) * (t.f[iz - 1] - t.f[iz]) < std::exp(-0.5 * x * x)) return x;
  }
}

}  // namespace vb
