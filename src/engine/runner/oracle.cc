// The privileged expert (oracle.h, docs/baselines.md "Oracle"): candidates rolled out with the
// real physics in a private planning episode, restored from a snapshot of the real one.
#include "vb/engine/runner/oracle.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include "vb/controllers/pid_controller.h"
#include "vb/engine/error.h"
#include "vb/engine/runner/episode.h"

namespace vb::runner {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// How far (cells) the cost-to-go looks for a free cell around a point inside an obstacle's
// footprint (a vehicle pressed against a rock still has a finite, comparable cost).
constexpr int kCostSearchCells = 8;

// A whole number (>= 1) of control periods in `seconds`; InputError otherwise.
int Periods(double seconds, double period_s, const std::string& what) {
  const double ratio = seconds / period_s;
  const long n = std::lround(ratio);
  if (!(n >= 1) || std::abs(ratio - static_cast<double>(n)) > 1e-9 * ratio) {
    char buf[160];
    std::snprintf(buf, sizeof(buf), "must be a whole number (>= 1) of control periods of %g s, got %g s",
                  period_s, seconds);
    throw InputError("", 0, "system", "oracle " + what + " " + buf);
  }
  return static_cast<int>(n);
}

}  // namespace

bool IsOracleName(const std::string& name) {
  return name == "oracle" || name.rfind("oracle-", 0) == 0;
}

OracleParams ParseOracleName(const std::string& name, const std::string& key) {
  OracleParams p;
  if (name == "oracle") return p;
  auto bad = [&](const std::string& why) {
    return InputError("", 0, key,
                      "'" + name + "': " + why +
                          "; expected oracle or oracle-h<horizon s>-r<replan s>-n<odd steering "
                          "levels or 0>-e<0|1> (docs/baselines.md)");
  };
  if (!IsOracleName(name)) throw bad("not an oracle name");
  size_t at = 7;  // after "oracle-"
  while (at <= name.size()) {
    const size_t end = std::min(name.find('-', at), name.size());
    const std::string key = name.substr(at, end - at);
    if (key.size() < 2) throw bad("empty key");
    const std::string value = key.substr(1);
    char* stop = nullptr;
    const double v = std::strtod(value.c_str(), &stop);
    if (stop == value.c_str() || *stop != '\0' || !std::isfinite(v) || value[0] == '-' ||
        value[0] == '+') {
      throw bad("'" + value + "' is not a number");
    }
    switch (key[0]) {
      case 'h':
        if (!(v > 0.0 && v <= 60.0)) throw bad("horizon must be in (0, 60] s");
        p.horizon_s = v;
        break;
      case 'r':
        if (!(v > 0.0 && v <= 60.0)) throw bad("replanning period must be in (0, 60] s");
        p.replan_period_s = v;
        break;
      case 'n': {
        if (v != std::floor(v) || v > 41 || (v != 0 && std::fmod(v, 2.0) != 1.0)) {
          throw bad("steering levels must be 0 or an odd count up to 41");
        }
        const int n = static_cast<int>(v);
        p.steering.clear();
        for (int i = 0; i < n; ++i) p.steering.push_back(n == 1 ? 0.0 : -1.0 + 2.0 * i / (n - 1));
        break;
      }
      case 'e':
        if (v != 0.0 && v != 1.0) throw bad("e must be 0 or 1");
        p.early_accept_fraction = v == 0.0 ? 0.0 : OracleParams().early_accept_fraction;
        break;
      default:
        throw bad("unknown key '" + key.substr(0, 1) + "'");
    }
    at = end + 1;
  }
  if (p.replan_period_s > p.horizon_s) throw bad("replanning period longer than the horizon");
  return p;
}

OracleController::OracleController(const Episode* real, const OracleParams& params,
                                   std::string name)
    : real_(real), params_(params), name_(std::move(name)) {
  VB_DEMAND(real_ != nullptr);
  // Candidate 0: the PID's own action; then the slower path followers; then the primitives.
  for (double v : params_.speeds_mps) candidates_.push_back({true, 0.0, v});
  for (double v : params_.speeds_mps) {
    for (double s : params_.steering) candidates_.push_back({false, s, v});
  }
  VB_DEMAND(!candidates_.empty());
}

OracleController::~OracleController() = default;

int OracleController::num_candidates() const { return static_cast<int>(candidates_.size()); }

controllers::ObservationConfig OracleController::observation_config() const {
  return controllers::PidController().observation_config();
}

void OracleController::BuildPlanner() {
  EpisodeRules rules = real_->rules();
  rules.trajectory_every_n_steps = 0;
  rules.timings = nullptr;
  plan_ = std::make_unique<Episode>(real_->task(), real_->vehicle_params(), rules,
                                    real_->soil_config());
  plan_->SetObservationConfig(observation_config());
  const int inflation = params_.cost_inflation_cells >= 0
                            ? params_.cost_inflation_cells
                            : terrain::PlannerInflationCells(real_->task());
  cost_grid_ = std::make_unique<terrain::OccupancyGrid>(
      terrain::Inflate(terrain::RasterizeObstacles(real_->task()), inflation));
}

void OracleController::Reset(const controllers::EpisodeContext& context) {
  context_ = context;
  segment_steps_ = Periods(params_.replan_period_s, context.control_period_s, "replanning period");
  horizon_steps_ = Periods(params_.horizon_s, context.control_period_s, "horizon");
  stall_steps_ = std::clamp(
      static_cast<int>(std::lround(params_.stall_window_s / context.control_period_s)), 1,
      horizon_steps_);
  if (!plan_) BuildPlanner();
  cost_field_ = std::make_unique<terrain::GoalDistanceField>(*cost_grid_,
                                                             cost_grid_->CellOf(context.goal_m));
  steering_ = 0.0;
  current_ = 0;
  segment_left_ = 0;
  have_prediction_ = false;
  stats_ = OracleStats();
}

double OracleController::CostToGo(const Vec2& p_m) const {
  const terrain::OccupancyGrid& g = *cost_grid_;
  const terrain::Cell at = g.CellOf(p_m);
  const double own = cost_field_->CostToGoal(at);
  if (std::isfinite(own)) return own * g.cell_m + (p_m - g.CenterOf(at)).norm();
  double best = kInf;
  for (int r = std::max(0, at.row - kCostSearchCells);
       r <= std::min(g.rows - 1, at.row + kCostSearchCells); ++r) {
    for (int c = std::max(0, at.col - kCostSearchCells);
         c <= std::min(g.cols - 1, at.col + kCostSearchCells); ++c) {
      const double f = cost_field_->CostToGoal({r, c});
      if (!std::isfinite(f)) continue;
      best = std::min(best, f * g.cell_m + (p_m - g.CenterOf({r, c})).norm());
    }
  }
  // Cut off from the goal (or the goal inside an obstacle): the straight distance, worse than
  // any connected point.
  if (!std::isfinite(best)) best = (context_.goal_m - p_m).norm() + 1.0e3;
  return best;
}

controllers::Command OracleController::CommandFor(const Candidate& c, bool in_first_segment,
                                                  const controllers::Observation& obs,
                                                  double* steering) const {
  static const controllers::PidParams kPid;
  const bool follow = !in_first_segment || c.follow_path;
  const double target = follow ? kPid.steering_kp * obs.heading_error_rad : c.steering;
  *steering = controllers::RateLimitedSteering(target, *steering,
                                               kPid.steering_rate_per_s * context_.control_period_s);
  controllers::Command command;
  command.steering = *steering;
  controllers::SpeedControl(in_first_segment ? c.speed_mps : params_.tail_speed_mps,
                            obs.forward_speed_mps, kPid.speed_kp, &command);
  return command;
}

double OracleController::Rollout(const Candidate& c, const EpisodeSnapshot& start,
                                 double start_ctg, Vec3* segment_end, bool* reached_segment_end,
                                 bool* accept) {
  Episode& e = *plan_;
  e.Restore(start);
  const long k0 = e.physics_steps();
  const double t0 = e.time_s();
  double steering = steering_;
  double peak_roll = 0.0;
  Vec2 stall_start = e.vehicle_state().pose_W.position.head<2>();
  *reached_segment_end = false;
  for (int i = 0; i < horizon_steps_ && !e.Done(); ++i) {
    if (i == horizon_steps_ - stall_steps_) stall_start = e.vehicle_state().pose_W.position.head<2>();
    e.Step(CommandFor(c, i < segment_steps_, e.Observe(), &steering));
    peak_roll = std::max(peak_roll, std::abs(e.vehicle_state().rpy.roll_rad));
    if (i + 1 == segment_steps_ && !e.Done()) {
      *segment_end = e.vehicle_state().pose_W.position;
      *reached_segment_end = true;
    }
  }
  ++stats_.rollouts;
  stats_.rollout_steps += e.physics_steps() - k0;

  const Vec2 end_xy = e.vehicle_state().pose_W.position.head<2>();
  const double ctg = CostToGo(end_xy);
  double cost = ctg;
  bool failed = false;
  const bool stalled =
      (end_xy - stall_start).norm() < params_.stall_distance_m * context_.scale;
  if (stalled) {
    cost += params_.stall_cost_m;
    failed = true;
  }
  if (e.Done()) {
    const TrialResult r = e.TakeResult();
    switch (r.status) {
      case TrialStatus::kSuccess:
        cost = params_.success_cost_m + (r.sim_time_s - t0);
        failed = false;
        break;
      case TrialStatus::kStuck:
        cost += params_.stuck_cost_m;
        failed = true;
        break;
      case TrialStatus::kTimeout:
        break;
      case TrialStatus::kRollover:
      case TrialStatus::kOutOfBounds:
      case TrialStatus::kSimError:
        cost += params_.failure_cost_m;
        failed = true;
        break;
    }
  }
  const double tip = std::max(0.0, peak_roll - params_.tip_roll_rad);
  cost += params_.tip_cost_m_per_rad * tip;
  const double gain = start_ctg - ctg;
  *accept = !failed && tip == 0.0 &&
            (cost < 0.0 || (params_.early_accept_fraction > 0.0 &&
                            gain >= params_.early_accept_fraction * params_.tail_speed_mps *
                                        params_.horizon_s));
  return cost;
}

void OracleController::Plan() {
  ++stats_.replans;
  const EpisodeSnapshot start = real_->Snapshot();
  const double start_ctg = CostToGo(real_->vehicle_state().pose_W.position.head<2>());
  double best_cost = kInf;
  int best = 0;
  Vec3 best_end = Vec3::Zero();
  bool best_reached = false;
  for (int i = 0; i < num_candidates(); ++i) {
    Vec3 end = Vec3::Zero();
    bool reached = false;
    bool accept = false;
    const double cost = Rollout(candidates_[static_cast<size_t>(i)], start, start_ctg, &end,
                                &reached, &accept);
    if (cost < best_cost) {
      best_cost = cost;
      best = i;
      best_end = end;
      best_reached = reached;
    }
    if (i == 0 && accept) {
      ++stats_.early_accepts;
      break;
    }
  }
  current_ = best;
  have_prediction_ = best_reached;
  predicted_end_ = best_end;
}

controllers::Command OracleController::Update(const controllers::Observation& obs) {
  if (segment_left_ == 0) {
    // The segment just driven was the scored rollout's: the real state must be its end state.
    if (have_prediction_) {
      ++stats_.predictions_checked;
      if (!(real_->vehicle_state().pose_W.position == predicted_end_)) {
        ++stats_.prediction_mismatches;
      }
    }
    Plan();
    segment_left_ = segment_steps_;
  }
  --segment_left_;
  return CommandFor(candidates_[static_cast<size_t>(current_)], true, obs, &steering_);
}

std::unique_ptr<controllers::Controller> OracleController::Clone() const {
  auto copy = std::make_unique<OracleController>(real_, params_, name_);
  copy->context_ = context_;
  copy->segment_steps_ = segment_steps_;
  copy->horizon_steps_ = horizon_steps_;
  if (plan_) {
    copy->BuildPlanner();
    copy->cost_field_ = std::make_unique<terrain::GoalDistanceField>(
        *copy->cost_grid_, copy->cost_grid_->CellOf(context_.goal_m));
  }
  copy->steering_ = steering_;
  copy->current_ = current_;
  copy->segment_left_ = segment_left_;
  copy->have_prediction_ = have_prediction_;
  copy->predicted_end_ = predicted_end_;
  copy->stats_ = stats_;
  return copy;
}

}  // namespace vb::runner
