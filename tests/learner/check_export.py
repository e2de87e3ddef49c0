# Copyright 2026 The DCS Authors.
"""Checks an exported policy (`dcs export`) against DCS's own outputs, in plain PyTorch.

Usage: /usr/bin/python3 check_export.py POLICY_PT CASE_DIR

Builds modules with Stable-Baselines3's layout (an MlpPolicy, or a MultiInputPolicy with its
CombinedExtractor shared by actor and critic) from the layout JSON beside POLICY_PT, loads the
state dict with load_state_dict(strict=True), and compares on CASE_DIR's observations:
  inputs.f32   [N, flat inputs] float32: the state then the context (image policies: the context)
  images.u8    [N, H, W, C] uint8, channel last (image policies only)
  actions.f32  [N, action size] float32: DCS's deterministic actions (actor::PolicyNetwork)
  values.f32   [N] float32: DCS's value estimates (the learner's forward pass)
Exits 0 if they agree, 1 (saying where) if not, 2 if PyTorch is missing.
"""

import json
import os
import sys

try:
    import numpy as np
    import torch
    from torch import nn
except ImportError as error:
    print(f"check_export.py needs PyTorch and NumPy for /usr/bin/python3: install Debian's "
          f"python3-torch (scripts/bootstrap does). {error}")
    sys.exit(2)

# Tolerance of the values and the Gaussian's mean, relative to max(1, |x|): float32 computed
# in two orders (DCS's Eigen products, torch's BLAS and convolutions) over dot products of up to
# 4,096 terms differs by a few ulps of the result. An absolute 1e-6 would be 2 ulps at |x| = 4
# (CarRacing's values after a few updates are near 5 and differ by up to 6 ulps, 2.9e-6), so
# relative; 1e-6 still fails on a single conv weight moved by 1e-3 (3.7e-6).
TOLERANCE = 1e-6
# Logits this close are a tie in float32: either argmax is DCS's deterministic action.
TIE = 1e-5


def mlp(widths, inputs, activation):
    """An nn.Sequential of Linear layers, each followed by `activation`, as SB3 builds them."""
    layers = []
    for width in widths:
        layers += [nn.Linear(inputs, width), activation()]
        inputs = width
    return nn.Sequential(*layers), inputs


class NatureCnn(nn.Module):
    """SB3's NatureCNN on a [B, C, H, W] float image in [0, 1]."""

    def __init__(self, height, width, channels, features):
        super().__init__()
        self.cnn = nn.Sequential(
            nn.Conv2d(channels, 32, kernel_size=8, stride=4), nn.ReLU(),
            nn.Conv2d(32, 64, kernel_size=4, stride=2), nn.ReLU(),
            nn.Conv2d(64, 64, kernel_size=3, stride=1), nn.ReLU(),
            nn.Flatten())
        with torch.no_grad():
            flattened = self.cnn(torch.zeros(1, channels, height, width)).shape[1]
        self.linear = nn.Sequential(nn.Linear(flattened, features), nn.ReLU())

    def forward(self, image):
        return self.linear(self.cnn(image))


class CombinedExtractor(nn.Module):
    """SB3's CombinedExtractor on the layout's Dict observation; the context through DCS's
    branch (network.context_layers, ReLU) if the run has one, else only flattened."""

    def __init__(self, layout):
        super().__init__()
        image = layout["observation"]["image"]
        height, width, channels = image["shape"]
        features = layout["network"]["cnn_features"]
        extractors = {image["key"]: NatureCnn(height, width, channels, features)}
        self.features_dim = features
        context = layout["context"]
        if context["key"]:
            branch, outputs = mlp(layout["network"]["context_layers"],
                                  len(context["features"]), nn.ReLU)
            extractors[context["key"]] = branch if len(branch) > 0 else nn.Flatten()
            self.features_dim += outputs
        self.order = layout["observation"]["input_order"]
        assert self.order == sorted(self.order), "gymnasium's Dict sorts its keys"
        self.extractors = nn.ModuleDict(extractors)

    def forward(self, observations):
        return torch.cat([self.extractors[key](observations[key]) for key in self.order], dim=1)


class Sb3Policy(nn.Module):
    """SB3's ActorCriticPolicy with its default separate pi and vf MLPs (tanh)."""

    def __init__(self, layout):
        super().__init__()
        observation = layout["observation"]
        if "image" in observation:
            self.features_extractor = CombinedExtractor(layout)
            # share_features_extractor=True: one module under three names, as in SB3.
            self.pi_features_extractor = self.features_extractor
            self.vf_features_extractor = self.features_extractor
            features = self.features_extractor.features_dim
        else:
            self.features_extractor = nn.Flatten()
            features = observation["state_size"] + len(layout["context"]["features"])
        network = layout["network"]
        self.mlp_extractor = nn.Module()
        self.mlp_extractor.policy_net, pi = mlp(network["pi_layers"], features, nn.Tanh)
        self.mlp_extractor.value_net, vf = mlp(network["vf_layers"], features, nn.Tanh)
        action = layout["action"]
        self.discrete = action["type"] == "discrete"
        self.action_net = nn.Linear(pi, action["n"] if self.discrete else len(action["low"]))
        if not self.discrete:
            self.log_std = nn.Parameter(torch.zeros(len(action["low"])))
        self.value_net = nn.Linear(vf, 1)

    def forward(self, observations):
        """The action head's outputs (logits or the Gaussian's mean) and the values."""
        features = self.features_extractor(observations)
        head = self.action_net(self.mlp_extractor.policy_net(features))
        values = self.value_net(self.mlp_extractor.value_net(features)).flatten()
        return head, values


def observations_of(layout, case_dir, count):
    """The policy's input: a tensor (MlpPolicy) or a dict of tensors (MultiInputPolicy)."""
    inputs = torch.from_numpy(np.fromfile(os.path.join(case_dir, "inputs.f32"), np.float32))
    inputs = inputs.reshape(count, -1)
    image = layout["observation"].get("image")
    if image is None:
        return inputs
    pixels = np.fromfile(os.path.join(case_dir, "images.u8"), np.uint8)
    pixels = torch.from_numpy(pixels).reshape(count, *image["shape"])
    observations = {image["key"]: pixels.permute(0, 3, 1, 2).float() / 255.0}
    if layout["context"]["key"]:
        observations[layout["context"]["key"]] = inputs
    return observations


def main(policy_path, case_dir):
    torch.set_num_threads(1)
    with open(os.path.splitext(policy_path)[0] + ".json") as file:
        layout = json.load(file)
    policy = Sb3Policy(layout)
    policy.load_state_dict(torch.load(policy_path), strict=True)

    values = torch.from_numpy(np.fromfile(os.path.join(case_dir, "values.f32"), np.float32))
    count = values.shape[0]
    actions = np.fromfile(os.path.join(case_dir, "actions.f32"), np.float32).reshape(count, -1)
    with torch.no_grad():
        head, torch_values = policy(observations_of(layout, case_dir, count))
    failures = []
    value_error = (torch_values - values).abs() / values.abs().clamp(min=1)
    if value_error.max() > TOLERANCE:
        i = int(value_error.argmax())
        failures.append(f"value of observation {i}: torch {torch_values[i]:.9g}, "
                        f"DCS {values[i]:.9g} (relative error {value_error[i]:.3g})")
    if policy.discrete:
        chosen = head.argmax(dim=1).numpy()
        top2 = head.topk(2, dim=1).values
        tie = (top2[:, 0] - top2[:, 1]).numpy() < TIE
        wrong = np.nonzero((chosen != actions[:, 0].astype(np.int64)) & ~tie)[0]
        if len(wrong) > 0:
            failures.append(f"{len(wrong)} of {count} actions differ, first observation "
                            f"{wrong[0]}: torch {chosen[wrong[0]]}, DCS {actions[wrong[0], 0]:g}")
        if len(np.unique(chosen)) < 2:
            failures.append("every observation gets the same action: the check shows nothing")
    else:
        mean_error = (head - torch.from_numpy(actions)).abs() / head.abs().clamp(min=1)
        if mean_error.max() > TOLERANCE:
            i, j = np.unravel_index(int(mean_error.argmax()), mean_error.shape)
            failures.append(f"mean of observation {i}, action {j}: torch {head[i, j]:.9g}, "
                            f"DCS {actions[i, j]:.9g}")
    for failure in failures:
        print(failure)
    print(f"{policy_path}: {count} observations, {'FAILED' if failures else 'agree'} "
          f"(largest value error {value_error.max():.3g})")
    return 1 if failures else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2]))
