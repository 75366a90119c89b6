"""Policy servers for the remote-policy tests, served by openpi's own ``WebsocketPolicyServer`` in a
process of their own (so a test can kill one mid-episode):

    python tests/helpers/policy_servers.py KIND PORT --task T --split S --episodes 0,1 [--log FILE]

KIND: ``replay`` (the expert's recorded actions of those manifest episodes, in order), ``log`` (holds
still, writes what it receives to --log), ``error`` / ``hang`` / ``die`` (hold still in the first
episode, then raise / never answer / exit in the second). ``vla_replay``, ``vla_log`` and ``vla_error``
are the same served by vla-eval's own model-server runner (one action per question, as its servers
answer)."""

import argparse
import json
import os
import time

import numpy as np
from openpi_server import WebsocketPolicyServer

CHUNK = 16


class Served:
    def __init__(self, kind: str, actions: list[np.ndarray], log: str | None):
        self.kind, self.actions, self.log = kind, actions, log
        self.episode = -1

    def infer(self, obs: dict) -> dict:
        step = int(obs["activearena/step"])
        if step == 0:
            self.episode += 1
        if self.log:
            with open(self.log, "a") as f:
                f.write(json.dumps({k: _describe(v) for k, v in obs.items()}) + "\n")
        if self.kind == "replay":
            acts = self.actions[self.episode]
            rows = [acts[min(t, len(acts) - 1)] for t in range(step, step + CHUNK)]
            return {"actions": np.stack(rows)}
        if self.episode >= 1 and self.kind == "error":
            raise ValueError("the policy server's model failed on purpose")
        if self.episode >= 1 and self.kind == "hang":
            time.sleep(3600)
        if self.episode >= 1 and self.kind == "die" and step >= 32:
            os._exit(1)
        return {"actions": np.tile(obs["observation/state"], (CHUNK, 1))}

    def reset(self) -> None:
        pass


def vla_eval_server(served: Served):
    """``served`` behind vla-eval's ``PredictModelServer``: the episode advances on ``episode_start``;
    ``ctx.step`` is the env step."""
    from vla_eval.model_servers.predict import PredictModelServer

    class Server(PredictModelServer):
        async def on_episode_start(self, config, ctx):
            served.episode += 1
            if served.log:
                with open(served.log, "a") as f:
                    f.write(json.dumps({"episode_start": config}) + "\n")
            await super().on_episode_start(config, ctx)

        def predict(self, obs, ctx):
            if served.log:
                with open(served.log, "a") as f:
                    f.write(json.dumps({k: _describe(v) for k, v in obs.items()}) + "\n")
            if served.kind == "vla_error" and served.episode >= 1:
                raise ValueError("the policy server's model failed on purpose")
            if served.kind == "vla_replay":
                acts = served.actions[served.episode]
                return {"actions": acts[min(ctx.step, len(acts) - 1)]}
            return {"actions": np.asarray(obs["state"], dtype=np.float32)}

        def get_action_spec(self):
            return {}

        def get_observation_spec(self):
            return {}

    return Server()


def _describe(value):
    if isinstance(value, np.ndarray):
        return {"type": "ndarray", "dtype": str(value.dtype), "shape": list(value.shape)}
    if isinstance(value, dict):
        return {"type": "dict", "value": {k: _describe(v) for k, v in value.items()}}
    return {"type": type(value).__name__, "value": value}


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument(
        "kind", choices=["replay", "log", "error", "hang", "die", "vla_replay", "vla_log", "vla_error"]
    )
    p.add_argument("port", type=int)
    p.add_argument("--task", default="click_bell_rotate_view")
    p.add_argument("--split", default="id")
    p.add_argument("--episodes", default="0")
    p.add_argument("--log", default=None)
    args = p.parse_args()
    actions = []
    if args.kind in ("replay", "vla_replay"):
        from lerobot_activearena.envs.manifests import manifest_seed
        from lerobot_activearena.episodes.rollout import run_expert_episode

        for k in map(int, args.episodes.split(",")):
            ep = run_expert_episode(args.task, manifest_seed(args.task, args.split, k), args.split)
            actions.append(np.asarray(ep.actions, dtype=np.float64))
    served = Served(args.kind, actions, args.log)
    if args.kind.startswith("vla_"):
        from vla_eval.model_servers.serve import serve

        serve(vla_eval_server(served), host="127.0.0.1", port=args.port)
    else:
        WebsocketPolicyServer(served, host="127.0.0.1", port=args.port).serve_forever()


if __name__ == "__main__":
    main()
