"""VbEnv against the real vb_gym: gymnasium's checker, spaces, seeding and determinism,
termination/truncation, configuration errors, a crashed server."""

from __future__ import annotations

import math
import os
import signal

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import vb_gym
from vb_gym import ConfigError, Crop, ServerCrashed, VbEnv, VbGymError
from vb_gym.core import STATE_NAMES

from conftest import RIGID_TASK, RIGID_TASK_2

SMALL = dict(crops=(Crop("elevation", 16, 0.25), Crop("semantics", 8, 1.0)))


def drive(env, actions):
    """(obs, reward, terminated, truncated) of each step, stopping at the end."""
    out = []
    for a in actions:
        obs, reward, terminated, truncated, info = env.step(a)
        out.append((obs, reward, terminated, truncated, info))
        if terminated or truncated:
            break
    return out


def obs_equal(a, b) -> bool:
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a)
    return np.array_equal(a, b)


def test_gymnasium_env_checker_passes():
    env = VbEnv(tasks=[RIGID_TASK, RIGID_TASK_2], **SMALL)
    try:
        check_env(env, skip_render_check=True)
    finally:
        env.close()


def test_registered_id_makes_the_env():
    env = gym.make("vb/OffRoad-v0", tasks=RIGID_TASK, **SMALL)
    try:
        obs, info = env.reset(seed=1)
        assert env.observation_space.contains(obs)
        assert info["task_name"] == "env000"
    finally:
        env.close()


def test_spaces_have_the_documented_layout():
    with VbEnv(tasks=RIGID_TASK, **SMALL) as env:
        space = env.observation_space
        assert set(space.spaces) == {"state", "wheels", "elevation", "semantics"}
        assert space["state"].shape == (len(STATE_NAMES),)
        assert space["wheels"].shape == (4, 6)
        assert space["elevation"].shape == (16, 16)
        assert space["semantics"].low.min() == 0 and space["semantics"].high.max() == 9
        assert env.action_space.shape == (2,)
        assert env.action_space.low.tolist() == [-1, -1]
        obs, _ = env.reset(seed=0)
        state = dict(zip(STATE_NAMES, obs["state"]))
        # At the start: stopped, goal ahead (the vehicle faces it), time 0.
        assert state["time_s"] == 0
        assert state["goal_forward_m"] > 50 and abs(state["goal_left_m"]) < 5
        assert abs(state["forward_speed_mps"]) < 0.5
        # Relative elevation: the crop is near the chassis height (within a few metres).
        assert np.abs(obs["elevation"]).max() < 5
    with VbEnv(tasks=RIGID_TASK, flatten=True, action="direct", include_wheels=False,
               crops=[Crop("occupancy", 4, 1.0)]) as env:
        assert env.observation_space.shape == (len(STATE_NAMES) + 16,)
        assert env.action_space.shape == (3,)
        obs, _ = env.reset(seed=0)
        assert obs.shape == (len(STATE_NAMES) + 16,) and obs.dtype == np.float32


def test_same_seed_gives_bit_identical_episodes_and_reset_draws_new_pairs():
    actions = [np.array([0.3 * math.sin(0.2 * k), 0.8], dtype=np.float32) for k in range(25)]
    with VbEnv(tasks=[RIGID_TASK, RIGID_TASK_2], **SMALL) as env:
        obs_a, info_a = env.reset(seed=42)
        run_a = drive(env, actions)
        drawn = {(info_a["task"], info_a["pair"])}
        for _ in range(8):   # reset() without a seed: new start/goal from the same stream
            _, info = env.reset()
            drawn.add((info["task"], info["pair"]))
        obs_b, info_b = env.reset(seed=42)
        run_b = drive(env, actions)
    # A fresh process gives the same bits too.
    with VbEnv(tasks=[RIGID_TASK, RIGID_TASK_2], **SMALL) as env:
        obs_c, info_c = env.reset(seed=42)
        run_c = drive(env, actions)
    assert len(drawn) >= 4
    for info in (info_b, info_c):
        assert (info["task"], info["pair"], info["seed"]) == (
            info_a["task"], info_a["pair"], info_a["seed"])
    assert obs_equal(obs_a, obs_b) and obs_equal(obs_a, obs_c)
    assert len(run_a) == len(run_b) == len(run_c) == 25
    for (oa, ra, *_), (ob, rb, *_), (oc, rc, *_) in zip(run_a, run_b, run_c):
        assert obs_equal(oa, ob) and obs_equal(oa, oc)
        assert ra == rb == rc
    # The vehicle moved (the episode is real, not a replayed constant).
    assert run_a[-1][0]["state"][STATE_NAMES.index("forward_speed_mps")] > 1.0


def test_options_fix_task_and_pair_and_nothing_leaks_across_episodes():
    with VbEnv(tasks=[RIGID_TASK, RIGID_TASK_2], time_limit_s=0.5, **SMALL) as env:
        _, info = env.reset(seed=0, options={"task": 1, "pair": 3})
        assert (info["task_name"], info["pair"], info["status"]) == ("env001", 3, "running")
        steps = drive(env, [np.zeros(2, np.float32)] * 10)
        assert len(steps) == 5 and steps[-1][3] and steps[-1][4]["status"] == "timeout"
        with pytest.raises(RuntimeError, match="call reset"):
            env.step(np.zeros(2, np.float32))
        obs, info = env.reset(options={"task": 1, "pair": 3})
        assert info["status"] == "running" and "outcome" not in info and info["time_s"] == 0
        assert obs["state"][STATE_NAMES.index("time_s")] == 0
        again = drive(env, [np.zeros(2, np.float32)] * 10)
        assert [s[1] for s in again] == [s[1] for s in steps]   # same rewards: no carried state
        with pytest.raises(ValueError, match="unknown"):
            env.reset(options={"level": 3})


def test_timeout_is_truncation_with_the_timeout_penalty():
    with VbEnv(tasks=RIGID_TASK, time_limit_s=1.0, **SMALL) as env:
        env.reset(seed=3)
        steps = drive(env, [np.array([0.0, -1.0], np.float32)] * 20)   # stand still
        obs, reward, terminated, truncated, info = steps[-1]
        assert len(steps) == 10 and truncated and not terminated
        assert info["outcome"]["status"] == "timeout"
        d = info["outcome"]["final_goal_distance_m"]
        assert info["reward_terms"]["terminal"] == pytest.approx(-100 - 10 * d)
        # Standing still: every step pays the stall penalty (-10 per 5 ms, 20 steps per 0.1 s).
        assert all(s[4]["reward_terms"]["stall"] == pytest.approx(-200) for s in steps[2:])


def test_reaching_the_goal_terminates_with_the_success_bonus():
    with VbEnv(tasks=RIGID_TASK, **SMALL) as env:
        obs, info = env.reset(seed=0, options={"pair": 0})
        heading = STATE_NAMES.index("heading_error_rad")
        ret = 0.0
        for _ in range(700):
            steer = float(np.clip(obs["state"][heading], -1, 1))
            obs, reward, terminated, truncated, info = env.step(np.array([steer, 1.0], np.float32))
            ret += reward
            if terminated or truncated:
                break
        assert terminated and not truncated, info
        assert info["outcome"]["status"] == "success"
        assert info["reward_terms"]["terminal"] == 3000.0
        assert 15 < info["outcome"]["traversal_time_s"] < 60
        assert ret > 3000.0


def test_the_original_rules_reach_the_episode():
    """rules="verti_bench": success only within 8 m (3-D) of the marker 2 m above the goal, i.e.
    ~7.85 m planar on level ground, where vb's rules stop at 10 m."""
    ends = {}
    for rules in ("vb", "verti_bench"):
        with VbEnv(tasks=RIGID_TASK, rules=rules, **SMALL) as env:
            obs, info = env.reset(seed=0, options={"pair": 0})
            heading = STATE_NAMES.index("heading_error_rad")
            for _ in range(700):
                steer = float(np.clip(obs["state"][heading], -1, 1))
                obs, _, terminated, truncated, info = env.step(np.array([steer, 1.0], np.float32))
                if terminated or truncated:
                    break
            assert info["outcome"]["status"] == "success", info
            assert info["outcome"]["rules"] == rules   # the outcome names what decided it
            ends[rules] = info["outcome"]["final_goal_distance_m"]
    assert 9.9 < ends["vb"] <= 10.0
    assert ends["verti_bench"] < 8.0
    with pytest.raises(ConfigError, match="rules"):
        VbEnv(tasks=RIGID_TASK, rules="paper")


def test_bad_configuration_gives_clear_errors():
    with pytest.raises(ConfigError, match="unknown option.*colour"):
        VbEnv(tasks=RIGID_TASK, colour="red")
    with pytest.raises(ConfigError, match="control_period_s"):
        VbEnv(tasks=RIGID_TASK, control_period_s=0.012)
    with pytest.raises(ConfigError, match="does not exist"):
        VbEnv(tasks="no/such/task.yaml")
    with pytest.raises(ConfigError, match="layer 'lidar' unknown"):
        VbEnv(tasks=RIGID_TASK, crops=[Crop("lidar")])
    with pytest.raises(ConfigError, match="action"):
        VbEnv(tasks=RIGID_TASK, action="torque")
    with pytest.raises(VbGymError, match="unknown vehicle 'tank'"):
        VbEnv(tasks=RIGID_TASK, vehicle="tank")
    with pytest.raises(ValueError, match="pairs"):
        VbEnv(tasks=RIGID_TASK, pairs=[12])
    with VbEnv(tasks=RIGID_TASK, **SMALL) as env:
        env.reset(seed=0)
        with pytest.raises(ValueError, match="non-finite"):
            env.step(np.array([np.nan, 0.0]))
        with pytest.raises(ValueError, match="shape"):
            env.step(np.zeros(3))


def test_a_crashed_server_raises_with_its_exit_code():
    env = VbEnv(tasks=RIGID_TASK, **SMALL)
    env.reset(seed=0)
    os.kill(env.server_pid, signal.SIGKILL)
    with pytest.raises(ServerCrashed, match=r"exit code -9"):
        env.step(np.zeros(2, np.float32))
    env.close()
    env.close()   # a second close is harmless


def test_reward_terms_on_hand_made_situations():
    w = vb_gym.RewardWeights()
    step = vb_gym.reward.step_reward
    # 0.4 m closer to the local goal in 0.1 s (4 m/s): progress only.
    r, t = step(w, 0.1, (0.0, 0.0), (0.4, 0.0), (10.0, 0.0), 0.0, 0.0, "running", 50.0)
    assert t == {"progress": pytest.approx(20.0), "stall": 0.0, "tilt": 0.0, "terminal": 0.0}
    # 0.1 m in 0.1 s (1 m/s < 2 m/s): stall, -10 per 5 ms = -200 per 0.1 s.
    r, t = step(w, 0.1, (0.0, 0.0), (0.1, 0.0), (10.0, 0.0), 0.0, 0.0, "running", 50.0)
    assert t["stall"] == -200.0 and r == pytest.approx(5.0 - 200.0)
    # At 200 Hz the same stall costs -10 per step, as the original.
    _, t = step(w, 0.005, (0.0, 0.0), (0.0, 0.0), (10.0, 0.0), 0.0, 0.0, "running", 50.0)
    assert t["stall"] == -10.0
    # Roll 45 deg: -20 * (45/30) * (pi/12) per 5 ms step; pitch 20 deg: no penalty.
    _, t = step(w, 0.005, (0.0, 0.0), (0.05, 0.0), (10.0, 0.0), math.radians(45),
                math.radians(20), "running", 50.0)
    assert t["tilt"] == pytest.approx(-20 * 1.5 * math.pi / 12)
    # A replanned local goal is not progress: distances from both positions to the same point.
    _, t = step(w, 0.1, (0.0, 0.0), (0.0, 0.0), (0.0, 10.0), 0.0, 0.0, "running", 50.0)
    assert t["progress"] == 0.0
    assert step(w, 0.1, (0, 0), (1, 0), (9, 0), 0, 0, "success", 5.0)[1]["terminal"] == 3000
    assert step(w, 0.1, (0, 0), (1, 0), (9, 0), 0, 0, "stuck", 5.0)[1]["terminal"] == -300
    assert step(w, 0.1, (0, 0), (1, 0), (9, 0), 0, 0, "out_of_bounds", 5)[1]["terminal"] == -600
    assert step(w, 0.1, (0, 0), (1, 0), (9, 0), 0, 0, "timeout", 30.0)[1]["terminal"] == -400
    custom = vb_gym.RewardWeights(success=10.0, progress=1.0)
    assert step(custom, 0.1, (0, 0), (1, 0), (9, 0), 0, 0, "success", 5)[0] == pytest.approx(11)
    with pytest.raises(ValueError, match="unknown trial status"):
        step(w, 0.1, (0, 0), (1, 0), (9, 0), 0, 0, "exploded", 5.0)


def test_generated_training_worlds_and_deformable_soil(tmp_path):
    """Worlds from vb_gen seeds (outside the benchmark set) load as tasks; on a deformable one
    the wheels sink (the soil solver is live behind the gym)."""
    gen = vb_gym.GeneratedTasks(seeds=(7,), terrain="deformable", out_dir=str(tmp_path))
    with VbEnv(tasks=gen, crops=(Crop("semantics", 8, 1.0),)) as env:
        assert [t["name"] for t in env.tasks] == ["gen_mid_deformable_sparse_s7"]
        obs, info = env.reset(seed=0, options={"pair": 2})
        for _ in range(20):
            obs, *_ = env.step(np.array([0.0, 1.0], np.float32))
        assert obs["wheels"][:, 3].max() > 0.01          # sinkage (m)
        assert obs["semantics"].max() >= 7                # mud, sand or snow around
    assert (tmp_path / "tasks" / "gen_mid_deformable_sparse_s7.yaml").exists()


def test_perception_presets_reach_the_observation_and_stay_seeded():
    """A perception preset changes what the policy sees (not the physics), and the same seed
    still gives the same bits."""
    opts = dict(tasks=RIGID_TASK, crops=(Crop("elevation", 8, 0.5),))
    runs = {}
    for preset in ("none", "severe", "severe"):
        with VbEnv(perception=preset, **opts) as env:
            obs, _ = env.reset(seed=4)
            steps = [env.step(np.array([0.0, 0.5], np.float32))[0] for _ in range(5)]
            runs.setdefault(preset, []).append(np.concatenate(
                [o["elevation"].ravel() for o in [obs] + steps]))
    assert np.array_equal(runs["severe"][0], runs["severe"][1])
    assert not np.array_equal(runs["none"][0], runs["severe"][0])
    with pytest.raises(VbGymError, match="perception"):
        VbEnv(perception="blurry", **opts)
