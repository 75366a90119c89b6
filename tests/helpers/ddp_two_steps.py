"""One process of a two-process CPU (gloo) DDP run of activearena_oft, launched by
test_oft_policy.py with `torchrun --nproc_per_node=2 tests/helpers/ddp_two_steps.py VLM ROOT REPO OUT`:
lerobot-train's Accelerator setup, two steps on this rank's share of the data; the main process saves
every rank's parameter sums and losses to OUT; the run ends as lerobot-train's does."""

import os
import sys

import torch
from accelerate import Accelerator
from accelerate.utils import DistributedDataParallelKwargs
from lerobot.datasets.dataset_metadata import LeRobotDatasetMetadata
from lerobot.datasets.factory import resolve_delta_timestamps
from lerobot.datasets.lerobot_dataset import LeRobotDataset
from lerobot.policies.factory import make_policy, make_pre_post_processors

from lerobot_activearena.policies.activearena_oft.configuration_activearena_oft import ActiveArenaOFTConfig


def main(vlm: str, root: str, repo: str, out: str) -> None:
    acc = Accelerator(
        step_scheduler_with_optimizer=False,
        cpu=True,
        kwargs_handlers=[DistributedDataParallelKwargs(find_unused_parameters=True)],
    )
    meta = LeRobotDatasetMetadata(repo, root=root)
    cfg = ActiveArenaOFTConfig(
        vlm_path=vlm, device="cpu", state_hidden=32, memory="chunk", history=2, think="subtask"
    )
    torch.manual_seed(0)
    policy = make_policy(cfg, ds_meta=meta)
    pre, _ = make_pre_post_processors(cfg, dataset_stats=meta.stats)
    ds = LeRobotDataset(
        repo, root=root, video_backend="pyav", delta_timestamps=resolve_delta_timestamps(cfg, meta)
    )
    policy.train()
    before = torch.stack([p.detach().double().sum() for p in policy.parameters()])
    opt = torch.optim.AdamW(policy.get_optim_params(), betas=(0.9, 0.95), eps=1e-8, weight_decay=1e-8)
    loader = torch.utils.data.DataLoader(
        ds, batch_size=2, shuffle=True, generator=torch.Generator().manual_seed(0)
    )
    policy, opt, loader = acc.prepare(policy, opt, loader)
    losses = []
    for _, raw in zip(range(2), loader, strict=False):
        loss, _ = policy(pre(raw))
        acc.backward(loss)
        opt.step()
        opt.zero_grad()
        losses.append(float(loss.detach()))
    sums = torch.stack([p.detach().double().sum() for p in acc.unwrap_model(policy).parameters()])
    gathered = acc.gather(sums[None])
    rank_losses = acc.gather(torch.tensor([losses], dtype=torch.float64))
    if acc.is_main_process:
        torch.save({"before": before, "after": gathered, "losses": rank_losses}, out)
    # As lerobot-train ends. Then leave without tearing down the interpreter: freeing the DDP model's
    # gloo process group at exit now and then aborts or hangs the process (pytorch/pytorch#179291).
    acc.wait_for_everyone()
    acc.end_training()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(0)


if __name__ == "__main__":
    main(*sys.argv[1:5])
