"""The one place where the harness sets up the process the original's code runs in.

`enter(cache)` must be called before anything imports the original's modules. It does only what
cannot be had here, and nothing that changes what the original computes:
- `pychrono.irrlicht` and `pychrono.sensor` (not built: no Irrlicht, no GPU sensors) become inert
  stand-in modules: the original imports them at module level and uses them only for rendering
  and cameras, which the harness switches off (`render: False`). Any attribute read fails loudly.
- The ROS message packages the original MPPI imports at module level become stand-ins whose
  messages are empty attribute bags: its `MapProcessor` ("only for crawler") builds a few in its
  constructor and never reads them in a simulation.
- torch's `.cuda()` (the original MPPI calls it unconditionally) returns the tensor/module on the
  CPU: the computation is the same, on another device.
- CHRONO_DATA_DIR points at the cache's chrono-data/ (prepare_original.sh).
- Python's, numpy's and torch's generators are seeded (the original never seeds them; only the
  original MPPI draws random numbers during a trial), so a rerun is the same trial.
"""
import os
import random
import sys
import types
from pathlib import Path


class _Inert(types.ModuleType):
    """A module that exists but refuses to be used."""

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        raise RuntimeError(f"vb reference harness: {self.__name__}.{name} is a stand-in "
                           "(not available without Irrlicht/ROS); the trial must not use it")


def _stand_in(name):
    module = _Inert(name)
    sys.modules[name] = module
    return module


def enter(cache: Path, seed: int = 0) -> None:
    cache = Path(cache)
    sys.path.insert(0, str(cache / "original"))
    os.environ["CHRONO_DATA_DIR"] = str(cache / "chrono-data") + "/"
    import pychrono

    for sub in ("irrlicht", "sensor"):
        setattr(pychrono, sub, _stand_in(f"pychrono.{sub}"))
    ros = {"grid_map_msgs.msg": ["GridMap"], "std_msgs.msg": ["Header"],
           "nav_msgs.msg": ["Odometry"],
           "geometry_msgs.msg": ["PoseStamped", "Twist", "Pose", "Point", "Quaternion"]}
    for name, classes in ros.items():
        package = sys.modules.get(name.split(".")[0]) or _stand_in(name.split(".")[0])
        msg = types.ModuleType(name)
        for cls in classes:
            setattr(msg, cls, type(cls, (_Message,), {}))
        sys.modules[name] = msg
        types.ModuleType.__setattr__(package, "msg", msg)

    import numpy as np
    import torch

    torch.Tensor.cuda = lambda self, *a, **k: self
    torch.nn.Module.cuda = lambda self, *a, **k: self
    torch.set_num_threads(1)
    random.seed(seed)
    np.random.seed(seed)
    torch.manual_seed(seed)


class _Message:
    """A ROS message stand-in: every field is another empty message."""

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        value = _Message()
        setattr(self, name, value)
        return value
