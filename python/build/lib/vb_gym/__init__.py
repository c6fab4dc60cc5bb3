"""vb_gym: gymnasium environments over vb's simulator process (docs/gym.md).

Pure Python (numpy, gymnasium): the physics runs in ``vb_gym`` processes (one per environment)
that speak the frame protocol of docs/gym_protocol.md.
"""

from gymnasium.envs.registration import register

from .config import ConfigError, Crop, EnvConfig, GeneratedTasks
from .env import VbEnv
from .protocol import ServerCrashed, ServerProcess, VbGymError
from .reward import RewardWeights
from .vector import VbVectorEnv

__all__ = [
    "ConfigError", "Crop", "EnvConfig", "GeneratedTasks", "RewardWeights", "ServerCrashed",
    "ServerProcess", "VbEnv", "VbGymError", "VbVectorEnv",
]
__version__ = "0.1.0"

# The episode ends by vb's rules (time limit included), so no TimeLimit wrapper.
register(
    id="vb/OffRoad-v0",
    entry_point="vb_gym.env:VbEnv",
    vector_entry_point="vb_gym.vector:VbVectorEnv",
)
