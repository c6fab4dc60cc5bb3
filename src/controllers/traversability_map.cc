// TNT's traversability map (traversability_map.h).
#include "vb/controllers/traversability_map.h"

#include <algorithm>
#include <cmath>

#include "vb/controllers/hybrid_models.h"
#include "vb/engine/error.h"

namespace vb::controllers {

namespace {
constexpr int kClasses = 10;
constexpr int kInputs = kTerrainGridPoints + kClasses;
}  // namespace

TraversabilityMap::TraversabilityMap(const nn::TensorSet& tensors,
                                     const TraversabilityMapParams& params)
    : params_(params),
      net_(tensors, "tnt.trav",
           {nn::Activation::kRelu, nn::Activation::kRelu, nn::Activation::kNone}) {
  if (net_.input_size() != kInputs || net_.output_size() != 1) {
    throw InputError(tensors.source, 0, "tnt.trav",
                     "network has " + std::to_string(net_.input_size()) + " inputs and " +
                         std::to_string(net_.output_size()) + " outputs, expected 25 and 1");
  }
  cost_.assign(static_cast<size_t>(params_.cells) * params_.cells, 1.0);
}

void TraversabilityMap::FillInput(const terrain::GroundTruthMaps& maps, const Vec2& p_m,
                                  double yaw_rad, float* col, int stride) const {
  TerrainShape(maps.terrain(), p_m.x(), p_m.y(), yaw_rad, col, stride);
  const int cls = std::clamp(static_cast<int>(std::lround(maps.Sample(terrain::MapLayer::kSemantics, p_m))),
                             0, kClasses - 1);
  for (int c = 0; c < kClasses; ++c) col[(kTerrainGridPoints + c) * stride] = c == cls ? 1.f : 0.f;
}

void TraversabilityMap::Update(const terrain::GroundTruthMaps& maps, const Vec2& centre_m,
                               double yaw_rad) {
  const int n = params_.cells;
  const double half = 0.5 * (n - 1) * params_.cell_m;
  origin_m_ = Vec2(centre_m.x() - half, centre_m.y() + half);
  if (in_.rows() != kInputs || in_.cols() != n * n) in_.resize(kInputs, n * n);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      const Vec2 p(origin_m_.x() + c * params_.cell_m, origin_m_.y() - r * params_.cell_m);
      FillInput(maps, p, yaw_rad, in_.data() + r * n + c, n * n);
    }
  }
  net_.ForwardBatch(in_, out_);
  for (int i = 0; i < n * n; ++i) {
    cost_[static_cast<size_t>(i)] = 1.0 - 1.0 / (1.0 + std::exp(-static_cast<double>(out_(0, i))));
  }
}

double TraversabilityMap::Predict(const terrain::GroundTruthMaps& maps, const Vec2& p_m,
                                  double yaw_rad) const {
  float in[kInputs];
  float out = 0.f;
  FillInput(maps, p_m, yaw_rad, in, 1);
  net_.Forward(in, &out);
  return 1.0 / (1.0 + std::exp(-static_cast<double>(out)));
}

double TraversabilityMap::Cost(double x_m, double y_m) const {
  const int n = params_.cells;
  const double c = (x_m - origin_m_.x()) / params_.cell_m;
  const double r = (origin_m_.y() - y_m) / params_.cell_m;
  if (!(c >= 0.0 && r >= 0.0 && c <= n - 1 && r <= n - 1)) return 1.0;
  const int c0 = std::min(static_cast<int>(c), n - 2);
  const int r0 = std::min(static_cast<int>(r), n - 2);
  const double u = c - c0, v = r - r0;
  const auto at = [&](int rr, int cc) { return cost_[static_cast<size_t>(rr) * n + cc]; };
  return (1 - v) * ((1 - u) * at(r0, c0) + u * at(r0, c0 + 1)) +
         v * ((1 - u) * at(r0 + 1, c0) + u * at(r0 + 1, c0 + 1));
}

}  // namespace vb::controllers
