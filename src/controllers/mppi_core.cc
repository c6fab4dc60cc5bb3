// MPPI core (mppi_core.h). The steps of one update follow Williams et al.'s information-theoretic
// MPPI as the original's planners implement it (reference §7.3): noise drawn per sample, step and
// control; the perturbed command clamped to the bounds and the noise recomputed from the clamped
// command (so the update never pushes the sequence where no sample went); costs per step through
// the plug-ins; weights exp(-(c - min c) / lambda), normalised; u_t += sum_k w_k eps_tk; clamp.
#include "vb/controllers/mppi_core.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "vb/engine/error.h"
#include "vb/engine/normal_sampler.h"

namespace vb::controllers {

MppiCore::MppiCore(const MppiParams& params) : params_(params), rng_(0) {
  VB_DEMAND(params_.horizon_steps > 0 && params_.samples > 0 && params_.temperature > 0.0);
  for (int d = 0; d < kMppiControlDims; ++d) {
    VB_DEMAND(params_.noise_variance[d] > 0.0 && params_.u_min[d] <= params_.u_max[d]);
  }
  const size_t t = static_cast<size_t>(params_.horizon_steps);
  const size_t k = static_cast<size_t>(params_.samples);
  nominal_.assign(t, MppiControl{0.0, 0.0});
  controls_.assign(t * k, MppiControl{0.0, 0.0});
  noise_.assign(t * k, MppiControl{0.0, 0.0});
  state_a_.assign(k, PlannerState());
  state_b_.assign(k, PlannerState());
  stage_cost_.assign(k, 0.0);
  total_cost_.assign(k, 0.0);
  weights_.assign(k, 0.0);
}

void MppiCore::Reset(uint64_t seed) {
  rng_ = Rng(seed);
  std::fill(nominal_.begin(), nominal_.end(), MppiControl{0.0, 0.0});
}

void MppiCore::SetNominal(const std::vector<MppiControl>& u) {
  VB_DEMAND(u.size() == nominal_.size());
  nominal_ = u;   // same size: copies into the existing storage
}

MppiControl MppiCore::Update(const PlannerState& start, const RolloutModel& model,
                             RolloutCost& cost, const MppiControl& u_min,
                             const MppiControl& u_max) {
  const int T = params_.horizon_steps;
  const int K = params_.samples;
  const double lambda = params_.temperature;
  MppiControl std_dev, inv_var;
  for (int d = 0; d < kMppiControlDims; ++d) {
    std_dev[d] = std::sqrt(params_.noise_variance[d]);
    inv_var[d] = 1.0 / params_.noise_variance[d];
  }

  // Sample: step-major so each step's batch is contiguous for the plug-ins.
  for (int t = 0; t < T; ++t) {
    const MppiControl& u = nominal_[t];
    MppiControl* v = &controls_[static_cast<size_t>(t) * K];
    MppiControl* eps = &noise_[static_cast<size_t>(t) * K];
    for (int k = 0; k < K; ++k) {
      for (int d = 0; d < kMppiControlDims; ++d) {
        const double perturbed = u[d] + std_dev[d] * NormalSampler::Draw(&rng_);
        v[k][d] = std::clamp(perturbed, u_min[d], u_max[d]);
        eps[k][d] = v[k][d] - u[d];
      }
    }
  }

  // Roll out and score.
  std::fill(state_a_.begin(), state_a_.end(), start);
  std::fill(total_cost_.begin(), total_cost_.end(), 0.0);
  for (int t = 0; t < T; ++t) {
    const MppiControl* v = &controls_[static_cast<size_t>(t) * K];
    const MppiControl* eps = &noise_[static_cast<size_t>(t) * K];
    model.Step(t, state_a_.data(), v, K, state_b_.data());
    std::swap(state_a_, state_b_);
    cost.Evaluate(t, state_a_.data(), v, K, stage_cost_.data());
    const MppiControl& u = nominal_[t];
    MppiControl a;  // lambda * u_d / var_d
    for (int d = 0; d < kMppiControlDims; ++d) a[d] = lambda * u[d] * inv_var[d];
    for (int k = 0; k < K; ++k) {
      double control_cost = 0.0;
      if (params_.control_cost == ControlCostForm::kSigned) {
        for (int d = 0; d < kMppiControlDims; ++d) control_cost += a[d] * eps[k][d];
      } else {
        for (int d = 0; d < kMppiControlDims; ++d) control_cost += 0.5 * std::abs(a[d] * eps[k][d]);
      }
      const double c = stage_cost_[k] + control_cost;
      total_cost_[k] = params_.accumulation == CostAccumulation::kSum ? total_cost_[k] + c : c;
    }
  }

  // Weights. A non-finite cost (a model leaving its domain) gets weight 0, never NaN weights.
  double min_cost = std::numeric_limits<double>::infinity();
  for (int k = 0; k < K; ++k) {
    if (std::isfinite(total_cost_[k])) min_cost = std::min(min_cost, total_cost_[k]);
  }
  double sum = 0.0;
  for (int k = 0; k < K; ++k) {
    weights_[k] = std::isfinite(total_cost_[k]) && std::isfinite(min_cost)
                      ? std::exp(-(total_cost_[k] - min_cost) / lambda)
                      : 0.0;
    sum += weights_[k];
  }
  for (int k = 0; k < K; ++k) {
    weights_[k] = (sum > 0.0 ? weights_[k] / sum : 0.0) + params_.weight_floor;
  }

  // Update the nominal sequence by the weighted noise, within the bounds.
  for (int t = 0; t < T; ++t) {
    const MppiControl* eps = &noise_[static_cast<size_t>(t) * K];
    MppiControl du{0.0, 0.0};
    for (int k = 0; k < K; ++k) {
      for (int d = 0; d < kMppiControlDims; ++d) du[d] += weights_[k] * eps[k][d];
    }
    for (int d = 0; d < kMppiControlDims; ++d) {
      nominal_[t][d] = std::clamp(nominal_[t][d] + du[d], u_min[d], u_max[d]);
    }
  }

  // Use the first command; shift for the next update.
  const MppiControl first = nominal_[0];
  std::rotate(nominal_.begin(), nominal_.begin() + 1, nominal_.end());
  if (params_.warm_start == WarmStart::kShiftHoldLast && T > 1) nominal_[T - 1] = nominal_[T - 2];
  return first;
}

}  // namespace vb::controllers
