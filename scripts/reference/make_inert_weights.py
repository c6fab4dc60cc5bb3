#!/usr/bin/env python3
"""Writes stand-ins for the three files the original MPPI loads in its constructor.

usage: make_inert_weights.py ORIGINAL_DIR     (the directory that holds verti_bench/)

The original's `systems/MPPI/MPPI.py` loads a TAL motion model (`TAL_13_14_14.torch`), a
traversability network (`best_traversability_model.pth`) and input scales (`stats_rock.pickle`).
The two networks are Git LFS objects that are not available. MPPI computes their outputs
(`map_embedding`, `trav_map_combined`) but its rollouts (the kinematic `ackermann_model`) and its
cost (goal distance, obstacle map, control) never read them; only TNT does
(reference_verti_bench.md §7.3). So seeded random weights of the right shapes are inert for MPPI:
they let the unmodified constructor run. Do not use them for TAL or TNT.

The scales are not weights: MPPI divides its state by them. They are the original file's values
as reference_verti_bench.md §7.3 records them.
Idempotent: existing files are kept.
"""
import pickle
import sys
from pathlib import Path

POSE_DOT_SCALE = [0.058334508, 0.497480703, 0.064863111]  # xyz, roll/pitch, yaw
MAP_OFFSET_SCALE = [0.186972976, 1.0]


def main() -> None:
    if len(sys.argv) != 2:
        sys.exit("usage: make_inert_weights.py ORIGINAL_DIR")
    root = Path(sys.argv[1]).resolve()
    mppi = root / "verti_bench/systems/MPPI"
    if not mppi.is_dir():
        sys.exit(f"make_inert_weights: {mppi}: no such directory")
    stats = mppi / "stats_rock.pickle"
    if not stats.exists():
        with open(stats, "wb") as f:
            pickle.dump({"pose_dot": POSE_DOT_SCALE, "map_offset": MAP_OFFSET_SCALE}, f)
    tal_file = mppi / "TAL_13_14_14.torch"
    trav_file = mppi / "best_traversability_model.pth"
    if tal_file.exists() and trav_file.exists():
        return
    sys.path.insert(0, str(root))
    import torch
    from verti_bench.systems.MPPI.models import TAL, ElevMapEncDec, PatchDecoder
    from verti_bench.systems.MPPI.traversabilityEstimator import TravEstimator

    torch.manual_seed(0)
    encoder = ElevMapEncDec()  # built as MPPIPlanner.__init__ builds it
    tal = TAL(encoder.map_encode, PatchDecoder(encoder.map_encode))
    torch.save(tal, tal_file)  # the original loads the whole module (weights_only=False)
    torch.save(TravEstimator(output_dim=(320, 260)).state_dict(), trav_file)
    print(f"make_inert_weights: wrote seeded stand-ins {tal_file.name}, {trav_file.name} into {mppi}")


if __name__ == "__main__":
    main()
