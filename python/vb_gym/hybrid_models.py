"""The learned models of the hybrid baselines (docs/learning.md "Hybrid kinodynamic models"), in
PyTorch (the `train` extra), sized for a CPU planner that evaluates them 12,000-16,000 times per
update. Inputs use the terrain grid of vb_gym.hybrid_features (15 heights relative to the centre
point, forward-major); angles in radians, lengths in metres.

| model | input | output |
|---|---|---|
| WMVCT  `wmvct.net`  | shape at the next pose (15), roll, pitch (2) | z - centre height, roll, pitch at the next pose |
| MPPI-6 `mppi6.m{i}` | shape at the next pose (15), roll, pitch, steering, step length (4) | roll, pitch at the next pose (5 members, averaged) |
| TAL    `tal.query`, `tal.head` | context (roll, pitch, step length, steering) and shape at the pose | body dx, dy, dyaw, world dz; roll, pitch at the next pose |
| TNT    `tnt.trav` | shape (15), surface class one-hot (10) | logit of the traversability (progress ratio x (1 - wheel slip)) |

TAL's terrain attention: softmax weights over the 15 grid points from the motion context
(`tal.query`), the head reads the context and the 15 heights times their weights (x 15).

Every network is an nn.Sequential of Linear and ReLU layers; the input/output normalisation is
folded into the first and last Linear layer on export, so the C++ side (vb::nn::Mlp) evaluates the
exported layers on raw inputs and gets raw outputs.
"""

from __future__ import annotations

import torch
from torch import nn

from vb_gym.hybrid_features import GRID_POINTS, NUM_CLASSES


def mlp(sizes: list[int]) -> nn.Sequential:
    layers: list[nn.Module] = []
    for i in range(len(sizes) - 1):
        layers.append(nn.Linear(sizes[i], sizes[i + 1]))
        if i < len(sizes) - 2:
            layers.append(nn.ReLU())
    return nn.Sequential(*layers)


class Normalised(nn.Module):
    """y = out_std * net((x - in_mean) / in_std) + out_mean; fold() bakes the affine maps into
    the first and last Linear layer (returns a plain nn.Sequential)."""

    def __init__(self, net: nn.Sequential, in_mean, in_std, out_mean, out_std):
        super().__init__()
        self.net = net
        for name, v in (("in_mean", in_mean), ("in_std", in_std), ("out_mean", out_mean),
                        ("out_std", out_std)):
            self.register_buffer(name, torch.as_tensor(v, dtype=torch.float32))

    def forward(self, x):
        return self.net((x - self.in_mean) / self.in_std) * self.out_std + self.out_mean

    def normalised_forward(self, x):
        return self.net((x - self.in_mean) / self.in_std)

    def fold(self) -> nn.Sequential:
        import copy
        net = copy.deepcopy(self.net)
        first, last = net[0], net[len(net) - 1]
        with torch.no_grad():
            w = first.weight / self.in_std[None, :]
            first.bias.copy_(first.bias - (w * self.in_mean[None, :]).sum(1))
            first.weight.copy_(w)
            last.weight.copy_(last.weight * self.out_std[:, None])
            last.bias.copy_(last.bias * self.out_std + self.out_mean)
        return net


class Tal(nn.Module):
    """Terrain-attentive learned 6-DoF step (see the module doc)."""

    CONTEXT = 4
    OUTPUTS = 6

    def __init__(self, query: Normalised, head: Normalised):
        super().__init__()
        self.query = query
        self.head = head

    @staticmethod
    def create(stats: dict) -> "Tal":
        q = Normalised(mlp([Tal.CONTEXT, 16, GRID_POINTS]), stats["ctx_mean"], stats["ctx_std"],
                       torch.zeros(GRID_POINTS), torch.ones(GRID_POINTS))
        h_mean = torch.cat([torch.as_tensor(stats["ctx_mean"]), torch.zeros(GRID_POINTS)])
        h_std = torch.cat([torch.as_tensor(stats["ctx_std"]),
                           torch.full((GRID_POINTS,), float(stats["shape_std"]))])
        h = Normalised(mlp([Tal.CONTEXT + GRID_POINTS, 48, 48, Tal.OUTPUTS]), h_mean, h_std,
                       stats["out_mean"], stats["out_std"])
        return Tal(q, h)

    def attention(self, ctx):
        return torch.softmax(self.query(ctx), dim=-1)

    def _head_input(self, ctx, shape):
        return torch.cat([ctx, GRID_POINTS * self.attention(ctx) * shape], dim=-1)

    def forward(self, ctx, shape):
        return self.head(self._head_input(ctx, shape))

    def normalised_forward(self, ctx, shape):
        return self.head.normalised_forward(self._head_input(ctx, shape))


def one_hot(classes, n: int = NUM_CLASSES):
    c = torch.as_tensor(classes, dtype=torch.long).clamp(0, n - 1)
    return torch.nn.functional.one_hot(c, n).float()


def export_tensors(prefix: str, seq: nn.Sequential) -> dict:
    """{prefix}.{i}.weight / .bias of every Linear of a Sequential (PyTorch [out, in] layout)."""
    out = {}
    for i, layer in enumerate(seq):
        if isinstance(layer, nn.Linear):
            out[f"{prefix}.{i}.weight"] = layer.weight.detach().float().contiguous().clone()
            out[f"{prefix}.{i}.bias"] = layer.bias.detach().float().contiguous().clone()
    return out
