"""Runnable examples (python -m vb_gym.examples.<name>)."""
