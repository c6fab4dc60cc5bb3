#!/usr/bin/env python3
"""Chrono runs of the simple set-ups behind vb's rugged-terrain "Known gaps" rows, with the
original's HMMWV: the slope protocol (gradeability) and flat soil (sinkage).

usage: chrono_setups.py slope --deg D [--mu 0.9] [--out FILE]
       chrono_setups.py soil --soil sand|mud|snow [--out FILE]
       (run through the harness environment: VB_REFERENCE_CACHE=... scripts/reference/chrono_setups.py ...)

The vehicle is built with the settings of the original's vehicles/HMMWV.py (HMMWV_Reduced, NSC,
primitive chassis collision, SIMPLE_MAP engine, AUTOMATIC_SIMPLE_MAP transmission, AWD with the
three differentials locked, rigid tires, 5 ms step, Bullet collision; our own code calling
Chrono's API). The protocols are reference_chrono_runs.md's:
- slope: a rigid plane tilted by D about y (uphill = +x), friction mu; the vehicle starts at rest
  on it facing uphill, brakes held 2 s, then full throttle, steering 0; climbed = 30 m up the
  slope within 30 s. Recorded every 0.5 s: distance up the slope, speed, yaw, gear, engine
  speed and the four wheels' normal loads (which side carries the load: vb's explanation of the
  original's lower limit is the drive torque that its powertrain leaves unreacted on the chassis,
  docs/validation.md).
- soil: a flat 40 m x 10 m SCM patch at 0.1 m with the original's parameters and bulldozing;
  2 s of settling, then the P speed controller (gain 1, 4 m/s) for 10 s straight. Sinkage =
  tire radius - spindle height above the undeformed surface, mean of the four wheels.
"""
import argparse
import json
import math
import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
STEP_S = 5e-3
TIRE_RADIUS_M = 0.467
SOILS = {  # the original's envs/terrain.py SCMParameters (reference_verti_bench.md §3)
    "snow": (0.2e6, 0, 1.1, 0, 30, 0.01, 4e7, 3e4),
    "mud": (2e6, 0, 1.1, 0, 30, 0.01, 2e8, 3e4),
    "sand": (5301e3, 102e3, 0.793, 1.3e3, 31.1, 1.2e-2, 4e8, 3e4),
}


def make_vehicle(chrono, veh, system, pose):
    v = veh.HMMWV_Reduced(system)
    v.SetContactMethod(chrono.ChContactMethod_NSC)
    v.SetChassisCollisionType(veh.CollisionType_PRIMITIVES)
    v.SetChassisFixed(False)
    v.SetEngineType(veh.EngineModelType_SIMPLE_MAP)
    v.SetTransmissionType(veh.TransmissionModelType_AUTOMATIC_SIMPLE_MAP)
    v.SetDriveType(veh.DrivelineTypeWV_AWD)
    v.SetTireType(veh.TireModelType_RIGID)
    v.SetTireStepSize(STEP_S)
    v.SetInitFwdVel(0.0)
    v.SetInitPosition(pose)
    v.Initialize()
    v.LockAxleDifferential(0, True)
    v.LockAxleDifferential(1, True)
    v.LockCentralDifferential(0, True)
    v.GetVehicle().EnableRealtime(False)
    return v


def make_system(chrono):
    system = chrono.ChSystemNSC()
    system.SetGravitationalAcceleration(chrono.ChVector3d(0, 0, -9.81))
    system.SetCollisionSystemType(chrono.ChCollisionSystem.Type_BULLET)
    system.SetNumThreads(min(8, os.cpu_count()), min(8, os.cpu_count()), 1)
    return system


def step(system, terrain, v, driver_inputs, t):
    terrain.Synchronize(t)
    v.Synchronize(t, driver_inputs, terrain)
    terrain.Advance(STEP_S)
    v.Advance(STEP_S)
    system.DoStepDynamics(STEP_S)


def wheels(v):
    return [axle.m_wheels[side] for axle in v.GetVehicle().GetAxles() for side in (0, 1)]


def slope(args, chrono, veh):
    system = make_system(chrono)
    theta = math.radians(args.deg)
    rot = chrono.QuatFromAngleY(-theta)  # +x rises
    terrain = veh.RigidTerrain(system)
    mat = chrono.ChContactMaterialNSC()
    mat.SetFriction(args.mu)
    mat.SetRestitution(0.01)
    terrain.AddPatch(mat, chrono.ChCoordsysd(chrono.ChVector3d(0, 0, 0), rot), 200, 40)
    terrain.Initialize()
    normal = (-math.sin(theta), 0.0, math.cos(theta))  # the plane's normal
    start = chrono.ChVector3d(-60 * math.cos(theta), 0, -60 * math.sin(theta))
    lift = TIRE_RADIUS_M + 0.05
    start = chrono.ChVector3d(start.x + lift * normal[0], 0, start.z + lift * normal[2])
    v = make_vehicle(chrono, veh, system, chrono.ChCoordsysd(start, rot))
    driver = veh.ChDriver(v.GetVehicle())
    inputs = driver.GetInputs()
    up = (math.cos(theta), 0.0, math.sin(theta))
    p0 = v.GetVehicle().GetPos()
    samples, climbed_s, best = [], None, 0.0
    t, k = 0.0, 0
    while t < 32.0:
        t = system.GetChTime()
        braking = t < 2.0
        inputs.m_throttle, inputs.m_braking, inputs.m_steering = (0.0, 1.0, 0.0) if braking else (1.0, 0.0, 0.0)
        p = v.GetVehicle().GetPos()
        d = (p.x - p0.x) * up[0] + (p.z - p0.z) * up[2]
        best = max(best, d)
        if climbed_s is None and d >= 30.0:
            climbed_s = t - 2.0
            break
        if k % 100 == 0:
            loads = []
            for w in wheels(v):
                f = w.GetSpindle().GetContactForce()
                loads.append(round(f.x * normal[0] + f.z * normal[2], 1))
            veh_ = v.GetVehicle()
            samples.append({"t_s": round(t, 3), "up_m": round(d, 3), "speed_mps": round(veh_.GetSpeed(), 3),
                            "yaw_deg": round(math.degrees(veh_.GetRot().GetCardanAnglesXYZ().z), 2),
                            "roll_deg": round(math.degrees(veh_.GetRot().GetCardanAnglesXYZ().x), 2),
                            "gear": veh_.GetTransmission().GetCurrentGear(),
                            "engine_radps": round(veh_.GetEngine().GetMotorSpeed(), 2),
                            "normal_loads_N_fl_fr_rl_rr": loads})
        step(system, terrain, v, inputs, t)
        k += 1
    return {"setup": "slope", "deg": args.deg, "mu": args.mu, "climbed_30m_s": climbed_s,
            "max_up_m": round(best, 3), "samples": samples}


def soil(args, chrono, veh):
    system = make_system(chrono)
    terrain = veh.SCMTerrain(system)
    terrain.SetSoilParameters(*SOILS[args.soil])
    terrain.EnableBulldozing(True)
    terrain.SetBulldozingParameters(55, 1, 5, 10)
    terrain.SetPlotType(veh.SCMTerrain.PLOT_NONE, 0, 1)
    terrain.Initialize(40.0, 10.0, 0.1)
    pose = chrono.ChCoordsysd(chrono.ChVector3d(-15, 0, TIRE_RADIUS_M + 0.1), chrono.QUNIT)
    v = make_vehicle(chrono, veh, system, pose)
    for w in wheels(v):
        terrain.AddMovingPatch(w.GetSpindle(), chrono.VNULL, chrono.ChVector3d(1.0, 0.6, 1.0))
    driver = veh.ChDriver(v.GetVehicle())
    inputs = driver.GetInputs()
    speed = veh.ChSpeedController()
    speed.Reset(v.GetRefFrame())
    speed.SetGains(1, 0, 0)
    static, driving, speeds = [], [], []
    while system.GetChTime() < 12.0:
        t = system.GetChTime()
        if t < 2.0:
            inputs.m_throttle, inputs.m_braking = 0.0, 1.0
        else:
            u = max(-1.0, min(1.0, speed.Advance(v.GetRefFrame(), 4.0, t, STEP_S)))
            inputs.m_throttle, inputs.m_braking = (u, 0.0) if u > 0 else (0.0, -u)
        inputs.m_steering = 0.0
        sink = sum(TIRE_RADIUS_M - w.GetSpindle().GetPos().z for w in wheels(v)) / 4.0
        if 1.5 <= t < 2.0:
            static.append(sink)
        if t >= 7.0:
            driving.append(sink)
            speeds.append(v.GetVehicle().GetSpeed())
        step(system, terrain, v, inputs, t)
    mean = lambda xs: round(sum(xs) / len(xs), 4)
    return {"setup": "soil", "soil": args.soil, "static_sinkage_m": mean(static),
            "driving_sinkage_m": mean(driving), "speed_mps": mean(speeds)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("setup", choices=["slope", "soil"])
    ap.add_argument("--deg", type=float, default=30.0)
    ap.add_argument("--mu", type=float, default=0.9)
    ap.add_argument("--soil", choices=sorted(SOILS), default="sand")
    ap.add_argument("--out")
    ap.add_argument("--cache", type=Path, default=None)
    args = ap.parse_args()
    sys.path.insert(0, str(HERE))
    import run_original

    cache = (args.cache or run_original.default_cache()).resolve()
    run_original.enter_harness_env(cache, Path(__file__))
    import original_env

    original_env.enter(cache)
    import pychrono as chrono
    import pychrono.vehicle as veh

    veh.SetDataPath(str(cache / "chrono-data/vehicle") + "/")
    result = slope(args, chrono, veh) if args.setup == "slope" else soil(args, chrono, veh)
    text = json.dumps(result, indent=1)
    if args.out:
        Path(args.out).write_text(text + "\n")
    print(text if args.setup == "soil" else json.dumps({k: v for k, v in result.items() if k != "samples"}))


if __name__ == "__main__":
    main()
