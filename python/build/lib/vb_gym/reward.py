"""The reward: the original Verti-Bench RL environment's terms (reference: off_road_VertiBench.py,
docs/gym.md "Reward"), each weight configurable.

Per env step of length dt (the control period):

* progress  ``progress * (d_prev - d)``: d is the planar distance from the chassis to the current
  local goal (the look-ahead point on the global path), d_prev the same from the previous
  position, so a replanned local goal does not count as progress.
* stall     ``stall * dt/ref_step`` when ``|d_prev - d| < stall_speed_mps * dt``.
* tilt      ``tilt * (|a|/th) * (|a| - th) * dt/ref_step`` for a = roll and a = pitch above the
  threshold th (radians).
* terminal  ``success``; ``timeout + timeout_per_m * goal distance``; ``stuck``;
  ``out_of_bounds``; ``rollover``; ``sim_error``.

The per-step terms are written per physics step of the original (ref_step = 5 ms) and scaled
with dt/ref_step, so an episode's return does not depend on the control period.
"""

from __future__ import annotations

import dataclasses
import math


@dataclasses.dataclass
class RewardWeights:
    progress: float = 50.0            # per metre of progress towards the local goal
    stall: float = -10.0              # per reference step without progress
    stall_speed_mps: float = 2.0      # 0.01 m per 5 ms: the original's threshold
    tilt: float = -20.0
    tilt_threshold_deg: float = 30.0
    success: float = 3000.0
    timeout: float = -100.0
    timeout_per_m: float = -10.0      # per metre left to the goal at the time limit
    stuck: float = -300.0
    out_of_bounds: float = -600.0     # the original's "fallen off"
    rollover: float = -600.0          # vb's addition: the original never ends on a rollover
    sim_error: float = 0.0
    reference_step_s: float = 0.005

    def validate(self) -> None:
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            if not isinstance(v, (int, float)) or not math.isfinite(v):
                raise ValueError(f"reward.{f.name}: {v!r} is not a finite number")
        if self.reference_step_s <= 0 or self.tilt_threshold_deg <= 0:
            raise ValueError("reward.reference_step_s and reward.tilt_threshold_deg must be > 0")


def step_reward(
    weights: RewardWeights,
    dt_s: float,
    prev_xy: tuple[float, float],
    xy: tuple[float, float],
    local_goal_xy: tuple[float, float],
    roll_rad: float,
    pitch_rad: float,
    status: str,
    goal_distance_m: float,
) -> tuple[float, dict[str, float]]:
    """The reward of one env step and its terms. status: "running" or the trial outcome."""
    d_prev = math.hypot(local_goal_xy[0] - prev_xy[0], local_goal_xy[1] - prev_xy[1])
    d = math.hypot(local_goal_xy[0] - xy[0], local_goal_xy[1] - xy[1])
    scale = dt_s / weights.reference_step_s
    terms = {"progress": weights.progress * (d_prev - d), "stall": 0.0, "tilt": 0.0,
             "terminal": 0.0}
    if abs(d_prev - d) < weights.stall_speed_mps * dt_s:
        terms["stall"] = weights.stall * scale
    th = math.radians(weights.tilt_threshold_deg)
    for angle in (abs(roll_rad), abs(pitch_rad)):
        if angle > th:
            terms["tilt"] += weights.tilt * (angle / th) * (angle - th) * scale
    if status == "success":
        terms["terminal"] = weights.success
    elif status == "timeout":
        terms["terminal"] = weights.timeout + weights.timeout_per_m * goal_distance_m
    elif status == "stuck":
        terms["terminal"] = weights.stuck
    elif status == "out_of_bounds":
        terms["terminal"] = weights.out_of_bounds
    elif status == "rollover":
        terms["terminal"] = weights.rollover
    elif status == "sim_error":
        terms["terminal"] = weights.sim_error
    elif status != "running":
        raise ValueError(f"unknown trial status {status!r}")
    return sum(terms.values()), terms
