"""Makes hybrid_fixture.safetensors: fixed inputs of the hybrid baselines' networks and PyTorch's
outputs for the committed weights data/models/{wmvct,mppi6,tal,tnt}.safetensors, so the C++ test
(test/controllers/hybrid_models_test.cc) checks vb's inference against PyTorch without torch.
Rerun after retraining a model (needs the `train` extra):

    PYTHONPATH=python python test/data/hybrid/make_hybrid_fixture.py
"""
import pathlib

import numpy as np
import torch
from safetensors.torch import save_file

from vb_gym.examples.train_hybrid import ENSEMBLE, load_models, tal_step

root = pathlib.Path(__file__).resolve().parents[3]
_, m = load_models(str(root / "data" / "models"))
rng = np.random.default_rng(11)
n = 8


def shape():
    return rng.normal(0.0, 0.4, (n, 15)) * (np.arange(15) != 7)   # centre point 0


def angles():
    return rng.normal(0.0, 0.15, (n, 2))


T = lambda a: torch.as_tensor(a, dtype=torch.float32)   # noqa: E731
wmvct_in = T(np.column_stack([shape(), angles()]))
mppi6_in = T(np.column_stack([shape(), angles(), rng.uniform(-1, 1, n), rng.uniform(0.35, 0.6, n)]))
tal_ctx = T(np.column_stack([angles(), rng.uniform(0.35, 0.47, n), rng.uniform(-1, 1, n)]))
tal_shape = T(shape())
classes = rng.integers(0, 10, n)
tnt_in = T(np.column_stack([shape(), np.eye(10)[classes]]))
with torch.no_grad():
    out = {
        "wmvct.input": wmvct_in, "wmvct.output": m["wmvct"](wmvct_in),
        "mppi6.input": mppi6_in,
        "mppi6.output": torch.stack([m["mppi6"][i](mppi6_in) for i in range(ENSEMBLE)]).mean(0),
        "tal.input": torch.cat([tal_ctx, tal_shape], 1),
        "tal.output": tal_step(torch, m["tal"], tal_ctx, tal_shape),
        "tnt.input": tnt_in, "tnt.output": m["tnt"](tnt_in),
    }
save_file({k: v.contiguous() for k, v in out.items()},
          str(pathlib.Path(__file__).with_name("hybrid_fixture.safetensors")),
          metadata={"made_by": "test/data/hybrid/make_hybrid_fixture.py"})
print("wrote", {k: tuple(v.shape) for k, v in out.items()})
