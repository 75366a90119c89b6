"""ActiveArena-Plan: the planner (``activearena_planner``: Qwen3-VL over the stride-16 frames, no state,
trained on its text target only) and the OFT executor (``activearena_plan``) with the run-time loop the
release does not publish. At every chunk (a multiple of 16 steps) the planner reads the last <= 13
stride frames; its retrievals join the env's persistent, de-duplicated ``MemoryBank``; the executor
acts from the bank's frames (each with its state) and the current one, prompted with the planner's
subtask. A malformed answer keeps the previous subtask and bank and is counted (``rollout_stats``);
before any valid answer the executor is prompted with the instruction."""

from __future__ import annotations

import torch
from lerobot.utils.constants import OBS_STATE
from torch import Tensor

from ...annotations.keyframes import STRIDE
from ..activearena_oft.modeling_activearena_oft import ActiveArenaOFTPolicy
from ..activearena_planner.answers import parse_planner_answer, stride_frames
from ..activearena_planner.modeling_activearena_planner import ActiveArenaPlannerPolicy
from ..activearena_planner.processor_activearena_planner import PLANNER_PROMPT
from ..activearena_vla.helpers import in_precision, stack_frames
from ..activearena_vla.processor_activearena_vla import FRAME_VALID, GRID, PIXELS, PREFIX_IDS
from .configuration_activearena_plan import ActiveArenaPlanConfig
from .memory_bank import MemoryBank
from .processor_activearena_plan import EXECUTOR_PROMPT


class ActiveArenaPlanPolicy(ActiveArenaOFTPolicy):
    config_class = ActiveArenaPlanConfig
    name = "activearena_plan"

    def reset(self) -> None:
        super().reset()
        self._banks: list[MemoryBank] | None = None
        self._frames: list[dict[int, dict]] | None = None  # env -> stride frame index -> stored frame
        self._calls: list[int] = []

    @property
    def planner(self) -> ActiveArenaPlannerPolicy:
        """The planner checkpoint at ``planner_path``, loaded at first use (kept out of this policy's
        parameters: the two are trained and saved separately)."""
        if getattr(self, "_planner", None) is None:
            from lerobot.configs.policies import PreTrainedConfig

            path = self.config.planner_path
            if not path:
                raise ValueError(
                    "activearena_plan runs its planner at evaluation: pass --policy.planner_path=<a trained "
                    "activearena_planner checkpoint> (see docs/policy.md, ActiveArena-Plan)"
                )
            cfg = PreTrainedConfig.from_pretrained(path)
            if cfg.type != "activearena_planner":
                raise ValueError(
                    f"--policy.planner_path={path} is an {cfg.type!r} checkpoint, not activearena_planner"
                )
            if cfg.image_max_pixels != self.config.image_max_pixels:
                raise ValueError(
                    f"planner and executor must process images alike: image_max_pixels {cfg.image_max_pixels} "
                    f"vs {self.config.image_max_pixels}"
                )
            cfg.device = self.config.device
            planner = ActiveArenaPlannerPolicy.from_pretrained(path, config=cfg)
            object.__setattr__(self, "_planner", planner.eval())
        return self._planner

    def rollout_stats(self) -> list[dict[str, int]]:
        """Per env since the last reset: planner answers, malformed ones, frames in the bank."""
        banks = self._banks or []
        return [
            {"planner_calls": c, "malformed_plans": b.malformed, "bank_frames": len(b.frames)}
            for c, b in zip(self._calls, banks, strict=True)
        ]

    @staticmethod
    def _prompts(tokenizer, template: str, texts: list[str]) -> tuple[Tensor, Tensor]:
        ids = tokenizer(
            [template.format(instruction=t) for t in texts],
            padding=True,
            padding_side="right",
            return_tensors="pt",
            add_special_tokens=False,
        )
        return ids["input_ids"], ids["attention_mask"].bool()

    # At evaluation the base's select_action runs: ``observe`` keeps every stride frame the planner may
    # see or retrieve, each chunk comes from ``plan_and_act``; no frame is written per step (the
    # planner's retrievals are this policy's memory).
    def observe(self, batch: dict[str, Tensor]) -> None:
        super().observe(batch)
        batch_size, t = batch[FRAME_VALID].shape[0], self.step
        if self._banks is None:
            self._banks = [MemoryBank() for _ in range(batch_size)]
            self._frames = [{} for _ in range(batch_size)]
            self._calls = [0] * batch_size
        if t % STRIDE == 0:
            self.ensure_pixels(batch)
            for b in range(batch_size):
                self._frames[b][t] = {
                    "pixels": batch[PIXELS][b],  # an env batch: one frame a sample
                    "grid": batch[GRID][b, -1],
                    "state": batch[OBS_STATE][b] if OBS_STATE in batch else None,
                    "planner": {},  # the planner's vision features of this frame
                }

    @torch.no_grad()
    def predict_action_chunk(self, batch: dict[str, Tensor], **kwargs) -> Tensor:
        """An env batch (T = 1): the planner's subtask and retrievals, then the executor's chunk. A dataset
        batch carries its own history and goes straight to the executor."""
        if batch[FRAME_VALID].shape[1] > 1:
            return super().predict_action_chunk(batch)
        return self.plan_and_act(batch)

    @in_precision
    def plan_and_act(self, batch: dict[str, Tensor]) -> Tensor:
        """Ask the planner (every chunk, on the stride frames seen so far), update each env's bank, and
        predict the chunk from the retrieved frames, the current one and the planner's subtask."""
        t, batch_size = self.step, batch[FRAME_VALID].shape[0]
        tasks = batch.get("task")
        if tasks is None:
            raise ValueError("activearena_plan needs the task instruction ('task') in the batch")
        tasks = [tasks] * batch_size if isinstance(tasks, str) else list(tasks)
        seen = stride_frames(t)
        # planner: the last <= 13 stride frames and the instruction, no state
        rows = [
            [{**self._frames[b][f], "vision": self._frames[b][f]["planner"].get("vision")} for f in seen]
            for b in range(batch_size)
        ]
        pixels, grid, valid, _, cache = stack_frames(rows, len(seen), with_state=False)
        prompt, mask = self._prompts(self.planner.text_tokenizer, PLANNER_PROMPT, tasks)
        answers = self.planner.plan(
            (pixels, grid, valid, None, batch[PREFIX_IDS], prompt, mask), vision_cache=cache
        )
        for (b, slot), e in cache.items():  # keep the planner's features for the frame's next visits
            self._frames[b][seen[slot]]["planner"]["vision"] = e.get("vision")
        for b, text in enumerate(answers):
            self._calls[b] += 1
            self._banks[b].update(parse_planner_answer(text, len(seen)), seen)
        # executor: the retrieved frames (each with its state), the current one, the planner's subtask
        slots = self.config.history + 1
        frames = [self._banks[b].executor_frames(t)[-slots:] for b in range(batch_size)]
        pixels, grid, valid, state, cache = stack_frames(
            [[self._frames[b][f] for f in fs] for b, fs in enumerate(frames)], slots, with_state=True
        )
        subtasks = [bank.subtask or task for bank, task in zip(self._banks, tasks, strict=True)]
        prompt, mask = self._prompts(self.text_tokenizer, EXECUTOR_PROMPT, subtasks)
        args = self.encode_args(pixels, grid, valid, state, batch[PREFIX_IDS], prompt, mask)
        pred = self.encode(*args, vision_cache=cache)[0]
        for b in range(batch_size):  # forget frames neither in the bank nor in the planner's next view
            keep = set(self._banks[b].frames) | set(stride_frames(t + STRIDE))
            self._frames[b] = {f: e for f, e in self._frames[b].items() if f in keep}
        return pred.float()
