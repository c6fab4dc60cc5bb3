// Learned rollout models of the hybrid baselines (hybrid_models.h).
#include "vb/controllers/hybrid_models.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "vb/engine/error.h"
#include "vb/terrain/terrain_heights.h"

namespace vb::controllers {

namespace {

constexpr int kMppi6Members = 5;
constexpr int kTalContext = 4;
constexpr int kTalOutputs = 6;
// TAL's step-length input is clamped to what the exploration data cover (the planner's speed
// bounds widen to [-1, 1] near the local goal; the data never drive backwards).
constexpr double kTalMaxStep_m = 0.8;

const std::vector<nn::Activation> kTwoHidden = {nn::Activation::kRelu, nn::Activation::kRelu,
                                                nn::Activation::kNone};
const std::vector<nn::Activation> kOneHidden = {nn::Activation::kRelu, nn::Activation::kNone};

void Expect(const nn::TensorSet& t, const nn::Mlp& net, const std::string& prefix, int in,
            int out) {
  if (net.input_size() != in || net.output_size() != out) {
    throw InputError(t.source, 0, prefix,
                     "network has " + std::to_string(net.input_size()) + " inputs and " +
                         std::to_string(net.output_size()) + " outputs, expected " +
                         std::to_string(in) + " and " + std::to_string(out));
  }
}

}  // namespace

double TerrainShape(const terrain::Terrain& terrain, double x_m, double y_m, double yaw_rad,
                    float* out, int stride) {
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  double px[kTerrainGridPoints], py[kTerrainGridPoints], h[kTerrainGridPoints];
  int i = 0;
  for (double f : kTerrainGridForward_m) {
    for (double l : kTerrainGridLeft_m) {
      px[i] = x_m + c * f - s * l;
      py[i] = y_m + s * f + c * l;
      ++i;
    }
  }
  terrain::Heights(terrain, px, py, kTerrainGridPoints, h);
  const double centre = h[kTerrainGridCentre];
  for (int j = 0; j < kTerrainGridPoints; ++j) out[j * stride] = static_cast<float>(h[j] - centre);
  return centre;
}

WmvctNetworks::WmvctNetworks(const nn::TensorSet& t) : net(t, "wmvct.net", kTwoHidden) {
  Expect(t, net, "wmvct.net", kTerrainGridPoints + 2, 3);
}

Mppi6Networks::Mppi6Networks(const nn::TensorSet& t) {
  for (int m = 0; m < kMppi6Members; ++m) {
    const std::string prefix = "mppi6.m" + std::to_string(m);
    members.emplace_back(t, prefix, kTwoHidden);
    Expect(t, members.back(), prefix, kTerrainGridPoints + 4, 2);
  }
}

TalNetworks::TalNetworks(const nn::TensorSet& t)
    : query(t, "tal.query", kOneHidden), head(t, "tal.head", kTwoHidden) {
  Expect(t, query, "tal.query", kTalContext, kTerrainGridPoints);
  Expect(t, head, "tal.head", kTalContext + kTerrainGridPoints, kTalOutputs);
}

void TalNetworks::Forward(nn::BatchMatrix& in, nn::BatchMatrix& out) const {
  const int n = static_cast<int>(in.cols());
  if (logits_.rows() != kTerrainGridPoints || logits_.cols() != n) {
    logits_.resize(kTerrainGridPoints, n);
    max_.assign(static_cast<size_t>(n), 0.f);
    total_.assign(static_cast<size_t>(n), 0.f);
  }
  // the query reads the context rows 0-3 in place (feature-major: they are the first 4n floats)
  query.ForwardBatch(in.data(), n, n, logits_.data(), n);
  // attention: softmax over the 15 terrain points, times 15, times the heights; every loop runs
  // over the samples (k inner), each sample's operations in the order of a scalar softmax
  float* q = logits_.data();
  float* mx = max_.data();
  float* total = total_.data();
  for (int k = 0; k < n; ++k) mx[k] = q[k];
  for (int i = 1; i < kTerrainGridPoints; ++i) {
    const float* qi = q + static_cast<long>(i) * n;
    for (int k = 0; k < n; ++k) mx[k] = qi[k] > mx[k] ? qi[k] : mx[k];
  }
  for (int i = 0; i < kTerrainGridPoints; ++i) {
    float* qi = q + static_cast<long>(i) * n;
    for (int k = 0; k < n; ++k) qi[k] = qi[k] - mx[k];
  }
  nn::ExpBatch(head.kernel_isa(), q, q, kTerrainGridPoints * n);
  for (int k = 0; k < n; ++k) total[k] = q[k];
  for (int i = 1; i < kTerrainGridPoints; ++i) {
    const float* qi = q + static_cast<long>(i) * n;
    for (int k = 0; k < n; ++k) total[k] = total[k] + qi[k];
  }
  for (int k = 0; k < n; ++k) total[k] = static_cast<float>(kTerrainGridPoints) / total[k];
  for (int i = 0; i < kTerrainGridPoints; ++i) {
    const float* qi = q + static_cast<long>(i) * n;
    float* hi = in.data() + static_cast<long>(kTalContext + i) * n;
    for (int k = 0; k < n; ++k) hi[k] = hi[k] * (total[k] * qi[k]);
  }
  head.ForwardBatch(in, out);
}

HybridRolloutModel::HybridRolloutModel(const BicycleModelParams& bicycle, WmvctNetworks wmvct)
    : kind_(HybridDynamics::kWmvct), bicycle_(bicycle), nets_{std::move(wmvct.net)} {}

HybridRolloutModel::HybridRolloutModel(const BicycleModelParams& bicycle, Mppi6Networks mppi6)
    : kind_(HybridDynamics::kMppi6), bicycle_(bicycle), nets_(std::move(mppi6.members)) {}

HybridRolloutModel::HybridRolloutModel(const BicycleModelParams& bicycle, TalNetworks tal)
    : kind_(HybridDynamics::kTal), bicycle_(bicycle), tal_(std::move(tal)) {}

void HybridRolloutModel::Step(int step, const PlannerState* states, const MppiControl* controls,
                              int count, PlannerState* next) const {
  VB_DEMAND(terrain_ != nullptr);
  if (static_cast<int>(centre_.size()) != count) centre_.assign(static_cast<size_t>(count), 0.f);
  switch (kind_) {
    case HybridDynamics::kWmvct:
      bicycle_.Step(step, states, controls, count, next);
      StepWmvct(states, controls, count, next);
      break;
    case HybridDynamics::kMppi6:
      bicycle_.Step(step, states, controls, count, next);
      StepMppi6(states, controls, count, next);
      break;
    case HybridDynamics::kTal:
      StepTal(states, controls, count, next);
      break;
  }
}

void HybridRolloutModel::StepWmvct(const PlannerState* states, const MppiControl* /*controls*/,
                                   int count, PlannerState* next) const {
  const int n_in = kTerrainGridPoints + 2;
  if (in_.rows() != n_in || in_.cols() != count) in_.resize(n_in, count);
  float* in = in_.data();
  for (int k = 0; k < count; ++k) {
    centre_[k] = static_cast<float>(
        TerrainShape(*terrain_, next[k].x_m, next[k].y_m, next[k].yaw_rad, in + k, count));
    in[kTerrainGridPoints * count + k] = static_cast<float>(states[k].roll_rad);
    in[(kTerrainGridPoints + 1) * count + k] = static_cast<float>(states[k].pitch_rad);
  }
  nets_[0].ForwardBatch(in_, out_);
  for (int k = 0; k < count; ++k) {
    next[k].z_m = centre_[k] + out_(0, k);
    next[k].roll_rad = out_(1, k);
    next[k].pitch_rad = out_(2, k);
  }
}

void HybridRolloutModel::StepMppi6(const PlannerState* states, const MppiControl* controls,
                                   int count, PlannerState* next) const {
  const int n_in = kTerrainGridPoints + 4;
  if (in_.rows() != n_in || in_.cols() != count) in_.resize(n_in, count);
  const double step_per_speed = bicycle_.params().step_length_per_speed_m * bicycle_.params().scale;
  float* in = in_.data();
  for (int k = 0; k < count; ++k) {
    TerrainShape(*terrain_, next[k].x_m, next[k].y_m, next[k].yaw_rad, in + k, count);
    in[kTerrainGridPoints * count + k] = static_cast<float>(states[k].roll_rad);
    in[(kTerrainGridPoints + 1) * count + k] = static_cast<float>(states[k].pitch_rad);
    in[(kTerrainGridPoints + 2) * count + k] = static_cast<float>(controls[k][kMppiSteer]);
    in[(kTerrainGridPoints + 3) * count + k] =
        static_cast<float>(step_per_speed * controls[k][kMppiSpeed]);
  }
  if (sum_.rows() != 2 || sum_.cols() != count) sum_.resize(2, count);
  sum_.setZero();
  for (const nn::Mlp& member : nets_) {
    member.ForwardBatch(in_, out_);
    sum_ += out_;
  }
  const float inv = 1.0f / static_cast<float>(nets_.size());
  for (int k = 0; k < count; ++k) {
    next[k].roll_rad = inv * sum_(0, k);
    next[k].pitch_rad = inv * sum_(1, k);
  }
}

void HybridRolloutModel::StepTal(const PlannerState* states, const MppiControl* controls,
                                 int count, PlannerState* next) const {
  const int n_in = kTalContext + kTerrainGridPoints;
  if (in_.rows() != n_in || in_.cols() != count) in_.resize(n_in, count);
  const double step_per_speed = bicycle_.params().step_length_per_speed_m * bicycle_.params().scale;
  for (int k = 0; k < count; ++k) {
    const PlannerState& s = states[k];
    const double ds = std::clamp(step_per_speed * controls[k][kMppiSpeed], 0.0, kTalMaxStep_m);
    float* in = in_.data() + k;
    in[0] = static_cast<float>(s.roll_rad);
    in[count] = static_cast<float>(s.pitch_rad);
    in[2 * count] = static_cast<float>(ds);
    in[3 * count] = static_cast<float>(controls[k][kMppiSteer]);
    TerrainShape(*terrain_, s.x_m, s.y_m, s.yaw_rad, in + kTalContext * count, count);
  }
  tal_->Forward(in_, out_);
  for (int k = 0; k < count; ++k) {
    const PlannerState& s = states[k];
    const float c = std::cos(static_cast<float>(s.yaw_rad));
    const float sn = std::sin(static_cast<float>(s.yaw_rad));
    const float dx = out_(0, k), dy = out_(1, k);
    PlannerState& n = next[k];
    n.x_m = s.x_m + c * dx - sn * dy;
    n.y_m = s.y_m + sn * dx + c * dy;
    n.yaw_rad = s.yaw_rad + out_(2, k);
    n.z_m = s.z_m + out_(3, k);
    n.roll_rad = out_(4, k);
    n.pitch_rad = out_(5, k);
  }
}

std::unique_ptr<RolloutModel> HybridRolloutModel::Clone() const {
  return std::make_unique<HybridRolloutModel>(*this);
}

}  // namespace vb::controllers
