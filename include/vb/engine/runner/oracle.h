// The privileged expert ("oracle", docs/baselines.md): a sampling planner whose rollouts are vb's
// own physics. Every replanning period it snapshots the real episode, restores the snapshot into
// a private planning episode once per candidate, drives the candidate for the horizon, scores
// the outcome (obstacle-aware cost-to-go at the end, success, rollover and tipping penalties)
// and commits to the best candidate's first segment. Candidates are stateless command laws of
// the observation and the steering applied so far, so the committed segment is bit for bit the
// rollout that was scored (the real episode is never touched by a rollout: it is only read by
// Episode::Snapshot).
//
// A candidate is (first segment, speed): for the replanning period either the path follower's
// steering (the PID's law on the look-ahead point, rate limited as the PID) or a constant
// steering primitive, at a target speed; then, for the rest of the horizon, the path follower at
// the PID's 4 m/s (a receding-horizon tail policy: "swerve now, then follow the path").
// Candidate 0 is the PID's own action; ties go to the lowest index.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "vb/controllers/controller.h"
#include "vb/terrain/grid_planner.h"

namespace vb::runner {

class Episode;

struct OracleParams {
  double horizon_s = 3.0;             // rollout length
  double replan_period_s = 1.0;       // committed segment (a whole number of control periods)
  // Constant-steering primitives of the first segment ([-1, 1], + left), each at every speed.
  std::vector<double> steering = {-1.0, -0.5, 0.0, 0.5, 1.0};
  // Target speeds (m/s) of the path-following and primitive candidates' first segment.
  std::vector<double> speeds_mps = {4.0, 2.0};
  double tail_speed_mps = 4.0;        // the path follower after the first segment
  // Early accept: when candidate 0 (the PID's action) neither tips nor ends in failure and its
  // rollout gains at least this fraction of tail_speed x horizon in cost-to-go, it is taken
  // without rolling out the others (most of a benchmark trial is easy driving). 0: always search.
  double early_accept_fraction = 0.5;
  // Cost terms (metres of cost-to-go).
  double failure_cost_m = 1.0e4;      // the rollout ends in rollover, out_of_bounds, sim_error
  double stuck_cost_m = 1.0e3;        // the rollout ends stuck
  // Stalled: the rollout moved less than stall_distance_m (x scale) in its last stall_window_s
  // (hung up on a rock, dug in, facing a wall: a stuck in the making that the 10 s stuck rule
  // cannot see within a short horizon).
  double stall_window_s = 1.0;
  double stall_distance_m = 0.5;
  double stall_cost_m = 100.0;
  double tip_roll_rad = 25.0 * 3.14159265358979323846 / 180.0;  // peak |roll| above: penalty
  double tip_cost_m_per_rad = 500.0;  // per radian of peak |roll| above tip_roll_rad
  double success_cost_m = -1.0e4;     // plus the time to the goal in seconds
  // Obstacle dilation of the cost-to-go grid in cells; -1: the global planners' (4 m x scale,
  // terrain::PlannerInflationCells), so the cost-to-go is the metric the path follower's A*
  // follows (a thinner dilation lures the planner into gaps the vehicle cannot pass).
  int cost_inflation_cells = -1;
};

// Parses "oracle" (default budget) or "oracle-h<horizon s>-r<replan s>-n<steering levels>-e<0|1>"
// with any subset of the keys in any order (n: odd count of primitives evenly spread over
// [-1, 1], 0 for none; e0: no early accept). Throws InputError naming the system otherwise.
OracleParams ParseOracleName(const std::string& name, const std::string& key = "system");
bool IsOracleName(const std::string& name);

// Work done, for the cost measurements (benchmarks, tests).
struct OracleStats {
  long replans = 0;
  long early_accepts = 0;
  long rollouts = 0;
  long rollout_steps = 0;         // physics steps simulated in rollouts
  // Committed segments whose real end state differed from the scored rollout's (must stay 0).
  long prediction_mismatches = 0;
  long predictions_checked = 0;
};

class OracleController : public controllers::Controller {
 public:
  // `real` is the episode the oracle drives: read (snapshots) at every replanning, never
  // stepped or restored by the oracle; it must outlive the controller.
  OracleController(const Episode* real, const OracleParams& params = OracleParams(),
                   std::string name = "oracle");
  ~OracleController() override;
  std::string name() const override { return name_; }
  controllers::ObservationConfig observation_config() const override;
  void Reset(const controllers::EpisodeContext& context) override;
  controllers::Command Update(const controllers::Observation& obs) override;
  std::unique_ptr<controllers::Controller> Clone() const override;

  const OracleStats& stats() const { return stats_; }
  // Number of candidates per full search.
  int num_candidates() const;

 private:
  struct Candidate {
    bool follow_path = true;   // first segment: path follower, else constant steering
    double steering = 0.0;
    double speed_mps = 4.0;
  };
  controllers::Command CommandFor(const Candidate& c, bool in_first_segment,
                                  const controllers::Observation& obs, double* steering) const;
  double CostToGo(const Vec2& p_m) const;
  // Rolls candidate c out from `start`; returns its cost and, if the rollout got that far, the
  // position at the end of the first segment (*segment_end, *reached_segment_end). *accept: the
  // early-accept test passed.
  double Rollout(const Candidate& c, const class EpisodeSnapshot& start, double start_ctg,
                 Vec3* segment_end, bool* reached_segment_end, bool* accept);
  void Plan();
  void BuildPlanner();

  const Episode* real_;
  OracleParams params_;
  std::string name_;
  std::vector<Candidate> candidates_;
  controllers::EpisodeContext context_;
  int segment_steps_ = 1;   // control periods per committed segment
  int horizon_steps_ = 1;   // control periods per rollout
  int stall_steps_ = 1;     // control periods of the stall window (<= horizon)
  // Built on first use (Reset): the planning episode and the cost-to-go field.
  std::unique_ptr<Episode> plan_;
  std::unique_ptr<terrain::OccupancyGrid> cost_grid_;
  std::unique_ptr<terrain::GoalDistanceField> cost_field_;
  // Driving state.
  double steering_ = 0.0;        // applied at the last control period
  int current_ = 0;              // committed candidate
  int segment_left_ = 0;         // control periods left in the committed segment
  bool have_prediction_ = false;
  Vec3 predicted_end_ = Vec3::Zero();
  OracleStats stats_;
};

}  // namespace vb::runner
