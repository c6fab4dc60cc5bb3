// The learned rollout models of the hybrid baselines (reference_verti_bench.md §7.4-7.7; docs/
// baselines.md "Hybrid systems", docs/learning.md "Hybrid kinodynamic models"): MPPI-core plug-ins
// that evaluate small PyTorch-trained MLPs (vb::nn::Mlp, Eigen) on a whole batch of rollout
// states per horizon step.
//
// Every model reads the same terrain description of a planar pose: the surface height at the 15
// points of an egocentric 5 x 3 grid (forward 2, 1, 0, -1, -2 m; left 1, 0, -1 m; forward-major)
// minus the height at the centre point (python/vb_gym/hybrid_features.py, where the training
// data come from; the grid is the vehicle's size, it does not scale with the environment).
//
//  - WMVCT:  bicycle (x, y, yaw), then z, roll, pitch at the new pose from the terrain under it
//            and the previous roll and pitch (`wmvct.net`: 17 -> 32 -> 32 -> 3).
//  - MPPI-6: bicycle (x, y, yaw), roll and pitch from an ensemble of 5 MLPs (mean) on the
//            terrain under the new pose, roll, pitch, steering and step length (`mppi6.m0..4`).
//  - TAL:    the whole step learned: softmax attention over the 15 terrain points from the motion
//            context (roll, pitch, step length, steering) (`tal.query`), and a head on the context
//            and the attended heights giving body dx, dy, dyaw, world dz and the new roll, pitch
//            (`tal.head`).
//  - TNT's traversability map (`tnt.trav`) is in hybrid_cost.h.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "vb/controllers/bicycle_model.h"
#include "vb/controllers/mppi_core.h"
#include "vb/nn/mlp.h"
#include "vb/nn/tensor_set.h"
#include "vb/terrain/terrain.h"

namespace vb::controllers {

constexpr int kTerrainGridPoints = 15;
constexpr int kTerrainGridCentre = 7;
constexpr std::array<double, 5> kTerrainGridForward_m = {2.0, 1.0, 0.0, -1.0, -2.0};
constexpr std::array<double, 3> kTerrainGridLeft_m = {1.0, 0.0, -1.0};

// Writes the 15 grid heights of pose (x, y, yaw) minus the centre height into out[0], out[stride],
// ..., out[14 * stride] and returns the centre height (the surface the wheels touch:
// Terrain::Height).
double TerrainShape(const terrain::Terrain& terrain, double x_m, double y_m, double yaw_rad,
                    float* out, int stride = 1);

// The networks of one system, built from a model file's tensors (throws InputError naming the
// file and tensor when they do not fit). Copied per controller (an Mlp keeps scratch buffers).
struct WmvctNetworks {
  nn::Mlp net;
  explicit WmvctNetworks(const nn::TensorSet& t);
};
struct Mppi6Networks {
  std::vector<nn::Mlp> members;
  explicit Mppi6Networks(const nn::TensorSet& t);
};
struct TalNetworks {
  nn::Mlp query, head;
  explicit TalNetworks(const nn::TensorSet& t);
  // One batched step: `in` is (4 + 15) x n, rows 0-3 the context (roll, pitch, step length,
  // steering), rows 4-18 the terrain shape, replaced by the attended heights (15 x softmax
  // weight x height); `out` becomes 6 x n (body dx, dy, dyaw, world dz, roll, pitch). No
  // allocation once the scratch has the batch's size.
  void Forward(nn::BatchMatrix& in, nn::BatchMatrix& out) const;

 private:
  mutable nn::BatchMatrix logits_;
  mutable std::vector<float> max_, total_;
};

enum class HybridDynamics { kWmvct, kMppi6, kTal };

// One rollout model for the three. set_terrain before use; the terrain must outlive the model.
class HybridRolloutModel : public RolloutModel {
 public:
  HybridRolloutModel(const BicycleModelParams& bicycle, WmvctNetworks wmvct);
  HybridRolloutModel(const BicycleModelParams& bicycle, Mppi6Networks mppi6);
  HybridRolloutModel(const BicycleModelParams& bicycle, TalNetworks tal);
  void set_terrain(const terrain::Terrain* terrain) { terrain_ = terrain; }
  void set_bicycle(const BicycleModelParams& bicycle) { bicycle_ = BicycleModel(bicycle); }
  const BicycleModelParams& bicycle() const { return bicycle_.params(); }
  void Step(int step, const PlannerState* states, const MppiControl* controls, int count,
            PlannerState* next) const override;
  std::unique_ptr<RolloutModel> Clone() const override;

  HybridDynamics kind() const { return kind_; }

 private:
  void StepWmvct(const PlannerState* states, const MppiControl* controls, int count,
                 PlannerState* next) const;
  void StepMppi6(const PlannerState* states, const MppiControl* controls, int count,
                 PlannerState* next) const;
  void StepTal(const PlannerState* states, const MppiControl* controls, int count,
               PlannerState* next) const;

  HybridDynamics kind_;
  BicycleModel bicycle_;
  std::vector<nn::Mlp> nets_;     // WMVCT: [net]; MPPI-6: members
  std::optional<TalNetworks> tal_;
  const terrain::Terrain* terrain_ = nullptr;
  // Scratch, sized on the first call (K is fixed for a controller): no allocation afterwards.
  mutable nn::BatchMatrix in_, out_, sum_;
  mutable std::vector<float> centre_;
};

}  // namespace vb::controllers
