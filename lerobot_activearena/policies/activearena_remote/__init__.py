"""`activearena_remote`: a policy served by another process (openpi's websocket protocol), scored
by activearena-eval and lerobot-eval like any LeRobot policy."""

from .configuration_activearena_remote import ActiveArenaRemoteConfig

__all__ = ["ActiveArenaRemoteConfig"]
