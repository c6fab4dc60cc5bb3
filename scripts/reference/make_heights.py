"""Remakes the original's high-resolution height map `height{N}_{level}.npy` as its
`envs/preHeight-VertiBench.py` makes it (the original's files are Git LFS objects, absent).

preHeight (reference_verti_bench.md §2.4, §4.2): a fresh NSC system with Bullet collision and no
vehicle; one RigidTerrain with one height-map patch of the whole world image, centred at the
origin, **129 m** square (its half size is 65, not the benchmark's 64.5: the map is offset from the
simulated 128 m terrain by up to 0.5 m at the rim, quirk 1), heights 0 .. 16 m x {0.3, 0.6, 1.0} by
level, friction 0.9, restitution 0.01; one 5 ms step, one Synchronize/Advance of the terrain; then
`GetHeight` at z = max height over x, y = linspace(-64.5, 64.5, 1291) (rounded to 6 decimals),
stored as [iy, ix] with iy along ascending y. The runtime (`TerrainManager._load_high_res_data`)
flips it to the image convention itself.

Called by run_original.py before a trial when the world's file is missing (~10-20 s per world).
"""
import glob
import os

HALF_SIZE_M = 65.0  # preHeight's m_terrain_length / m_terrain_width
SAMPLES = 1291
STEP_S = 5e-3
LEVEL_SCALE = {"low": 0.3, "mid": 0.6, "high": 1.0}  # preHeight's GeometryDiff


def maps_dir(cache):
    return os.path.join(str(cache), "original/verti_bench/envs/data/BenchMaps/sampled_maps")


def config_path(cache, world):
    found = glob.glob(os.path.join(maps_dir(cache), "Configs/Final", f"config{world}_*.yaml"))
    if len(found) != 1:
        raise SystemExit(f"make_heights: world {world}: expected one config{world}_LEVEL.yaml in "
                         f"{maps_dir(cache)}/Configs/Final, found {len(found)}")
    return found[0]


def height_path(cache, world):
    level = config_path(cache, world).rsplit("_", 1)[1][:-len(".yaml")]
    return os.path.join(maps_dir(cache), "Configs/Final", f"height{world}_{level}.npy"), level


def make_height_map(cache, world):
    """Writes the world's height file if it is missing; returns its path."""
    path, level = height_path(cache, world)
    if os.path.exists(path):
        return path
    import numpy as np
    import pychrono as chrono
    import pychrono.vehicle as veh
    import yaml

    if level not in LEVEL_SCALE:
        raise SystemExit(f"make_heights: {config_path(cache, world)}: unknown level '{level}'")
    h_min, h_max = 0.0, 16.0 * LEVEL_SCALE[level]
    with open(config_path(cache, world)) as f:
        terrain = yaml.safe_load(f)["terrain"]
    if abs(terrain["min_height"] - h_min) > 1e-9 or abs(terrain["max_height"] - h_max) > 1e-9:
        raise SystemExit(f"make_heights: {config_path(cache, world)}: heights "
                         f"[{terrain['min_height']}, {terrain['max_height']}] are not the level's "
                         f"[{h_min}, {h_max}]")
    system = chrono.ChSystemNSC()
    system.SetGravitationalAcceleration(chrono.ChVector3d(0, 0, -9.81))
    system.SetCollisionSystemType(chrono.ChCollisionSystem.Type_BULLET)
    ground = veh.RigidTerrain(system)
    material = chrono.ChContactMaterialNSC()
    material.SetFriction(0.9)
    material.SetRestitution(0.01)
    image = os.path.join(maps_dir(cache), "Worlds", f"{world}.bmp")
    ground.AddPatch(material, chrono.ChCoordsysd(chrono.ChVector3d(0, 0, 0), chrono.CSYSNORM.rot),
                    image, HALF_SIZE_M * 2 - 1, HALF_SIZE_M * 2 - 1, h_min, h_max)
    ground.Initialize()
    system.DoStepDynamics(STEP_S)
    ground.Synchronize(STEP_S)
    ground.Advance(STEP_S)
    xs = np.round(np.linspace(-HALF_SIZE_M + 0.5, HALF_SIZE_M - 0.5, SAMPLES), 6)
    ys = np.round(np.linspace(-HALF_SIZE_M + 0.5, HALF_SIZE_M - 0.5, SAMPLES), 6)
    heights = np.empty((SAMPLES, SAMPLES), dtype=np.float64)
    for iy, y in enumerate(ys):
        for ix, x in enumerate(xs):
            heights[iy, ix] = ground.GetHeight(chrono.ChVector3d(x, y, h_max))
    tmp = os.path.join(os.path.dirname(path), "." + os.path.basename(path) + ".tmp.npy")
    np.save(tmp, heights)  # hidden: the runtime's glob height{N}_*.npy must not see it
    os.replace(tmp, path)
    return path
