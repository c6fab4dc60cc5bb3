// TNT's learned traversability (reference_verti_bench.md §7.6; docs/baselines.md "Hybrid
// systems"): a map of the predicted progress ratio (the fraction of the commanded 2 m/s the
// exploring vehicle achieved over the next second, python/vb_gym/hybrid_features.py) around the
// vehicle, computed once per planner update by one batched evaluation of `tnt.trav` (terrain
// shape of 15 points + surface class one-hot -> logit) at every cell, with the vehicle's heading.
// The rollouts then look their cost up by world position (the original indexed its 320 x 260
// map with metres as pixels; vb converts metres to cells).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "vb/engine/types.h"
#include "vb/nn/mlp.h"
#include "vb/nn/tensor_set.h"
#include "vb/terrain/gt_maps.h"

namespace vb::controllers {

struct TraversabilityMapParams {
  int cells = 25;          // per side, centred on the vehicle
  double cell_m = 1.0;     // a rollout reaches <= 10 m: the map spans +-12 m
};

class TraversabilityMap {
 public:
  // `tnt.trav` of a model file (throws InputError when the network does not fit).
  TraversabilityMap(const nn::TensorSet& tensors, const TraversabilityMapParams& params = {});

  // Evaluates the network at every cell around `centre_m` (cell grid aligned with the world axes)
  // for a vehicle heading `yaw_rad`. No allocation after the first call.
  void Update(const terrain::GroundTruthMaps& maps, const Vec2& centre_m, double yaw_rad);

  // Traversability in [0, 1] (1 = drives at the commanded speed) at one terrain point and heading
  // (one network evaluation; the map's cells use this).
  double Predict(const terrain::GroundTruthMaps& maps, const Vec2& p_m, double yaw_rad) const;

  // 1 - traversability at a world point, bilinear between cell centres; outside the map 1.
  double Cost(double x_m, double y_m) const;

  const TraversabilityMapParams& params() const { return params_; }
  // Traversability of cell (row, col): row 0 north, col 0 west.
  double At(int row, int col) const { return 1.0 - cost_[static_cast<size_t>(row) * params_.cells + col]; }

 private:
  // The network's 25 inputs of one point into col[0], col[stride], ...
  void FillInput(const terrain::GroundTruthMaps& maps, const Vec2& p_m, double yaw_rad,
                 float* col, int stride) const;

  TraversabilityMapParams params_;
  nn::Mlp net_;
  Vec2 origin_m_ = Vec2::Zero();   // centre of cell (0, 0)
  std::vector<double> cost_;       // cells x cells, row-major
  nn::BatchMatrix in_, out_;
};

}  // namespace vb::controllers
