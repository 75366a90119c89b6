"""The two websocket protocols a remote policy speaks, client side. Both send msgpack messages whose
numpy arrays travel as ``{"__ndarray__": True, "data", "dtype", "shape"}`` maps.

- openpi (``openpi_client.websocket_client_policy``): the server sends its metadata first, then
  answers each observation with ``{"actions": (H, D), ...}``, or with a text frame holding its
  traceback before closing the connection (code 1011). Map keys of arrays are bytes.
- vla-eval (allenai's harness): every message is ``{"type", "payload", "seq", "timestamp"}``; a
  ``hello`` exchange, then ``episode_start``, one ``observation`` -> ``action`` (or ``error``) per
  question, ``episode_end``. Map keys are strings.
"""

from __future__ import annotations

import time

import msgpack
import numpy as np
import websockets.exceptions
import websockets.sync.client


class RemotePolicyError(RuntimeError):
    """The policy server failed, closed the connection or did not answer in time."""


def _encoder(key):
    def encode(obj):
        if isinstance(obj, np.ndarray):
            if obj.dtype.kind in "VOc":
                raise TypeError(f"cannot send a numpy array of dtype {obj.dtype}")
            return {
                key("__ndarray__"): True,
                key("data"): obj.tobytes(),
                key("dtype"): obj.dtype.str,
                key("shape"): list(obj.shape),
            }
        if isinstance(obj, np.generic):
            return obj.item()
        return obj

    return encode


def _decode(obj: dict):
    for k in ("__ndarray__", b"__ndarray__"):
        if k in obj:
            get = (lambda name: obj[name]) if isinstance(k, str) else (lambda name: obj[name.encode()])
            return np.frombuffer(get("data"), dtype=np.dtype(get("dtype"))).reshape(get("shape")).copy()
    return obj


def pack(obj, str_keys: bool = False) -> bytes:
    """msgpack bytes; arrays as openpi (bytes keys) or vla-eval (``str_keys``) encode them."""
    return msgpack.packb(obj, default=_encoder(str if str_keys else str.encode), use_bin_type=True)


def unpack(data: bytes):
    return msgpack.unpackb(data, object_hook=_decode, raw=False)


class OpenPIClient:
    """One connection to an openpi policy server."""

    def __init__(self, url: str, connect_timeout_s: float, timeout_s: float):
        self.url, self.timeout_s = url, timeout_s
        try:
            self._ws = websockets.sync.client.connect(
                url, compression=None, max_size=None, open_timeout=connect_timeout_s
            ).__enter__()  # held open across episodes; close() ends it
            self.metadata = unpack(self._ws.recv(timeout=timeout_s))
        except (OSError, TimeoutError, websockets.exceptions.WebSocketException) as exc:
            raise RemotePolicyError(
                f"no policy server at {url} ({type(exc).__name__}: {exc}); start it first, or fix --policy.url"
            ) from exc

    def infer(self, obs: dict) -> dict:
        try:
            self._ws.send(pack(obs))
            answer = self._ws.recv(timeout=self.timeout_s)
        except TimeoutError as exc:
            raise RemotePolicyError(
                f"the policy server at {self.url} did not answer within {self.timeout_s} s "
                "(--policy.timeout_s)"
            ) from exc
        except websockets.exceptions.ConnectionClosed as exc:
            raise RemotePolicyError(f"the policy server at {self.url} closed the connection ({exc})") from exc
        if isinstance(answer, str):  # openpi sends the traceback as text, then closes
            raise RemotePolicyError(f"the policy server at {self.url} failed:\n{answer}")
        return unpack(answer)

    def close(self) -> None:
        self._ws.close()


class VlaEvalClient:
    """One connection to a vla-eval model server (its ``serve`` runner)."""

    def __init__(self, url: str, connect_timeout_s: float, timeout_s: float):
        self.url, self.timeout_s, self._seq = url, timeout_s, 0
        try:
            self._ws = websockets.sync.client.connect(
                url, compression=None, max_size=None, open_timeout=connect_timeout_s
            ).__enter__()
            hello = {"harness_version": "activearena", "protocol_version": 1, "benchmark": "activearena"}
            self.metadata = self._ask("hello", hello, "hello")
        except (OSError, TimeoutError, websockets.exceptions.WebSocketException) as exc:
            raise RemotePolicyError(
                f"no vla-eval model server at {url} ({type(exc).__name__}: {exc}); start it first, or fix "
                "--policy.url"
            ) from exc

    def _send(self, kind: str, payload: dict) -> None:
        self._seq += 1
        message = {"type": kind, "payload": payload, "seq": self._seq, "timestamp": time.time()}
        self._ws.send(pack(message, str_keys=True))

    def _ask(self, kind: str, payload: dict, expect: str) -> dict:
        self._send(kind, payload)
        answer = unpack(self._ws.recv(timeout=self.timeout_s))
        if not isinstance(answer, dict) or answer.get("type") == "error":
            raise RemotePolicyError(
                f"the vla-eval model server at {self.url} failed:\n{answer.get('payload') if isinstance(answer, dict) else answer}"
            )
        if answer.get("type") != expect:
            raise RemotePolicyError(
                f"the model server at {self.url} answered {answer.get('type')!r} to {kind!r}"
            )
        return answer["payload"]

    def start_episode(self, task: dict) -> None:
        self._send("episode_start", {"task": task})

    def end_episode(self) -> None:
        self._send("episode_end", {"metrics": {}})

    def infer(self, obs: dict) -> dict:
        try:
            return self._ask("observation", obs, "action")
        except TimeoutError as exc:
            raise RemotePolicyError(
                f"the model server at {self.url} did not answer within {self.timeout_s} s (--policy.timeout_s)"
            ) from exc
        except websockets.exceptions.ConnectionClosed as exc:
            raise RemotePolicyError(f"the model server at {self.url} closed the connection ({exc})") from exc

    def close(self) -> None:
        self._ws.close()
