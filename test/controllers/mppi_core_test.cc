// MPPI core on hand-made problems: convergence on a quadratic cost, weights and update against a
// hand computation from the drawn samples, cost accumulation variants, warm start, determinism,
// and no allocation per update.
#include "vb/controllers/mppi_core.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <vector>

// Counts heap allocations of this test binary (the hot-loop rule: an update allocates nothing).
static std::atomic<long> g_allocations{0};
// For the other tests of this binary (hybrid_controller_test.cc).
long VbTestAllocations() { return g_allocations.load(); }
void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace vb::controllers {
namespace {

// x += u_speed, y += u_steer: the state integrates the commands.
class IntegratorModel : public RolloutModel {
 public:
  void Step(int, const PlannerState* s, const MppiControl* u, int n,
            PlannerState* next) const override {
    for (int k = 0; k < n; ++k) {
      next[k] = s[k];
      next[k].x_m += u[k][0];
      next[k].y_m += u[k][1];
    }
  }
  std::unique_ptr<RolloutModel> Clone() const override {
    return std::make_unique<IntegratorModel>(*this);
  }
};

// Quadratic in the commands: minimum at u = target at every step.
class QuadraticCommandCost : public RolloutCost {
 public:
  explicit QuadraticCommandCost(MppiControl target) : target_(target) {}
  void Evaluate(int, const PlannerState*, const MppiControl* u, int n, double* c) override {
    for (int k = 0; k < n; ++k) {
      const double a = u[k][0] - target_[0], b = u[k][1] - target_[1];
      c[k] = a * a + b * b;
    }
  }
  std::unique_ptr<RolloutCost> Clone() const override {
    return std::make_unique<QuadraticCommandCost>(*this);
  }

 private:
  MppiControl target_;
};

// The state's x after the step (and records the step index it was called with).
class StateXCost : public RolloutCost {
 public:
  void Evaluate(int step, const PlannerState* s, const MppiControl*, int n, double* c) override {
    last_step = step;
    for (int k = 0; k < n; ++k) c[k] = s[k].x_m;
  }
  std::unique_ptr<RolloutCost> Clone() const override {
    return std::make_unique<StateXCost>(*this);
  }
  int last_step = -1;
};

MppiParams Wide() {
  MppiParams p;
  p.u_min = {-2.0, -2.0};
  p.u_max = {2.0, 2.0};
  return p;
}

TEST(MppiCoreTest, ConvergesOnAQuadraticCost) {
  // MPPI minimises the cost plus the control penalty (lambda / 2) u^T Sigma^-1 u that its
  // control term lambda u^T Sigma^-1 eps stands for. Per step and dimension the cost (u - c)^2
  // then has its minimum at u* = c * 2 var / (2 var + lambda): with lambda 1, var (0.2, 0.5) and
  // c (0.7, -0.4): u* = (0.2, -0.2). The commands converge there and then jitter by the sampling
  // error of the weighted mean (~0.05 here); averaged over updates they sit on it.
  MppiParams p = Wide();
  p.horizon_steps = 5;
  p.temperature = 1.0;
  MppiCore core(p);
  core.Reset(1);
  IntegratorModel model;
  QuadraticCommandCost cost({0.7, -0.4});
  const MppiControl expected{0.7 * 0.4 / 1.4, -0.4 * 1.0 / 2.0};
  MppiControl mean{0.0, 0.0};
  const int n = 200, settle = 20;
  for (int i = 0; i < n; ++i) {
    const MppiControl u = core.Update(PlannerState(), model, cost);
    if (i < settle) continue;
    mean[0] += u[0] / (n - settle);
    mean[1] += u[1] / (n - settle);
    EXPECT_NEAR(u[0], expected[0], 0.2) << i;
    EXPECT_NEAR(u[1], expected[1], 0.2) << i;
  }
  EXPECT_NEAR(mean[0], expected[0], 0.01);
  EXPECT_NEAR(mean[1], expected[1], 0.01);
}

TEST(MppiCoreTest, ConvergesOnAQuadraticStateCost) {
  // Reach the point (6, -3) at the end of a 10-step horizon with the integrator: the optimum of
  // a last-step cost |x_T - p|^2 is any sequence summing to p; check the sum.
  MppiParams p = Wide();
  p.horizon_steps = 10;
  p.accumulation = CostAccumulation::kLastStep;
  MppiCore core(p);
  core.Reset(2);
  IntegratorModel model;
  class EndPointCost : public RolloutCost {
   public:
    void Evaluate(int, const PlannerState* s, const MppiControl*, int n, double* c) override {
      for (int k = 0; k < n; ++k) {
        c[k] = (s[k].x_m - 6.0) * (s[k].x_m - 6.0) + (s[k].y_m + 3.0) * (s[k].y_m + 3.0);
      }
    }
    std::unique_ptr<RolloutCost> Clone() const override {
      return std::make_unique<EndPointCost>(*this);
    }
  } cost;
  MppiControl first{};
  for (int i = 0; i < 60; ++i) {
    // hold the start: check where the nominal sequence (before the shift) ends
    first = core.Update(PlannerState(), model, cost);
    core.SetNominal([&] {
      std::vector<MppiControl> u = core.nominal();
      std::rotate(u.rbegin(), u.rbegin() + 1, u.rend());
      u[0] = first;
      return u;
    }());
  }
  double sx = 0, sy = 0;
  for (const MppiControl& u : core.nominal()) {
    sx += u[0];
    sy += u[1];
  }
  EXPECT_NEAR(sx, 6.0, 0.15);
  EXPECT_NEAR(sy, -3.0, 0.15);
}

TEST(MppiCoreTest, WeightsAndUpdateMatchAHandComputation) {
  MppiParams p = Wide();
  p.horizon_steps = 2;
  p.samples = 5;
  p.temperature = 0.5;
  p.accumulation = CostAccumulation::kSum;
  MppiCore core(p);
  core.Reset(3);
  core.SetNominal({MppiControl{0.3, -0.1}, MppiControl{0.2, 0.4}});
  const std::vector<MppiControl> u0 = core.nominal();
  IntegratorModel model;
  StateXCost cost;
  const MppiControl first = core.Update(PlannerState(), model, cost);

  // By hand from the drawn samples: cost_k = sum_t x_t + control terms, x_t the running sum of
  // the speed commands; control term lambda * sum_d u_d eps_d / var_d.
  std::vector<double> c(5, 0.0), w(5, 0.0);
  for (int k = 0; k < 5; ++k) {
    double x = 0.0;
    for (int t = 0; t < 2; ++t) {
      const MppiControl& v = core.sampled(t, k);
      x += v[0];
      c[k] += x;
      for (int d = 0; d < 2; ++d) c[k] += 0.5 * u0[t][d] * (v[d] - u0[t][d]) / p.noise_variance[d];
    }
    EXPECT_NEAR(core.costs()[k], c[k], 1e-12) << k;
  }
  const double cmin = *std::min_element(c.begin(), c.end());
  double sum = 0.0;
  for (int k = 0; k < 5; ++k) sum += w[k] = std::exp(-(c[k] - cmin) / 0.5);
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(core.weights()[k], w[k] / sum, 1e-12) << k;
  MppiControl expect_first = u0[0];
  for (int d = 0; d < 2; ++d) {
    for (int k = 0; k < 5; ++k) expect_first[d] += w[k] / sum * (core.sampled(0, k)[d] - u0[0][d]);
  }
  EXPECT_NEAR(first[0], expect_first[0], 1e-12);
  EXPECT_NEAR(first[1], expect_first[1], 1e-12);
  // the weighted mean moved the speed command towards lower x (lower cost)
  EXPECT_LT(first[0], 0.3 + 1e-12);
}

TEST(MppiCoreTest, LastStepAccumulationCountsOnlyTheLastStep) {
  MppiParams p = Wide();
  p.horizon_steps = 4;
  p.samples = 16;
  p.accumulation = CostAccumulation::kLastStep;
  MppiCore core(p);
  core.Reset(4);   // nominal zero: no control cost
  IntegratorModel model;
  StateXCost cost;
  core.Update(PlannerState(), model, cost);
  EXPECT_EQ(cost.last_step, 3);
  for (int k = 0; k < 16; ++k) {
    double x = 0.0;
    for (int t = 0; t < 4; ++t) x += core.sampled(t, k)[0];
    EXPECT_NEAR(core.costs()[k], x, 1e-12);
  }
}

TEST(MppiCoreTest, SamplesStayInsideTheBoundsAndTheUpdateToo) {
  MppiCore core;   // default bounds: speed [0.45, 0.6], steering [-1, 1]
  core.Reset(5);
  IntegratorModel model;
  StateXCost cost;
  const MppiControl u = core.Update(PlannerState(), model, cost);
  for (int t = 0; t < 20; ++t) {
    for (int k = 0; k < 800; ++k) {
      EXPECT_GE(core.sampled(t, k)[0], 0.45);
      EXPECT_LE(core.sampled(t, k)[0], 0.6);
      EXPECT_LE(std::abs(core.sampled(t, k)[1]), 1.0);
    }
  }
  EXPECT_GE(u[0], 0.45);
  EXPECT_LE(u[0], 0.6);
}

TEST(MppiCoreTest, WarmStartShiftsOrRollsTheSequence) {
  for (WarmStart mode : {WarmStart::kShiftHoldLast, WarmStart::kRollCyclic}) {
    MppiParams p = Wide();
    p.horizon_steps = 4;
    p.samples = 8;
    p.noise_variance = {1e-20, 1e-20};   // the update moves nothing measurable
    p.warm_start = mode;
    MppiCore core(p);
    core.Reset(6);
    core.SetNominal({MppiControl{0.1, 0}, MppiControl{0.2, 0}, MppiControl{0.3, 0},
                     MppiControl{0.4, 0}});
    IntegratorModel model;
    StateXCost cost;
    EXPECT_NEAR(core.Update(PlannerState(), model, cost)[0], 0.1, 1e-9);
    const std::vector<MppiControl>& u = core.nominal();
    EXPECT_NEAR(u[0][0], 0.2, 1e-9);
    EXPECT_NEAR(u[2][0], 0.4, 1e-9);
    EXPECT_NEAR(u[3][0], mode == WarmStart::kRollCyclic ? 0.1 : 0.4, 1e-9);
  }
}

TEST(MppiCoreTest, DeterministicWithASeedAndDifferentAcrossSeeds) {
  IntegratorModel model;
  QuadraticCommandCost cost({0.5, 0.5});
  auto run = [&](uint64_t seed) {
    MppiCore core;
    core.Reset(seed);
    std::vector<double> out;
    for (int i = 0; i < 5; ++i) {
      const MppiControl u = core.Update(PlannerState(), model, cost);
      out.push_back(u[0]);
      out.push_back(u[1]);
    }
    return out;
  };
  EXPECT_EQ(run(9), run(9));   // bit for bit
  EXPECT_NE(run(9), run(10));
}

TEST(MppiCoreTest, AnUpdateAllocatesNothing) {
  MppiCore core;
  core.Reset(11);
  IntegratorModel model;
  QuadraticCommandCost cost({0.5, 0.0});
  core.Update(PlannerState(), model, cost);
  const long before = g_allocations.load();
  for (int i = 0; i < 3; ++i) core.Update(PlannerState(), model, cost);
  EXPECT_EQ(g_allocations.load(), before);
}

}  // namespace
}  // namespace vb::controllers
