"""Which level (training world, start/goal pair) each new episode gets: the difference between
vb's three learned baselines (docs/learning.md).

* ``UniformSampler`` (RL): every level equally likely.
* ``ManualCurriculum`` (MCL): three stages of growing difficulty (STAGES); a stage ends when the
  success rate of its last SWITCH_WINDOW episodes reaches SWITCH_SUCCESS, or when its step budget
  (a fraction of the total, STAGE_BUDGET) is used up, whichever comes first.
* ``PrioritizedLevelReplay`` (ACL): Jiang et al. 2021's PLR over the levels: a level's score is
  the mean positive generalized advantage of its last visit (the "positive value loss"), replay
  draws seen levels by rank of the score (temperature BETA) mixed with staleness (RHO); with
  probability 1 - P_REPLAY (or while fewer than MIN_SEEN are seen) an unseen level is drawn.

All randomness comes from the numpy Generator given to the sampler (seeded by the command).
"""

from __future__ import annotations

from collections import deque
from typing import Sequence

import numpy as np

from .worlds import World

Level = tuple[int, int]   # (index into the world list, pair)


class UniformSampler:
    name = "uniform"

    def __init__(self, worlds: Sequence[World], num_pairs: int, rng: np.random.Generator):
        self.worlds, self.num_pairs, self.rng = list(worlds), num_pairs, rng

    def sample(self) -> Level:
        return int(self.rng.integers(len(self.worlds))), int(self.rng.integers(self.num_pairs))

    def on_episode_end(self, level: Level, status: str, num_timesteps: int) -> None:
        pass

    def on_step(self, num_timesteps: int) -> None:
        pass

    def wants_scores(self) -> bool:
        return False

    def update_score(self, level: Level, score: float) -> None:
        pass

    def stage(self) -> int:
        return 0


# MCL stages: the allowed (elevations, terrains, densities). Stage 2 is the full pool.
STAGES = (
    (("low",), ("rigid",), ("sparse", "medium")),
    (("low", "mid"), ("rigid", "mixed"), ("sparse", "medium", "dense")),
    (("low", "mid", "high"), ("rigid", "deformable", "mixed"), ("sparse", "medium", "dense")),
)
STAGE_BUDGET = (0.2, 0.25)     # most steps of stage 0 and 1, as fractions of the total
SWITCH_WINDOW = 40
SWITCH_SUCCESS = 0.6


class ManualCurriculum(UniformSampler):
    name = "manual"

    def __init__(self, worlds: Sequence[World], num_pairs: int, rng: np.random.Generator,
                 total_timesteps: int):
        super().__init__(worlds, num_pairs, rng)
        self.total = total_timesteps
        self._stage = 0
        self.stage_start = 0
        self.recent: deque[bool] = deque(maxlen=SWITCH_WINDOW)
        self.switches: list[dict] = []
        self._allowed = self._allowed_worlds()

    def _allowed_worlds(self) -> list[int]:
        el, te, de = STAGES[self._stage]
        return [i for i, w in enumerate(self.worlds)
                if w.elevation in el and w.terrain in te and w.density in de]

    def sample(self) -> Level:
        w = self._allowed[int(self.rng.integers(len(self._allowed)))]
        return w, int(self.rng.integers(self.num_pairs))

    def stage(self) -> int:
        return self._stage

    def _advance(self, num_timesteps: int, reason: str) -> None:
        self.switches.append({"from_stage": self._stage, "at_timestep": num_timesteps,
                              "reason": reason})
        self._stage += 1
        self.stage_start = num_timesteps
        self.recent.clear()
        self._allowed = self._allowed_worlds()

    def on_episode_end(self, level: Level, status: str, num_timesteps: int) -> None:
        if self._stage >= len(STAGES) - 1:
            return
        self.recent.append(status == "success")
        if len(self.recent) == SWITCH_WINDOW and np.mean(self.recent) >= SWITCH_SUCCESS:
            self._advance(num_timesteps, f"success {np.mean(self.recent):.2f} over the last "
                                         f"{SWITCH_WINDOW} episodes")

    def on_step(self, num_timesteps: int) -> None:
        if self._stage < len(STAGES) - 1 and \
                num_timesteps - self.stage_start >= STAGE_BUDGET[self._stage] * self.total:
            self._advance(num_timesteps, "step budget of the stage used up")


BETA = 0.1
RHO = 0.3
P_REPLAY = 0.5
MIN_SEEN = 8


class PrioritizedLevelReplay(UniformSampler):
    name = "plr"

    def __init__(self, worlds: Sequence[World], num_pairs: int, rng: np.random.Generator):
        super().__init__(worlds, num_pairs, rng)
        self.levels = [(w, p) for w in range(len(self.worlds)) for p in range(num_pairs)]
        self.index = {level: i for i, level in enumerate(self.levels)}
        self.scores = np.zeros(len(self.levels))
        self.last_sampled = np.zeros(len(self.levels))
        self.seen = np.zeros(len(self.levels), dtype=bool)
        self.episodes = 0
        self.replays = 0

    def wants_scores(self) -> bool:
        return True

    def replay_distribution(self) -> np.ndarray:
        seen = np.flatnonzero(self.seen)
        order = np.argsort(-self.scores[seen], kind="stable")
        ranks = np.empty(len(seen))
        ranks[order] = np.arange(1, len(seen) + 1)
        h = (1.0 / ranks) ** (1.0 / BETA)
        p_score = h / h.sum()
        staleness = self.episodes - self.last_sampled[seen]
        p_stale = staleness / staleness.sum() if staleness.sum() > 0 else np.full(
            len(seen), 1.0 / len(seen))
        p = np.zeros(len(self.levels))
        p[seen] = (1.0 - RHO) * p_score + RHO * p_stale
        return p

    def sample(self) -> Level:
        self.episodes += 1
        unseen = np.flatnonzero(~self.seen)
        replay = self.rng.random() < P_REPLAY
        if len(unseen) == 0 or (self.seen.sum() >= MIN_SEEN and replay):
            i = int(self.rng.choice(len(self.levels), p=self.replay_distribution()))
            self.replays += 1
        else:
            i = int(unseen[self.rng.integers(len(unseen))])
            self.seen[i] = True
        self.last_sampled[i] = self.episodes
        return self.levels[i]

    def update_score(self, level: Level, score: float) -> None:
        self.scores[self.index[level]] = score
