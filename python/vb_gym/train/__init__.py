"""Training of vb's learned baselines RL, MCL and ACL (optional extra: pip install -e "python[sb3]").

``python -m vb_gym.train rl|mcl|acl --timesteps N --seed S --out DIR`` (docs/learning.md)."""
