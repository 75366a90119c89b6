"""FAST action tokenizer (Pertsch et al.) for ActiveArena-VLA's `fast_subtask_action_12_ws` run.

A chunk (horizon x action_dim, normalised to [-1, 1]) becomes integers: an orthonormal DCT-II over
time for every dimension, times ``scale``, rounded, flattened frequency-major (every dimension's
lowest frequency first). The integers, shifted by the smallest one seen when fitting, are spelled as
characters and compressed with a byte-level BPE (Hugging Face ``tokenizers``) fitted on the
benchmark's own chunks. ``decode`` returns None for an id sequence that does not spell exactly
horizon x action_dim integers: the caller decides what to do (the policy holds its last command).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
from tokenizers import Tokenizer, decoders, models, pre_tokenizers, trainers

CONFIG_FILE, TOKENIZER_FILE = "fast_tokenizer_config.json", "fast_tokenizer.json"


def dct_matrix(n: int) -> np.ndarray:
    """Orthonormal DCT-II (n x n): coefficients = M @ signal, signal = M.T @ coefficients."""
    k, t = np.arange(n)[:, None], np.arange(n)[None, :]
    m = np.sqrt(2.0 / n) * np.cos(math.pi * (2 * t + 1) * k / (2 * n))
    m[0] /= np.sqrt(2.0)
    return m


class FastActionTokenizer:
    def __init__(
        self, bpe: Tokenizer, min_code: int, horizon: int = 16, action_dim: int = 18, scale: float = 10.0
    ):
        self.bpe, self.min_code = bpe, int(min_code)
        self.horizon, self.action_dim, self.scale = int(horizon), int(action_dim), float(scale)
        self._dct = dct_matrix(self.horizon)

    @property
    def vocab_size(self) -> int:
        return self.bpe.get_vocab_size()

    # ---- integers ------------------------------------------------------------------------------
    def codes(self, chunk: np.ndarray) -> np.ndarray:
        """(horizon, action_dim) chunk -> its horizon * action_dim integer DCT codes."""
        chunk = np.asarray(chunk, float)
        if chunk.shape != (self.horizon, self.action_dim):
            raise ValueError(f"a chunk is {(self.horizon, self.action_dim)}, got {chunk.shape}")
        return np.rint(self._dct @ chunk * self.scale).astype(np.int64).reshape(-1)

    def chunk(self, codes: np.ndarray) -> np.ndarray:
        coeffs = np.asarray(codes, float).reshape(self.horizon, self.action_dim) / self.scale
        return self._dct.T @ coeffs

    def _text(self, codes: np.ndarray) -> str:
        low = int(codes.min())
        if low < self.min_code:
            raise ValueError(
                f"DCT code {low} is below the smallest the tokenizer was fitted on ({self.min_code}): the chunk "
                "is outside the fitted range (is it normalised as the fitting data was?); refit on data that covers it"
            )
        return "".join(chr(int(c) - self.min_code) for c in codes)

    # ---- tokens --------------------------------------------------------------------------------
    def encode(self, chunk: np.ndarray) -> list[int]:
        return self.bpe.encode(self._text(self.codes(chunk))).ids

    def decode(self, ids) -> np.ndarray | None:
        """Token ids -> (horizon, action_dim) chunk, or None when they do not spell one."""
        try:
            text = self.bpe.decode([int(i) for i in ids], skip_special_tokens=False)
        except Exception:  # noqa: BLE001  (ids outside the vocabulary)
            return None
        if len(text) != self.horizon * self.action_dim or "\ufffd" in text:  # cut or broken bytes
            return None
        return self.chunk(np.array([ord(c) for c in text]) + self.min_code)

    # ---- fitting and files ---------------------------------------------------------------------
    @classmethod
    def fit(
        cls,
        chunks: np.ndarray,
        vocab_size: int = 2048,
        scale: float = 10.0,
        min_frequency: int = 2,
    ) -> FastActionTokenizer:
        """Fit the BPE on (N, horizon, action_dim) normalised chunks."""
        chunks = np.asarray(chunks, float)
        if chunks.ndim != 3 or len(chunks) == 0:
            raise ValueError(f"fit takes (N, horizon, action_dim) chunks, got shape {chunks.shape}")
        if vocab_size <= 256:
            raise ValueError(f"vocab_size {vocab_size} must exceed the 256 byte symbols")
        probe = cls(Tokenizer(models.BPE()), 0, chunks.shape[1], chunks.shape[2], scale)
        codes = [probe.codes(c) for c in chunks]
        min_code = int(min(c.min() for c in codes))
        bpe = Tokenizer(models.BPE())
        bpe.pre_tokenizer = pre_tokenizers.ByteLevel(add_prefix_space=False, use_regex=False)
        bpe.decoder = decoders.ByteLevel()
        trainer = trainers.BpeTrainer(
            vocab_size=vocab_size,
            min_frequency=min_frequency,
            initial_alphabet=pre_tokenizers.ByteLevel.alphabet(),
            show_progress=False,
        )
        tok = cls(bpe, min_code, chunks.shape[1], chunks.shape[2], scale)
        bpe.train_from_iterator((tok._text(c) for c in codes), trainer=trainer)
        return tok

    def save_pretrained(self, directory: str | Path) -> None:
        d = Path(directory)
        d.mkdir(parents=True, exist_ok=True)
        self.bpe.save(str(d / TOKENIZER_FILE))
        config = {"min_code": self.min_code, "horizon": self.horizon, "action_dim": self.action_dim}
        (d / CONFIG_FILE).write_text(json.dumps({**config, "scale": self.scale}, indent=2) + "\n")

    @classmethod
    def from_pretrained(cls, directory: str | Path) -> FastActionTokenizer:
        d = Path(directory)
        missing = [f for f in (CONFIG_FILE, TOKENIZER_FILE) if not (d / f).is_file()]
        if missing:
            raise FileNotFoundError(
                f"{d} is not a FAST tokenizer folder (missing {', '.join(missing)}); fit one with "
                "`activearena-fit-fast-tokenizer`"
            )
        c = json.loads((d / CONFIG_FILE).read_text())
        return cls(
            Tokenizer.from_file(str(d / TOKENIZER_FILE)),
            c["min_code"],
            c["horizon"],
            c["action_dim"],
            c["scale"],
        )
