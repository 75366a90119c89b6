"""LeRobot's own policy types on the benchmark: the baseline presets (``configs/policy/baselines``)
parse as lerobot-train configs with the paper's settings; ACT and diffusion, from their presets,
trained for 2 steps by LeRobot's training loop on a builder dataset (no pretrained backbone), then
evaluated by ``activearena-eval``
(``--policy.path``) and by lerobot-eval on the same seeds, with the same episode records; and
``activearena-eval --policy.type`` of a built-in type."""

import json
from pathlib import Path

import pytest
from helpers.params import BELL, DATASET_REPO
from lerobot.configs.default import EvalConfig
from lerobot.configs.eval import EvalPipelineConfig
from lerobot.configs.policies import PreTrainedConfig
from lerobot.configs.train import TrainPipelineConfig
from lerobot.scripts.lerobot_eval import eval_main as lerobot_eval_main
from lerobot.scripts.lerobot_train import train as lerobot_train

from lerobot_activearena.cli.eval import main as activearena_eval, parse_policy
from lerobot_activearena.cli.learning_curve import main as learning_curve_main
from lerobot_activearena.envs.configs import ActiveArenaEnvConfig

BASELINES = Path(__file__).resolve().parents[2] / "configs" / "policy" / "baselines"
EPISODE_LENGTH = 12  # steps per evaluation episode: enough to compare trajectories
POLICY_OPTIONS = {  # small networks: the test is about the plumbing, not the policy
    "act": [
        "--policy.pretrained_backbone_weights=null",
        "--policy.chunk_size=8",
        "--policy.n_action_steps=8",
        "--policy.dim_model=64",
        "--policy.dim_feedforward=128",
        "--policy.n_heads=2",
    ],
    "diffusion": [
        "--policy.pretrained_backbone_weights=null",
        "--policy.num_inference_steps=2",
        "--policy.horizon=8",
        "--policy.n_action_steps=4",
        "--policy.down_dims=[32,64]",
        "--policy.diffusion_step_embed_dim=32",
    ],
}


def _train(policy_type: str, dataset: Path, out: Path) -> Path:
    """The preset ``configs/policy/baselines/<type>.json`` through LeRobot's training loop (as
    ``lerobot-train --config_path``), shrunk by command-line overrides."""
    args = [
        *POLICY_OPTIONS[policy_type],
        "--policy.device=cpu",
        f"--dataset.repo_id={DATASET_REPO}",
        f"--dataset.root={dataset}",
        "--steps=2",
        "--batch_size=2",
        "--num_workers=0",
        "--save_freq=2",
        f"--output_dir={out}",
    ]
    lerobot_train(TrainPipelineConfig.from_pretrained(BASELINES / f"{policy_type}.json", cli_args=args))
    return out / "checkpoints" / "last" / "pretrained_model"


def _records(folder: Path) -> dict[int, dict]:
    recs = [json.loads(line) for f in sorted(folder.rglob("*.jsonl")) for line in f.read_text().splitlines()]
    return {r["episode"]: r for r in recs}


@pytest.mark.parametrize("policy_type", ["act", "diffusion"])
def test_lerobot_policy_trained_on_a_builder_dataset_plays_in_activearena_eval(
    policy_type, bell_count_dataset, tmp_path
):
    ckpt = _train(policy_type, bell_count_dataset, tmp_path / "train")
    run = tmp_path / "protocol"
    activearena_eval(
        [
            f"--policy.path={ckpt}",
            "--policy.device=cpu",
            f"--env.episode_length={EPISODE_LENGTH}",
            f"--tasks={BELL}",
            "--splits=id",
            "--episodes=2",
            "--videos=0",
            f"--out={run}",
        ]
    )
    info = json.loads((run / "id" / "eval_info.json").read_text())
    assert info["overall"]["n_episodes"] == 2 and info["per_task"][0]["task_id"] == BELL
    mine = {
        json.loads(line)["episode"]: json.loads(line) for line in (run / "id/episodes/records.jsonl").open()
    }

    # lerobot-eval, same checkpoint and seeds: the same episodes, step for step
    policy = PreTrainedConfig.from_pretrained(ckpt)
    policy.pretrained_path = ckpt
    policy.device = "cpu"
    out = tmp_path / "lerobot_eval"
    env = ActiveArenaEnvConfig(task=BELL, episode_length=EPISODE_LENGTH, episode_log_dir=str(out / "records"))
    cfg = EvalPipelineConfig(
        env=env, policy=policy, eval=EvalConfig(n_episodes=2, batch_size=1), output_dir=out, seed=1000
    )
    lerobot_eval_main(cfg)
    theirs = _records(out / "records")
    assert sorted(mine) == sorted(theirs) == [0, 1]
    for k in (0, 1):
        assert mine[k]["steps"] == EPISODE_LENGTH
        for key in ("scene_seed", "steps", "success", "failure_state", "view_targets"):
            assert mine[k][key] == theirs[k][key], (k, key)


def test_the_cpu_recipe_trains_act_at_96x128_and_plays_at_that_size(tmp_path):
    """``datasets_build/cpu_learning.json`` (one bell episode) -> ``act_cpu.json`` through LeRobot's
    training loop -> activearena-eval with the env rendering at the policy's 96 x 128."""
    from lerobot.datasets.lerobot_dataset import LeRobotDataset

    from lerobot_activearena.cli.build_dataset import main as build_main

    root = tmp_path / "cpu_data"
    build_main(
        ["--recipe", str(BASELINES.parents[2] / "datasets_build" / "cpu_learning.json")]
        + ["--repo-id", "local/cpu", "--root", str(root), "--tasks", BELL]
        + ["--episodes", "1", "--workers", "1"]
    )
    ds = LeRobotDataset("local/cpu", root=root)
    assert ds[0]["observation.images.head"].shape == (3, 96, 128)
    out = tmp_path / "train"
    args = [
        f"--dataset.root={root}",
        "--dataset.repo_id=local/cpu",
        "--policy.dim_model=32",  # the plumbing, not the policy
        "--policy.dim_feedforward=64",
        "--policy.n_heads=2",
        "--steps=2",
        "--batch_size=2",
        "--num_workers=0",
        "--save_freq=2",
        f"--output_dir={out}",
    ]
    lerobot_train(TrainPipelineConfig.from_pretrained(BASELINES / "act_cpu.json", cli_args=args))
    ckpt = out / "checkpoints" / "last" / "pretrained_model"
    assert PreTrainedConfig.from_pretrained(ckpt).input_features["observation.images.head"].shape == (
        3,
        96,
        128,
    )
    run = tmp_path / "protocol"
    common = [f"--policy.path={ckpt}", f"--env.episode_length={EPISODE_LENGTH}", f"--tasks={BELL}"]
    common += ["--splits=id", "--episodes=1", "--videos=1", f"--out={run}"]
    with pytest.raises(SystemExit):  # the default 384 x 512 env is refused, naming the fix
        activearena_eval(common)
    activearena_eval([*common, "--env.observation_height=96", "--env.observation_width=128"])
    rec = _records(run / "id" / "episodes")[0]
    assert rec["steps"] == EPISODE_LENGTH and rec["success"] is False

    # the learning curve of the run: one record per checkpoint, kept when the command is re-run
    curve = tmp_path / "curve"
    args = [str(out), f"--task={BELL}", "--episodes=1", f"--out={curve}"]
    args += ["--heldout-repo-id=local/cpu", f"--heldout-root={root}"]
    learning_curve_main(args)
    (rec,) = [json.loads(line) for line in (curve / "curve.jsonl").read_text().splitlines()]
    assert rec["step"] == 2 and rec["closed_loop"]["success"] == 0.0
    assert rec["closed_loop"]["episodes"] == 1 and rec["closed_loop"]["indices"] == "0-0"
    (state,) = [k for k, n in rec["closed_loop"]["failures"].items() for _ in range(n)]  # the one failure
    assert state == _records(curve / "eval_000002" / "id" / "episodes")[0]["failure_state"]
    assert rec["open_loop"]["frames"] == ds.num_frames and rec["open_loop"]["l1"] > 0
    assert (curve / "learning_curve.png").stat().st_size > 0
    stamp = (curve / "curve.jsonl").stat().st_mtime_ns
    learning_curve_main(args)
    assert (curve / "curve.jsonl").stat().st_mtime_ns == stamp
    with pytest.raises(SystemExit):  # validation episodes are never mixed into a curve of others
        learning_curve_main([*args, "--validation"])
    # choosing a checkpoint: the episodes after the protocol's 50, never the protocol's own
    val = tmp_path / "val"
    learning_curve_main([str(out), f"--task={BELL}", "--episodes=1", f"--out={val}", "--validation"])
    (rec,) = [json.loads(line) for line in (val / "curve.jsonl").read_text().splitlines()]
    assert rec["closed_loop"]["indices"] == "50-50"
    assert list(_records(val / "eval_000002" / "id" / "episodes")) == [50]


def test_built_in_policy_types_parse_by_type():
    for policy_type in ("act", "diffusion", "smolvla", "pi05"):
        cfg, path = parse_policy([f"--policy.type={policy_type}", "--policy.device=cpu"])
        assert cfg.type == policy_type and path is None


def test_baseline_presets_parse_with_the_papers_settings():
    import lerobot.policies  # noqa: F401  (registers LeRobot's policy configs, as lerobot-train does)

    presets = {p.stem: p for p in BASELINES.glob("*.json")}
    assert sorted(presets) == ["act", "act_cpu", "act_cpu_jitter", "diffusion", "fastwam", "pi05", "smolvla"]
    cfgs = {
        name: TrainPipelineConfig.from_pretrained(path, cli_args=["--dataset.root=/nonexistent"]).policy
        for name, path in presets.items()
    }
    assert all(cfg.type == name.split("_")[0] for name, cfg in cfgs.items())
    # the CPU recipe's ACT: 17 M parameters, trained from scratch (backbone at the full learning rate)
    act_cpu = cfgs["act_cpu"]
    assert (act_cpu.dim_model, act_cpu.dim_feedforward, act_cpu.n_encoder_layers, act_cpu.chunk_size) == (
        256,
        1024,
        2,
        16,
    )
    assert act_cpu.pretrained_backbone_weights is None
    assert act_cpu.optimizer_lr_backbone == act_cpu.optimizer_lr == 1e-4
    assert cfgs["act_cpu_jitter"] == act_cpu  # the same policy; only the image augmentation differs
    # pi0.5: head image + 18-D state, the two wrist slots masked, 5 flow-matching steps, from pi05_base
    pi05 = cfgs["pi05"]
    assert (pi05.empty_cameras, pi05.num_inference_steps, str(pi05.pretrained_path)) == (
        2,
        5,
        "lerobot/pi05_base",
    )
    # Fast-WAM: 32-step chunks of 18-D actions, 10 flow-matching steps at inference
    wam = cfgs["fastwam"]
    assert (wam.action_dim, wam.proprio_dim, wam.action_horizon, wam.num_inference_steps) == (18, 18, 32, 10)
    assert str(cfgs["smolvla"].pretrained_path) == "lerobot/smolvla_base"
    readme = (BASELINES.parents[1] / "README.md").read_text()
    for hub_id in ("lerobot/pi05_base", "lerobot/fastwam_base", "lerobot/smolvla_base"):
        assert hub_id in readme, f"configs/README.md should name {hub_id}"


def test_jitter_preset_changes_colours_not_geometry():
    """``act_cpu_jitter`` adds colour jitter (for the OOD split's held-out materials and light) to the
    CPU recipe's shift: through LeRobot's own ``ImageTransforms``, images keep their shape and range,
    and their colour statistics move, which the plain preset's shift alone leaves almost unchanged."""
    import torch
    from lerobot.transforms.transforms import ImageTransforms

    def transforms(name):
        cfg = TrainPipelineConfig.from_pretrained(BASELINES / f"{name}.json", cli_args=["--dataset.root=/x"])
        return ImageTransforms(cfg.dataset.image_transforms)

    torch.manual_seed(0)
    image = torch.rand(3, 96, 128) * 0.5 + 0.25
    jitter, plain = transforms("act_cpu_jitter"), transforms("act_cpu")
    jittered = [jitter(image) for _ in range(20)]
    assert all(j.shape == image.shape and j.min() >= 0.0 and j.max() <= 1.0 for j in jittered)
    channel_means = torch.stack([j.mean(dim=(1, 2)) for j in jittered])
    plain_means = torch.stack([plain(image).mean(dim=(1, 2)) for _ in range(20)])
    assert channel_means.std(dim=0).max() > 5 * plain_means.std(dim=0).max()
