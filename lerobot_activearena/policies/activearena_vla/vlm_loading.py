"""Load the Qwen3-VL parts (model, processor, tokenizer) from ``vlm_path``, a Hugging Face id or a
local folder, with one error that names the fix when it cannot be found."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any


def load_from_vlm_path(loader: Callable[..., Any], vlm_path: str, what: str, **kwargs) -> Any:
    try:
        return loader(vlm_path, **kwargs)
    except (OSError, ValueError) as exc:
        raise OSError(
            f"could not load the Qwen3-VL {what} from vlm_path={vlm_path!r}: {exc}\n"
            "Set --policy.vlm_path to a local folder holding a saved Qwen3-VL (model, tokenizer and processor, "
            "e.g. a download of Qwen/Qwen3-VL-2B-Instruct), make the Hugging Face Hub reachable, or, for a smoke "
            "run, create a tiny random one with `activearena-make-tiny-vlm DIR`."
        ) from exc
