"""Makes mlp_fixture.safetensors: a small PyTorch MLP (every activation vb::nn::Mlp supports),
fixed inputs and PyTorch's outputs, so the C++ test (test/nn/mlp_test.cc) checks vb's forward
pass against PyTorch without needing torch. Needs torch and safetensors (the `sb3` extra):

    python test/data/nn/make_mlp_fixture.py
"""
import pathlib

import torch
from safetensors.torch import save_file

torch.manual_seed(7)
torch.set_num_threads(1)
activations = ["relu", "tanh", "elu", "sigmoid", "softplus", "none"]
modules = {"relu": torch.nn.ReLU, "tanh": torch.nn.Tanh, "elu": torch.nn.ELU,
           "sigmoid": torch.nn.Sigmoid, "softplus": torch.nn.Softplus}
widths = [11, 32, 24, 16, 16, 8, 3]
layers = []
for k, act in enumerate(activations):
    layers.append(torch.nn.Linear(widths[k], widths[k + 1]))
    if act != "none":
        layers.append(modules[act]())
net = torch.nn.Sequential(*layers)
# Scale the inputs so every activation sees both signs and large values (softplus threshold).
inputs = torch.randn(5, widths[0]) * 3.0
with torch.no_grad():
    outputs = net(inputs)
tensors = {f"net.{name}": p.detach().contiguous() for name, p in net.named_parameters()}
tensors["inputs"] = inputs.contiguous()
tensors["outputs"] = outputs.contiguous()
out = pathlib.Path(__file__).with_name("mlp_fixture.safetensors")
save_file(tensors, str(out), metadata={"activations": ",".join(activations),
                                       "torch": torch.__version__})
print(out, {k: tuple(v.shape) for k, v in tensors.items()})
