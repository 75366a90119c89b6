"""openpi's websocket protocol, client side: msgpack messages whose numpy arrays travel as
``{"__ndarray__": True, "data", "dtype", "shape"}`` maps; the server sends its metadata first, then
answers each observation with ``{"actions": (H, D), ...}``, or with a text frame holding its traceback
before closing the connection (code 1011)."""

from __future__ import annotations

import msgpack
import numpy as np
import websockets.exceptions
import websockets.sync.client


class RemotePolicyError(RuntimeError):
    """The policy server failed, closed the connection or did not answer in time."""


def _encode(obj):
    if isinstance(obj, np.ndarray):
        if obj.dtype.kind in "VOc":
            raise TypeError(f"cannot send a numpy array of dtype {obj.dtype}")
        return {b"__ndarray__": True, b"data": obj.tobytes(), b"dtype": obj.dtype.str, b"shape": obj.shape}
    if isinstance(obj, np.generic):
        return {b"__npgeneric__": True, b"data": obj.item(), b"dtype": obj.dtype.str}
    return obj


def _decode(obj: dict):
    if b"__ndarray__" in obj:
        return np.ndarray(buffer=obj[b"data"], dtype=np.dtype(obj[b"dtype"]), shape=obj[b"shape"])
    if b"__npgeneric__" in obj:
        return np.dtype(obj[b"dtype"]).type(obj[b"data"])
    return obj


def pack(obj) -> bytes:
    return msgpack.packb(obj, default=_encode)


def unpack(data: bytes):
    return msgpack.unpackb(data, object_hook=_decode)


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
