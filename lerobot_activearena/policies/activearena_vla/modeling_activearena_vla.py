"""The ActiveArena-VLA base every head shares: Qwen3-VL reads the memory images, the current image
(each optionally followed by a soft state token) and the prompt; a head's action queries (if it
has any) follow the prompt, then the optional ``<think>`` span, trained with next-token loss. The
queries cannot attend to the span (causal attention), so regressed actions never depend on text.
A head fills the hooks ``build_action_head``, ``n_queries``, ``decode_actions`` and ``action_loss`` (or
overrides ``forward`` and ``encode``, as the text heads do, decoding with ``greedy_decode``).

The same ``assemble`` / ``encode`` serve training (history from the batch) and evaluation (history from the
policy's memory bank, written causally and reset per episode), so both see identical inputs."""

from __future__ import annotations

import copy
import math
from collections import deque

import numpy as np
import torch
from lerobot.policies.pretrained import PreTrainedPolicy
from lerobot.utils.constants import OBS_STATE
from torch import Tensor, nn
from transformers.modeling_outputs import BaseModelOutputWithPast

from ...annotations.keyframes import STRIDE, memory_frames, motion_keyframes
from .configuration_activearena_vla import ActiveArenaVLAConfig
from .helpers import (
    blank_entry,
    blank_memory_pixels,
    checkpoint_layers,
    compile_layers,
    drop_memory_frames,
    drop_sample_memory,
    in_precision,
    residual_in_compute_dtype,
    stack_frames,
    weights_dtype,
)
from .processor_activearena_vla import (
    ACTION_WEIGHT,
    FRAME_VALID,
    FRAMES,
    GRID,
    MEMORY_INDEX,
    MEMORY_PIXELS,
    PIXELS,
    PREFIX_IDS,
    PROMPT_IDS,
    PROMPT_MASK,
    RAW_STATE,
    THINK_IDS,
    THINK_MASK,
    check_saved_annotations,
    frame_inputs,
    to_uint8,
)
from .state_encoder import StateEncoder
from .vlm_loading import load_from_vlm_path, load_policy_vlm

TEXT, IMAGE, STATE, QUERY, THINK = 0, 1, 2, 3, 4


class ActiveArenaVLAPolicy(PreTrainedPolicy):
    """Not a policy type of its own: the registered heads subclass it."""

    config_class = ActiveArenaVLAConfig
    name = "activearena_vla"

    def __init__(self, config: ActiveArenaVLAConfig, **kwargs):
        super().__init__(config)
        config.validate_features()
        self.config = config
        self.vlm = load_policy_vlm(config.vlm_path, weights_dtype(config), config.attn_implementation)
        if config.freeze_vision:
            self.vlm.model.visual.requires_grad_(False)
        # memory_vision=frozen: the memory frames' tower, a frozen copy of the one loaded
        self.memory_tower = (
            copy.deepcopy(self.vlm.model.visual).requires_grad_(False)
            if config.memory_vision == "frozen"
            else None
        )
        if config.vision_cache and type(self).forward is not ActiveArenaVLAPolicy.forward:
            raise ValueError(
                f"{self.name} trains with its own forward pass, which reads no vision cache: "
                "train it without --policy.vision_cache"
            )
        self._vision_table = None  # the vision cache, loaded at the first training batch that reads it
        if config.residual_dtype == "compute":
            residual_in_compute_dtype(self.vlm)
        if config.gradient_checkpointing:
            checkpoint_layers(
                self.vlm,
                config.gradient_checkpointing_layers,
                config.gradient_checkpointing_mode,
                config.gradient_checkpointing_language_layers,
            )
        compile_layers(self.vlm, config.compile_layers)
        vc = self.vlm.config
        width = vc.text_config.hidden_size
        self.max_frames = config.history + 1
        self.build_action_head(width)
        state_ft = config.input_features.get(OBS_STATE)
        self.state_encoder = (
            StateEncoder(int(state_ft.shape[0]), config.state_hidden, width, self.max_frames)
            if config.use_state
            else None
        )
        self.image_token_id, self.vision_start_id, self.vision_end_id = (
            vc.image_token_id,
            vc.vision_start_token_id,
            vc.vision_end_token_id,
        )
        self.pad_id = vc.text_config.pad_token_id or 0
        self.reset()

    @classmethod
    def from_pretrained(cls, pretrained_name_or_path, **kwargs):
        policy = super().from_pretrained(pretrained_name_or_path, **kwargs)
        check_saved_annotations(policy.config, pretrained_name_or_path)
        return policy

    # ----- the action head: the hooks each head fills -----
    def build_action_head(self, width: int) -> None:
        """Create the head's modules for a backbone of hidden size ``width``."""
        raise NotImplementedError

    @property
    def n_queries(self) -> int:
        """Action query tokens (``self.action_queries``) placed after the prompt."""
        return 0

    @property
    def think_first(self) -> bool:
        """Whether the think span sits before the action queries (the actions read it) or after them."""
        return False

    @property
    def device(self) -> torch.device:
        return self.vlm.get_input_embeddings().weight.device

    def decode_actions(self, hidden: Tensor, kind: Tensor) -> Tensor:
        """The (B, chunk, predicted_action_dim) prediction from the backbone's last-layer states."""
        raise NotImplementedError

    def action_loss(self, hidden: Tensor, kind: Tensor, batch: dict[str, Tensor]) -> tuple[Tensor, dict]:
        """Per-sample action loss and its log entries."""
        raise NotImplementedError

    # ----- optimisation -----
    def get_optim_params(self) -> list[dict]:
        vision = {id(p) for p in self.vlm.model.visual.parameters()}
        trained = [p for p in self.vlm.parameters() if p.requires_grad]
        heads = [p for n, p in self.named_parameters() if not n.startswith("vlm.") and p.requires_grad]
        if self.config.vision_lr is None:
            return [
                {"params": trained, "lr": self.config.optimizer_lr},
                {"params": heads, "lr": self.config.head_lr},
            ]
        return [
            {"params": [p for p in trained if id(p) not in vision], "lr": self.config.optimizer_lr},
            {"params": [p for p in trained if id(p) in vision], "lr": self.config.vision_lr},
            {"params": heads, "lr": self.config.head_lr},
        ]

    # ----- sequence assembly -----
    def assemble(
        self,
        pixels: Tensor,
        grid: Tensor,
        valid: Tensor,
        state: Tensor | None,
        prefix: Tensor,
        prompt: Tensor,
        prompt_mask: Tensor,
        think: Tensor | None = None,
        think_mask: Tensor | None = None,
        without_pixels: set | None = None,
        queries: bool = True,
    ) -> dict[str, Tensor]:
        """One right-padded token sequence per sample: the frames (each followed by its state token), the
        prompt, the action queries, then the optional think span (before the queries where
        ``think_first``; ``queries=False`` leaves them out). Returns the backbone's inputs and the
        per-position ``kind`` (-1 = padding). ``pixels`` holds every present frame's pixel values except
        those of the (sample, frame) slots in ``without_pixels``, whose features the caller supplies."""
        batch_size, n_frames = valid.shape
        dev = self.device
        # The token bookkeeping reads these small integer tensors element by element: on the host, one
        # copy each, instead of a device sync per element (hundreds a step on a GPU).
        valid, grid, prefix, prompt, prompt_mask = (
            t.cpu() for t in (valid, grid, prefix, prompt, prompt_mask)
        )
        if think is not None:
            think, think_mask = think.cpu(), think_mask.cpu()
        if state is not None and state.dim() == 2:  # no history: one state per sample
            state = state[:, None]
        seqs, kinds, memories, images, states = [], [], [], [], []
        for b in range(batch_size):
            ids, kind = prefix[b].tolist(), [TEXT] * prefix.shape[1]
            memory = [False] * len(ids)  # the positions of a memory frame (its image, markers and state)
            for j in range(n_frames):
                if not valid[b, j]:
                    continue
                n = int(grid[b, j].prod()) // self.vlm.config.vision_config.spatial_merge_size**2
                ids += [self.vision_start_id] + [self.image_token_id] * n + [self.vision_end_id]
                kind += [TEXT] + [IMAGE] * n + [TEXT]
                images.append((b, j))
                if self.state_encoder is not None and (
                    self.config.state_frames == "all" or j < n_frames - 1  # the current frame is the last
                ):
                    ids.append(self.pad_id)
                    kind.append(STATE)
                    states.append(
                        (b, j, j + self.max_frames - n_frames)
                    )  # current frame: always the last slot
                memory += [j < n_frames - 1] * (len(ids) - len(memory))
            p = prompt[b][prompt_mask[b]].tolist()
            t = think[b][think_mask[b]].tolist() if think is not None else []
            n_queries = self.n_queries if queries else 0
            if self.think_first:
                ids += p + t + [self.pad_id] * n_queries
                kind += [TEXT] * len(p) + [THINK] * len(t) + [QUERY] * n_queries
            else:
                ids += p + [self.pad_id] * n_queries + t
                kind += [TEXT] * len(p) + [QUERY] * n_queries + [THINK] * len(t)
            seqs.append(ids)
            kinds.append(kind)
            memories.append(memory)
        seq_len = max(len(s) for s in seqs)
        input_ids = torch.full((batch_size, seq_len), self.pad_id, dtype=torch.long)
        kind = torch.full((batch_size, seq_len), -1, dtype=torch.long)
        memory = torch.zeros((batch_size, seq_len), dtype=torch.bool)
        for b, (s, k, m) in enumerate(zip(seqs, kinds, memories, strict=True)):
            input_ids[b, : len(s)], kind[b, : len(k)] = torch.tensor(s), torch.tensor(k)
            memory[b, : len(m)] = torch.tensor(m, dtype=torch.bool)
        attn = (kind >= 0).long()
        mm = (kind == IMAGE).long()
        # M-RoPE positions from the host copies (Qwen3-VL's get_rope_index reads them per image), and
        # the image grid stays there: the vision tower reads it with .tolist() too
        thw = torch.stack([grid[b, j] for b, j in images])
        position_ids, _ = self.vlm.model.get_rope_index(
            input_ids=input_ids, mm_token_type_ids=mm, image_grid_thw=thw, attention_mask=attn
        )
        input_ids, kind, attn, mm = input_ids.to(dev), kind.to(dev), attn.to(dev), mm.to(dev)
        embeds = self.vlm.get_input_embeddings()(input_ids)
        if (kind == QUERY).any():
            embeds = embeds.masked_scatter(
                (kind == QUERY)[..., None], self.action_queries.to(embeds.dtype).repeat(batch_size, 1)
            )
        if states:
            rows = torch.stack([state[b, j] for b, j, _ in states]).to(dev, torch.float32)
            slots = torch.tensor([s for _, _, s in states], device=dev)
            embeds = embeds.masked_scatter(
                (kind == STATE)[..., None], self.state_encoder(rows, slots).to(embeds.dtype)
            )
        pixel_frames = [i for i, k in enumerate(images) if not without_pixels or k not in without_pixels]
        pv = pixels.reshape(-1, pixels.shape[-1])  # (patches of all frames, dim)
        needed = int(thw[pixel_frames].prod(-1).sum()) if pixel_frames else 0
        if len(pv) != needed:
            raise ValueError(
                f"pixel values of {len(pv)} patches, but the grids of the {len(pixel_frames)} frames that need "
                f"them hold {needed}: pixel_values holds the present frames only, packed in (sample, frame) order"
            )
        pv = pv.to(dev, self.vlm.dtype)
        return {
            "input_ids": input_ids,
            "kind": kind,
            "memory": memory.to(dev),
            "inputs_embeds": embeds,
            "attention_mask": attn,
            "position_ids": position_ids.to(dev),
            "pixel_values": pv,
            "image_grid_thw": thw,
            "mm_token_type_ids": mm,
            "images": images,
            "pixel_frames": pixel_frames,
            "n_frames": n_frames,
        }

    def vision_features(
        self, pixel_values: Tensor, grid: Tensor, memory: bool = False
    ) -> list[tuple[Tensor, list[Tensor]]]:
        """Vision tower per image (each image attends only to itself): its merged tokens and DeepStack
        features, so a memory frame's can be kept and reused at later chunks. ``memory``: the images
        are memory frames (read by ``memory_tower`` where there is one)."""
        # the grid is on the host (``assemble``), so the tower's cu_seqlens are too; flash-attn's
        # variable-length kernel needs them on the GPU
        flash = self.config.attn_implementation == "flash_attention_2"
        grid = grid.to(self.device) if flash else grid
        sizes = (grid.prod(-1) // self.vlm.config.vision_config.spatial_merge_size**2).tolist()
        if memory and self.memory_tower is not None:
            with torch.no_grad():
                out = self.memory_tower(
                    pixel_values.type(self.memory_tower.dtype), grid_thw=grid, return_dict=True
                )
            embeds = torch.split(out.pooler_output, sizes)
        else:
            out = self.vlm.model.get_image_features(pixel_values, grid)
            embeds = out.pooler_output
        deep = [torch.split(d, sizes) for d in out.deepstack_features]
        return [(e, [d[i] for d in deep]) for i, e in enumerate(embeds)]

    def run_backbone(self, seq: dict, use_cache: bool = False, vision_cache: dict | None = None):
        """The language model over the assembled sequence, image tokens from the vision tower. Memory
        frames found in ``vision_cache`` ((sample, frame) -> bank entry) reuse the entry's features;
        the others are computed and stored there. Returns the output and each image's features."""
        vision_cache = vision_cache or {}
        images, grid, pixel_frames = seq["images"], seq["image_grid_thw"], seq["pixel_frames"]
        sizes = grid.prod(-1)[pixel_frames].tolist()
        rows = dict(zip(pixel_frames, torch.split(seq["pixel_values"], sizes), strict=True))
        feats: list = [vision_cache[k].get("vision") if k in vision_cache else None for k in images]
        todo = [i for i, f in enumerate(feats) if f is None]
        if any(i not in rows for i in todo):
            raise ValueError("a frame without pixel values has no features in the vision cache either")
        # a frame is a memory frame unless it is its sample's last slot (the current frame)
        current = seq["n_frames"] - 1
        groups = (
            [[i for i in todo if images[i][1] != current], [i for i in todo if images[i][1] == current]]
            if self.memory_tower is not None
            else [todo]
        )
        for group in groups:
            if not group:
                continue
            memory = self.memory_tower is not None and images[group[0]][1] != current
            computed = self.vision_features(torch.cat([rows[i] for i in group]), grid[group], memory)
            for i, f in zip(group, computed, strict=True):
                feats[i] = f
                if images[i] in vision_cache:
                    vision_cache[images[i]]["vision"] = f
        mask = seq["kind"] == IMAGE
        embeds = seq["inputs_embeds"].masked_scatter(
            mask[..., None], torch.cat([f[0] for f in feats]).to(seq["inputs_embeds"].dtype)
        )
        deep = [torch.cat([f[1][layer] for f in feats]) for layer in range(len(feats[0][1]))]
        # Sequences are right-padded, so under causal attention no real token sees a pad: without a
        # cache the padding mask changes only the pads' own (unread) outputs, and leaving it out lets
        # SDPA run its causal flash kernel with grouped-query heads instead of a masked kernel over
        # repeated keys and values. A cache is kept for tokens appended after the pads: they need it.
        readers = self.memory_read_mask(seq, embeds.dtype)
        if self.config.unpad_language_model and not use_cache and len(embeds) > 1:
            return self.language_model_per_sample(embeds, seq, mask, deep, readers), feats
        out = self.vlm.model.language_model(
            inputs_embeds=embeds,
            attention_mask=readers if readers is not None else seq["attention_mask"] if use_cache else None,
            position_ids=seq["position_ids"],
            use_cache=use_cache,
            visual_pos_masks=mask,
            deepstack_visual_embeds=deep,
        )
        return out, feats

    def memory_read_mask(self, seq: dict, dtype: torch.dtype) -> Tensor | None:
        """With ``memory_readers=span``: the (B, 1, L, L) attention mask under which a memory frame's
        positions are read only by the think span and by later positions of the memory itself (causal
        otherwise; True or 0 = attends, as the attention kernel takes it). None: plain causal attention."""
        memory = seq["memory"]
        if self.config.memory_readers == "all" or not memory.any():
            return None
        kind, length = seq["kind"], memory.shape[1]
        allowed = torch.ones(length, length, dtype=torch.bool, device=memory.device).tril()
        allowed = allowed & (kind >= 0)[:, None, :]
        allowed = allowed & ~(memory[:, None, :] & ~(memory | (kind == THINK))[:, :, None])
        allowed |= torch.eye(length, dtype=torch.bool, device=memory.device)  # a pad reads itself
        if self.config.attn_implementation == "eager":  # added to the scores
            return torch.zeros(allowed.shape, dtype=dtype, device=memory.device).masked_fill(
                ~allowed, torch.finfo(dtype).min
            )[:, None]
        return allowed[:, None]

    def language_model_per_sample(
        self, embeds: Tensor, seq: dict, mask: Tensor, deep: list, readers: Tensor | None = None
    ):
        """The language model once per sample over its own tokens (``unpad_language_model``): no pad
        position is computed or kept for the backward pass. Same outputs as the padded batch (causal
        attention over right-padded rows, or ``readers``' mask); the pads' rows are zeros."""
        lengths, position_ids = (seq["kind"] >= 0).sum(1), seq["position_ids"]
        rows, start = [], 0
        for b, n in enumerate(lengths.tolist()):
            images = int(mask[b, :n].sum())
            out = self.vlm.model.language_model(
                inputs_embeds=embeds[b : b + 1, :n],
                attention_mask=None if readers is None else readers[b : b + 1, :, :n, :n],
                position_ids=position_ids[:, b : b + 1, :n],
                use_cache=False,
                visual_pos_masks=mask[b : b + 1, :n],
                deepstack_visual_embeds=[d[start : start + images] for d in deep],
            )
            start += images
            rows.append(out.last_hidden_state[0])
        hidden = torch.nn.utils.rnn.pad_sequence(rows, batch_first=True)
        hidden = nn.functional.pad(hidden, (0, 0, 0, embeds.shape[1] - hidden.shape[1]))
        return BaseModelOutputWithPast(last_hidden_state=hidden)

    def encode(self, *args, vision_cache: dict | None = None) -> tuple[Tensor, Tensor | None]:
        """Returns the (B, chunk, predicted_action_dim) prediction and, when a think span is given, its
        LM loss. Arguments as ``assemble``."""
        h, kind, lm_loss = self.hidden_states(*args, vision_cache=vision_cache)
        return self.decode_actions(h, kind), lm_loss

    def hidden_states(self, *args, vision_cache: dict | None = None) -> tuple[Tensor, Tensor, Tensor | None]:
        """The backbone's last-layer states, the per-position ``kind`` and, when a think span is given,
        its LM loss. Arguments as ``assemble``."""
        without = {k for k, e in vision_cache.items() if "pixels" not in e} if vision_cache else None
        seq = self.assemble(*args, without_pixels=without)
        kind, input_ids = seq["kind"], seq["input_ids"]
        h = self.run_backbone(seq, vision_cache=vision_cache)[0].last_hidden_state
        if not (kind == THINK).any():
            return h, kind, None
        span = kind == THINK
        src = span.clone()
        src[:, :-1] &= span[:, 1:]  # a think token predicts the next think token
        src[:, -1] = False
        tgt = torch.zeros_like(span)
        tgt[:, 1:] = src[:, :-1]
        logits = self.vlm.lm_head(h[src]).float()
        loss = nn.functional.cross_entropy(logits, input_ids[tgt], reduction="none")
        weight = self.think_token_weights(input_ids, span)[tgt]
        return h, kind, (loss * weight).sum() / weight.sum()

    def think_token_weights(self, input_ids: Tensor, span: Tensor) -> Tensor:
        """Per position, the LM-loss weight of the token there as a target: ``decision_token_weight``
        after the span's last ";" (the decision clause of a ``think=decision`` target), 1 elsewhere."""
        weight = torch.ones(input_ids.shape, device=input_ids.device)
        if self.config.decision_token_weight == 1:
            return weight
        semicolon = self.text_tokenizer.convert_tokens_to_ids(";")
        pos = torch.arange(input_ids.shape[1], device=input_ids.device).expand_as(input_ids)
        last = torch.where(span & (input_ids == semicolon), pos, -1).max(1).values[:, None]
        return weight.masked_fill(span & (last >= 0) & (pos > last), self.config.decision_token_weight)

    # ----- training -----
    def training_args(self, batch: dict[str, Tensor]) -> tuple:
        """``assemble``'s arguments from a preprocessed dataset batch (history frames, think target)."""
        state = batch.get(OBS_STATE) if self.state_encoder is not None else None
        if state is not None and state.dim() == 2:
            state = state[:, None]
        if state is not None and self.training and self.config.memory_state_dropout > 0:
            dropped = torch.rand(len(state), device=state.device) < self.config.memory_state_dropout
            state = torch.where(dropped[:, None, None], state[:, -1:].expand_as(state), state)
        think = batch.get(THINK_IDS) if self.config.think != "none" else None
        self.ensure_pixels(batch)
        return (
            batch[PIXELS],
            batch[GRID],
            batch[FRAME_VALID],
            state,
            batch[PREFIX_IDS],
            batch[PROMPT_IDS],
            batch[PROMPT_MASK],
            think,
            batch.get(THINK_MASK),
        )

    def cached_memory(self, batch: dict[str, Tensor]) -> dict | None:
        """The memory frames' features from the vision cache (``MEMORY_INDEX``): (sample, slot) -> entry
        without pixels, or None when the batch carries its memory as images."""
        if MEMORY_INDEX not in batch:
            return None
        if not self.config.vision_cache:
            raise ValueError("the batch indexes a vision cache, but --policy.vision_cache is not set")
        if self._vision_table is None:
            from .vision_cache import VisionCache

            self._vision_table = VisionCache(
                self.config.vision_cache,
                self.memory_tower if self.memory_tower is not None else self.vlm.model.visual,
                self.config.image_max_pixels,
            )
        table, grid = self._vision_table, batch[GRID][:, :-1].cpu()  # the memory slots'
        if not bool((grid == table.grid).all()):
            raise ValueError(
                f"the vision cache's frames have grid {table.grid.tolist()}, this batch's memory frames "
                f"{grid[0, 0].tolist()}: the cache was made from images of another size"
            )
        cache = {}
        for b, row in enumerate(batch[MEMORY_INDEX].cpu().tolist()):
            for slot, g in enumerate(row):
                if g >= 0:
                    cache[(b, slot)] = {"vision": table.features(g, self.device)}
        return cache

    def check_think_budget(self, batch: dict[str, Tensor]) -> None:
        """With ``think_first``, refuses a ``<think>`` target longer than ``subtask_max_tokens``: the
        evaluation's greedy decoding stops there, so the actions would read a span cut short of what
        they were trained on. (``memory=subtask`` decodes only to see the subtask change; a short
        budget is its speed setting.)"""
        if THINK_MASK not in batch or not self.think_first:
            return
        longest = int(batch[THINK_MASK].sum(-1).max()) - 2  # the target and </think>, as decoding counts them
        if longest > self.config.subtask_max_tokens:
            raise ValueError(
                f"the <think> target has {longest} tokens with </think>, more than --policy.subtask_max_tokens="
                f"{self.config.subtask_max_tokens}: at evaluation its decoding would be cut short. Set "
                f"--policy.subtask_max_tokens to at least {longest}"
            )

    @in_precision
    def forward(self, batch: dict[str, Tensor], reduction: str = "mean"):
        if self.training:
            self.check_think_budget(batch)
        args, cache = list(self.training_args(batch)), self.cached_memory(batch)
        if self.training and self.config.memory_dropout > 0:
            dropped = torch.rand(len(args[2])) < self.config.memory_dropout
            args[0], args[2], cache = drop_sample_memory(args[0], args[1], args[2], cache, dropped)
        h, kind, lm_loss = self.hidden_states(*args, vision_cache=cache)
        per_sample, info = self.action_loss(h, kind, batch)
        c = self.config
        weighted = c.decision_weight != 1 or c.opening_weight != 1 or c.miss_weight != 1
        if self.training and weighted and ACTION_WEIGHT not in batch:
            raise ValueError(
                f"--policy.decision_weight={c.decision_weight} / --policy.opening_weight="
                f"{c.opening_weight} / --policy.miss_weight={c.miss_weight}, but the batch carries no action "
                "weights: the annotation step that writes them was left out of the preprocessor"
            )
        if ACTION_WEIGHT in batch:  # decision_weight / opening_weight / miss_weight
            weight = batch[ACTION_WEIGHT].to(per_sample)
            per_sample = per_sample * weight * (len(weight) / weight.sum().clamp_min(1e-8))  # all 0: no loss
        loss = per_sample.mean() if reduction == "mean" else per_sample
        if lm_loss is not None:
            loss = loss + self.config.lm_loss_weight * lm_loss
            info["lm_loss"] = float(lm_loss.detach())
        return loss, info

    # ----- evaluation: memory bank -----
    # ``select_action`` runs, per env step: ``observe`` (bookkeeping of the new observation), a new chunk
    # from ``predict_action_chunk`` when the queue is empty, ``remember`` (memory writes), then pops one
    # action. A head changes what is remembered through ``writes_frame``, how an env chunk is decoded
    # through ``predict_chunk``, and what an episode starts with through ``start_episode``.
    def reset(self) -> None:
        self._queue: deque[Tensor] = deque()
        self._bank: list[list[dict]] | None = None
        self._raw_states: list[list[np.ndarray]] | None = None
        self._current_vision: dict = {}
        self._t = 0

    @property
    def step(self) -> int:
        """Env steps taken since the last ``reset``."""
        return self._t

    @property
    def queued_actions(self) -> int:
        """Actions of the current chunk not yet returned."""
        return len(self._queue)

    def memory(self, b: int = 0) -> list[dict]:
        """Env ``b``'s memory, oldest first (empty before an episode): per frame its env step ``t``,
        ``pixels``, ``grid``, ``state`` and cached ``vision`` features (None until first encoded)."""
        return [] if self._bank is None else list(self._bank[b])

    @property
    def chunk_write_stride(self) -> int:
        """Chunk memory's write period: every 16th step where the policy re-plans every 16 steps (the
        paper's); with ``n_action_steps`` below 16, every step a later decision reads (gcd(16, n))."""
        return math.gcd(STRIDE, self.config.n_action_steps)

    def chunk_memory(self, b: int) -> list[dict]:
        """What a decision at this step reads of env b's chunk memory: the frames 16, 32, ... steps back
        (the K newest), the stride-16 history the policy was trained on at every frame."""
        read = set(memory_frames("chunk", self._t, self.config.history))
        return [e for e in self._bank[b] if e["t"] in read]

    def writes_frame(self, b: int) -> bool:
        """Is the frame just observed (step ``self.step``) written to env b's memory? The paper's
        chunk (every 16th step) and motion (keyframes of the state so far) write policies."""
        policy = self.config.memory
        if policy == "chunk":
            return self._t % self.chunk_write_stride == 0
        if policy == "motion":
            return bool(motion_keyframes(np.stack(self._raw_states[b]))[-1])
        return False

    def history_batch(self, batch: dict[str, Tensor]):
        """Stack each env's last K memory entries (left-padded) and the current frame (``stack_frames``).
        The vision cache maps (env, slot) to the memory entry (its features are reused or stored there),
        and the current frame's slot to a new entry that receives its features."""
        history = self.config.history if self.config.uses_history else 0
        cur_state = batch.get(OBS_STATE)
        cur_state = cur_state[:, -1] if cur_state is not None and cur_state.dim() == 3 else cur_state
        self.ensure_pixels(batch)
        rows = []
        for b in range(batch[FRAME_VALID].shape[0]):
            current = {  # an env batch: one frame a sample, so sample b's pixels are row b
                "pixels": batch[PIXELS][b],
                "grid": batch[GRID][b, -1],
                "state": None if cur_state is None else cur_state[b],
            }
            if not history:
                memory = []
            elif self.config.memory == "chunk":
                memory = self.chunk_memory(b)
            else:
                memory = self._bank[b][-history:]
            if self.config.memory_ablation == "blank":
                memory = [blank_entry(e) for e in memory]
            elif self.config.memory_ablation == "drop":
                memory = []
            rows.append([*memory, current])
        return stack_frames(rows, history + 1)

    @torch.no_grad()
    @in_precision
    def predict_action_chunk(self, batch: dict[str, Tensor], **kwargs) -> Tensor:
        """A chunk for the batch's current frames. A dataset batch carries its own history (T > 1);
        an env batch (T = 1) gets it from the memory bank."""
        cache = None
        if batch[FRAME_VALID].shape[1] > 1:
            self.ensure_pixels(batch)
            state = batch.get(OBS_STATE)
            state = state[:, None] if state is not None and state.dim() == 2 else state
            pixels, grid, valid = batch[PIXELS], batch[GRID], batch[FRAME_VALID]
            if self.config.memory_ablation == "blank":
                pixels = blank_memory_pixels(pixels, valid, grid)
            elif self.config.memory_ablation == "drop":
                pixels, valid = drop_memory_frames(pixels, valid, grid)
        else:
            if self._bank is None:
                self.start_episode(batch)
            pixels, grid, valid, state, cache = self.history_batch(batch)
        args = self.encode_args(
            pixels, grid, valid, state, batch[PREFIX_IDS], batch[PROMPT_IDS], batch[PROMPT_MASK]
        )
        if cache is None and not self.think_first:
            pred = self.encode(*args)[0]
        else:  # a think-first policy decodes its span before it acts, on dataset batches too
            pred = self.predict_chunk(args, vision_cache=cache)
        if self.config.fixed_view:  # placeholders: the postprocessor sets torso and head to home
            pred = nn.functional.pad(pred, (0, self.config.action_dim - pred.shape[-1]))
        # the current frames' features, for a memory write at this step (none where a memory tower
        # of its own reads the memory, or the memory keeps frames at another size: those are encoded
        # at their first use as memory)
        if cache is not None and self.memory_tower is None and self.config.current_image_pixels is None:
            self._current_vision = {
                b: entry.get("vision") for (b, slot), entry in cache.items() if slot == valid.shape[1] - 1
            }
        return pred.float()

    def encode_args(self, pixels, grid, valid, state, prefix, prompt, prompt_mask) -> tuple:
        """``assemble``'s inputs at evaluation (no think span); the state only where it has tokens."""
        return (
            pixels,
            grid,
            valid,
            state if self.state_encoder is not None else None,
            prefix,
            prompt,
            prompt_mask,
        )

    def predict_chunk(self, encode_args: tuple, vision_cache: dict | None = None) -> Tensor:
        """The (B, chunk, predicted_action_dim) chunk at an env step, from ``encode_args``' inputs."""
        return self.encode(*encode_args, vision_cache=vision_cache)[0]

    def start_episode(self, batch: dict[str, Tensor]) -> None:
        """Empty memories for the batch's envs (called at the first env step after ``reset``)."""
        batch_size = batch[FRAME_VALID].shape[0]
        self._bank = [[] for _ in range(batch_size)]
        self._raw_states = [[] for _ in range(batch_size)]

    @property
    def text_tokenizer(self):
        """The backbone's tokenizer (loaded at first use)."""
        if not hasattr(self, "_text_tokenizer"):
            from transformers import AutoTokenizer

            self._text_tokenizer = load_from_vlm_path(
                AutoTokenizer.from_pretrained, self.config.vlm_path, "tokenizer"
            )
        return self._text_tokenizer

    def think_token_ids(self) -> tuple[int, int]:
        tok = self.text_tokenizer
        return tok.convert_tokens_to_ids("<think>"), tok.convert_tokens_to_ids("</think>")

    @in_precision
    def greedy_decode(
        self,
        encode_args: tuple,
        start: list[int],
        stop: int,
        max_tokens: int,
        use_cache: bool = True,
        vision_cache: dict | None = None,
    ) -> tuple[list[tuple[int, ...]], list[Tensor], tuple[Tensor, Tensor]]:
        """Greedy decoding after the ``start`` tokens (fed as the think span) until every sample has
        produced ``stop`` or ``max_tokens`` tokens. Returns each sample's new tokens (up to and
        including its first ``stop``), each step's (B, vocab) logits and the first pass's last-layer
        states and ``kind``. With ``use_cache`` the images and prompt go through the backbone once and
        every new token reuses their keys and values; without it each step re-encodes the whole
        sequence (the reference)."""
        batch_size, dev = encode_args[2].shape[0], self.device
        fed = torch.tensor([start] * batch_size, dtype=torch.long)  # start and every token fed back since
        rows, step_logits = torch.arange(batch_size, device=dev), []
        seq = cache = first = None
        for _ in range(max_tokens):
            if seq is None or not use_cache:
                # think first: the queries would sit after the span, so the decoding runs without them
                seq = self.assemble(
                    *encode_args, fed, torch.ones_like(fed, dtype=torch.bool), queries=not self.think_first
                )
                out = self.run_backbone(seq, use_cache=use_cache, vision_cache=vision_cache)[0]
                last = (
                    torch.where(seq["kind"] == THINK, torch.arange(seq["kind"].shape[1], device=dev), -1)
                    .max(1)
                    .values
                )
                hidden, cache = out.last_hidden_state[rows, last], out.past_key_values
                if first is None:
                    first = (out.last_hidden_state, seq["kind"])
                position = seq["position_ids"][:, rows, last]  # (3, B): a text token's M-RoPE position
                attn = seq["attention_mask"]
            else:
                position = position + 1  # the next text token, on all M-RoPE axes
                attn = torch.cat([attn, attn.new_ones(batch_size, 1)], dim=1)
                out = self.vlm.model.language_model(
                    inputs_embeds=self.vlm.get_input_embeddings()(fed[:, -1:].to(dev)),
                    attention_mask=attn,
                    position_ids=position[..., None],
                    past_key_values=cache,
                    use_cache=True,
                )
                hidden, cache = out.last_hidden_state[:, -1], out.past_key_values
            logits = self.vlm.lm_head(hidden).float()
            step_logits.append(logits)
            fed = torch.cat([fed, logits.argmax(-1).cpu()[:, None]], dim=1)
            if (fed[:, len(start) :] == stop).any(1).all():
                break
        tokens = []
        for row in fed[:, len(start) :].tolist():  # each sample's tokens up to and including its first stop
            tokens.append(tuple(row[: row.index(stop) + 1] if stop in row else row))
        return tokens, step_logits, first

    @property
    def image_processor(self):
        """The backbone's image processor (loaded at first use)."""
        if not hasattr(self, "_image_processor"):
            from transformers import AutoProcessor

            processor = load_from_vlm_path(AutoProcessor.from_pretrained, self.config.vlm_path, "processor")
            self._image_processor = processor.image_processor
        return self._image_processor

    def ensure_pixels(self, batch: dict[str, Tensor]) -> None:
        """An env batch's pixel values and grids (``PIXELS``, ``GRID``), from its ``FRAMES`` through the
        backbone's image processor, at the first step that reads them (the preprocessor defers them)."""
        if PIXELS in batch or FRAMES not in batch:
            return
        frames = to_uint8(batch[FRAMES].images.to(self.device))
        pv, grid = frame_inputs(self.image_processor, frames, self.config, self.device)
        batch[PIXELS], batch[GRID] = pv, grid[:, None]

    def memory_pixels(self, batch: dict[str, Tensor]) -> tuple[Tensor, Tensor]:
        """An env batch's (B, patches, dim) pixel values and (B, 3) grids as its memory keeps them:
        the current frame's, or with ``current_image_pixels`` the frames at ``image_max_pixels``."""
        self.ensure_pixels(batch)
        if self.config.current_image_pixels is None:
            return batch[PIXELS], batch[GRID][:, -1]
        if MEMORY_PIXELS not in batch:
            if FRAMES not in batch:
                raise ValueError(
                    "with --policy.current_image_pixels the memory keeps the env frames at image_max_pixels, "
                    "but this batch carries only the current frame's pixels: keep the preprocessor's "
                    "defer_env_frames on"
                )
            frames = to_uint8(batch[FRAMES].images.to(self.device))
            pv, grid = frame_inputs(self.image_processor, frames, self.config, self.device, memory=True)
            batch[MEMORY_PIXELS] = (pv, grid)
        return batch[MEMORY_PIXELS]

    @torch.no_grad()
    def select_action(self, batch: dict[str, Tensor], **kwargs) -> Tensor:
        self.eval()
        self.observe(batch)
        if not self._queue:
            chunk = self.predict_action_chunk(batch)[:, : self.config.n_action_steps]
            self._queue.extend(chunk.transpose(0, 1))
        self.remember(batch)
        self._t += 1
        return self._queue.popleft()

    def replan(self) -> None:
        """Drop the actions queued from the last decision: the next ``select_action`` decides a new chunk
        from its own observation (the memory bank is kept)."""
        self._queue.clear()

    def observe(self, batch: dict[str, Tensor]) -> None:
        """Bookkeeping of an env step's observation before any chunk is predicted: start the episode's
        memories, keep the raw state (the motion write policy reads the states so far)."""
        if self._bank is None:
            self.start_episode(batch)
        batch_size = batch[FRAME_VALID].shape[0]
        if RAW_STATE in batch:
            dim = self.config.input_features[OBS_STATE].shape[0]
            if tuple(batch[RAW_STATE].shape) != (batch_size, dim):
                raise ValueError(
                    f"observation.state must be (batch, {dim}) at evaluation, got "
                    f"{tuple(batch[RAW_STATE].shape)}: pass the current state only (history comes "
                    "from the policy's memory bank)"
                )
            for b in range(batch_size):
                self._raw_states[b].append(batch[RAW_STATE][b].float().cpu().numpy())
        self._current_vision = {}

    def remember(self, batch: dict[str, Tensor]) -> None:
        """Write the step's frame to each env's memory where ``writes_frame`` says so (K newest kept)."""
        if self.config.uses_history:
            for b in range(batch[FRAME_VALID].shape[0]):
                if self.writes_frame(b):  # vision features: this step's, else computed at first use
                    pixels, grid = self.memory_pixels(batch)
                    self._bank[b].append(
                        {
                            "t": self._t,
                            "pixels": pixels[b],  # one frame a sample
                            "grid": grid[b],
                            "state": batch[OBS_STATE][b] if OBS_STATE in batch else None,
                            "vision": self._current_vision.get(b),
                        }
                    )
                    kept = self.config.history
                    if self.config.memory == "chunk":  # the frames of every re-planning step's history
                        kept *= STRIDE // self.chunk_write_stride
                    del self._bank[b][:-kept]
