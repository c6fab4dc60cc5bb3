"""The outcome of one trial under the original's rules and under vb's, decided step by step.

Both trackers take the state at every physics step (time, reference-point position, roll) and
say when their rule set has decided. They are what the harness uses to label the original's runs
by both rule sets, so a disagreement between vb and the original is never a difference of rules.

The original's rules (its `*_sim.py` loops, reference_verti_bench.md §6.1), in its order per step:
  stuck    the step moved (3-D) less than 0.01 m: counter += step, else counter = 0; counter >= 10 s
  success  3-D distance to the goal marker < 8 m (the marker: high-res height at the goal + 2 m)
  timeout  time > max_time (60 s)
The original has no rollover outcome; `with_rollover` relabels a failure that ends with |roll| >
30 deg as "rollover", as the paper must have (vb's rollover rule at the end).

vb's rules (docs/architecture.md "Episode", src/engine/runner/episode.cc), after each step:
  success        planar distance to the goal <= 10 m
  out_of_bounds  the reference point left the 128 m world
  early end      |roll| > 90 deg, or moved <= 1 m (planar) over the last 10 s;
                 then, as at the 60 s limit: rollover if |roll| > 30 deg, stuck if the window
                 condition holds, else timeout
"""
import math
from collections import deque

STEP_S = 5e-3


class OriginalRules:
    def __init__(self, goal_marker, max_time_s=60.0, step_s=STEP_S):
        self.goal = goal_marker
        self.max_time_s = max_time_s
        self.step_s = step_s
        self.counter_s = 0.0
        self.last = None
        self.status = None
        self.time_s = None

    def push(self, t, pos):
        """Returns the status once decided (then keeps it)."""
        if self.status is not None:
            return self.status
        if self.last is not None:
            if math.dist(pos, self.last) < 0.01:
                self.counter_s += self.step_s  # accumulated as the original does
            else:
                self.counter_s = 0.0
            if self.counter_s >= 10.0:
                return self._decide("stuck", t)
        self.last = pos
        if math.dist(pos, self.goal) < 8.0:
            return self._decide("success", t)
        if t > self.max_time_s:
            return self._decide("timeout", t)
        return None

    def _decide(self, status, t):
        self.status, self.time_s = status, t
        return status


def with_rollover(status, final_roll_deg):
    return "rollover" if status in ("stuck", "timeout") and abs(final_roll_deg) > 30.0 else status


class VbRules:
    def __init__(self, goal_xy, max_time_s=60.0, step_s=STEP_S, world_half_m=64.0,
                 goal_radius_m=10.0, window_s=10.0, stuck_distance_m=1.0):
        self.goal_xy = goal_xy
        self.max_steps = round(max_time_s / step_s)
        self.world_half_m = world_half_m
        self.goal_radius_m = goal_radius_m
        self.window = deque(maxlen=round(window_s / step_s))
        self.stuck_distance_m = stuck_distance_m
        self.k = -1
        self.status = None
        self.time_s = None

    def _stuck(self):
        w = self.window
        return len(w) == w.maxlen and math.dist(w[0], w[-1]) <= self.stuck_distance_m

    def _classify(self, roll_deg):
        if abs(roll_deg) > 30.0:
            return "rollover"
        return "stuck" if self._stuck() else "timeout"

    def push(self, t, pos, roll_deg):
        if self.status is not None:
            return self.status
        self.k += 1
        xy = (pos[0], pos[1])
        self.window.append(xy)
        if self.k == 0:
            return None  # the initial state: vb checks after each step
        if math.dist(xy, self.goal_xy) <= self.goal_radius_m:
            return self._decide("success", t)
        if abs(xy[0]) > self.world_half_m or abs(xy[1]) > self.world_half_m:
            return self._decide("out_of_bounds", t)
        if abs(roll_deg) > 90.0 or self._stuck() or self.k >= self.max_steps:
            return self._decide(self._classify(roll_deg), t)
        return None

    def finish(self, t, roll_deg):
        """The trial ended before vb's rules decided (the original's goal or time limit)."""
        if self.status is None:
            self._decide(self._classify(roll_deg), t)
        return self.status

    def _decide(self, status, t):
        self.status, self.time_s = status, t
        return status
