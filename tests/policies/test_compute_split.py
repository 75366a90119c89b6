"""analysis/policies/compute_split.py: forward FLOPs per sample by module, and the frames the vision
tower encodes, for ACT's CPU preset and the small VLA presets."""

from helpers.analysis_scripts import ROOT, load
from helpers.params import DATASET_REPO

from lerobot_activearena.policies.activearena_vla.tiny_vlm import make_tiny_vlm

compute_split = load("analysis/policies/compute_split.py")


def test_flops_split_by_module_and_frames_counted(tmp_path, tiny_vlm, bell_count_dataset):
    act = compute_split.policy_config(str(ROOT / compute_split.ACT))
    counts, frames = compute_split.forward_flops(act, bell_count_dataset, DATASET_REPO, depth=1)
    assert frames == 0 and counts["ACT"] == counts["Global"] > 1e8  # the ResNet18 alone is ~0.9 GFLOP

    free = compute_split.policy_config(str(ROOT / "configs/policy/small/oft_subtask_no_0_ws.json"))
    chunk = compute_split.policy_config(str(ROOT / "configs/policy/small/oft_subtask_action_12_ws.json"))
    wide_vlm = make_tiny_vlm(tmp_path / "wide", vision_hidden=128, vision_depth=3)
    per_frame = {}
    for name, cfg, path in (("free", free, tiny_vlm), ("chunk", chunk, tiny_vlm), ("wide", free, wide_vlm)):
        cfg.vlm_path = str(path)
        counts, frames = compute_split.forward_flops(cfg, bell_count_dataset, DATASET_REPO, depth=1)
        assert 0 < compute_split.vision_flops(counts) < counts["Global"]
        per_frame[name] = (compute_split.vision_flops(counts) / frames, frames)
    assert per_frame["free"][1] == 1 and per_frame["chunk"][1] > 1  # mid-episode: some memory frames
    assert abs(per_frame["chunk"][0] / per_frame["free"][0] - 1) < 0.01  # the same tower per frame
    assert per_frame["wide"][0] > 3 * per_frame["free"][0]
