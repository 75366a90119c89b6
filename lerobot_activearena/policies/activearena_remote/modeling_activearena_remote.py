"""A policy that lives in another process: each env of a batch has its own connection to the policy
server; when its queue is empty the env's head image, state and instruction go out under the keys of
the protocol's table (``OBSERVATION_KEYS``: openpi, ``VLA_EVAL_OBSERVATION_KEYS``: vla-eval), and the
first ``n_action_steps`` actions of the returned chunk are executed (one, when the server answers a
single action: vla-eval servers chunk on their side)."""

from __future__ import annotations

from collections import deque

import numpy as np
import torch
from lerobot.policies.pretrained import PreTrainedPolicy
from lerobot.utils.constants import OBS_STATE
from torch import Tensor, nn

from ...sim.action import ACTION_DIM
from .configuration_activearena_remote import IMAGE_KEY, ActiveArenaRemoteConfig
from .websocket_client import OpenPIClient, RemotePolicyError, VlaEvalClient

# What the server receives (openpi protocol) and what it must answer; docs/remote.md shows this table.
OBSERVATION_KEYS = {
    "observation/image": "uint8 (H, W, 3): the head camera, RGB, at the env's size (default 384 x 512)",
    "observation/state": "float32 (18,): left arm 7, left gripper, right arm 7, right gripper, torso yaw, "
    "head pitch (rad; grippers 0 = closed, 1 = open)",
    "prompt": "str: the episode's instruction",
    "activearena/step": "int: env steps since the episode began (0: a new episode, reset any memory)",
}
VLA_EVAL_OBSERVATION_KEYS = {
    "images": "{'head': uint8 (H, W, 3)}: the head camera, RGB, at the env's size",
    "state": "float32 (18,): as `observation/state`",
    "task_description": "str: the episode's instruction",
}
ANSWER_KEYS = {
    "actions": "float (18,) or (H, 18): absolute joint targets in the state's layout (a chunk of H >= 1)"
}


class ActiveArenaRemotePolicy(PreTrainedPolicy):
    config_class = ActiveArenaRemoteConfig
    name = "activearena_remote"

    def __init__(self, config: ActiveArenaRemoteConfig, **kwargs):
        super().__init__(config)
        config.validate_features()
        self.config = config
        self.register_buffer("_device_anchor", torch.zeros(1), persistent=False)
        self._unused = nn.Identity()
        self._clients: list[OpenPIClient | VlaEvalClient] = []
        self._episode_open: set[int] = set()  # vla-eval: envs whose server holds an open episode
        self.reset()

    def get_optim_params(self) -> list:
        return []

    def forward(self, batch: dict[str, Tensor]):
        raise NotImplementedError("activearena_remote is served by another process; train it there")

    def reset(self) -> None:
        """A new episode in every env: empty chunk queues, step counters at 0 (connections stay open)."""
        self._queues: list[deque] = []
        self._steps: list[int] = []

    def _client(self, b: int) -> OpenPIClient | VlaEvalClient:
        kind = OpenPIClient if self.config.protocol == "openpi" else VlaEvalClient
        while len(self._clients) <= b:
            self._clients.append(kind(self.config.url, self.config.connect_timeout_s, self.config.timeout_s))
        return self._clients[b]

    def observation(self, batch: dict[str, Tensor], b: int) -> dict:
        """Env ``b``'s observation in the server's keys (``OBSERVATION_KEYS``)."""
        image = batch[IMAGE_KEY][b]
        image = (image.float().clamp(0, 1) * 255).round().to(torch.uint8).permute(1, 2, 0)
        image = np.ascontiguousarray(image.cpu().numpy())
        state = batch[OBS_STATE][b].float().cpu().numpy()
        if self.config.protocol == "vla_eval":
            return {"images": {"head": image}, "state": state, "task_description": self._prompt(batch, b)}
        return {
            "observation/image": image,
            "observation/state": state,
            "prompt": self._prompt(batch, b),
            "activearena/step": self._steps[b],
        }

    @staticmethod
    def _prompt(batch: dict[str, Tensor], b: int) -> str:
        task = batch.get("task")
        return task[b] if isinstance(task, (list, tuple)) else ""

    def chunk(self, batch: dict[str, Tensor], b: int) -> np.ndarray:
        """Ask env ``b``'s server for a chunk; returns its first ``n_action_steps`` actions."""
        client = self._client(b)
        if self._steps[b] == 0 and isinstance(client, VlaEvalClient):
            if b in self._episode_open:
                client.end_episode()
            client.start_episode({"name": self._prompt(batch, b), "benchmark": "activearena"})
            self._episode_open.add(b)
        answer = client.infer(self.observation(batch, b))
        actions = np.asarray(answer.get("actions") if isinstance(answer, dict) else None)
        if actions.ndim == 1:
            actions = actions[None]
        if actions.ndim != 2 or actions.shape[1] != ACTION_DIM or len(actions) == 0:
            raise RemotePolicyError(
                f"the policy server at {self.config.url} answered {type(answer).__name__} with actions of shape "
                f"{actions.shape}; expected {{'actions': (H, {ACTION_DIM})}} (docs/remote.md)"
            )
        return actions[: self.config.n_action_steps]

    def _start(self, batch: dict[str, Tensor]) -> int:
        """The batch's env count; at an episode's first step, empty queues and step counters."""
        n = batch[IMAGE_KEY].shape[0]
        if not self._steps:
            self._queues, self._steps = [deque() for _ in range(n)], [0] * n
        return n

    @torch.no_grad()
    def predict_action_chunk(self, batch: dict[str, Tensor], **kwargs) -> Tensor:
        n = self._start(batch)
        return torch.stack([torch.from_numpy(self.chunk(batch, b)) for b in range(n)])

    @torch.no_grad()
    def select_action(self, batch: dict[str, Tensor], **kwargs) -> Tensor:
        n = self._start(batch)
        for b in range(n):
            if not self._queues[b]:
                self._queues[b].extend(torch.from_numpy(self.chunk(batch, b).copy()))
        action = torch.stack([q.popleft() for q in self._queues])
        self._steps = [t + 1 for t in self._steps]
        return action
