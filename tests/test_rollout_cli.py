import json

import av

from lerobot_activearena.cli.rollout import main


def test_rollout_writes_video_and_annotations(tmp_path, capsys):
    main(["--out", str(tmp_path), "--seed", "1", "--n-objects", "6"])
    lines = (tmp_path / "annotations.jsonl").read_text().splitlines()
    episode = json.loads((tmp_path / "episode.json").read_text())
    assert episode["frames"] == len(lines) > 100
    assert episode["target_lift_m"] > 0.1
    first, last = json.loads(lines[0]), json.loads(lines[-1])
    assert len(first["state"]) == 18 and len(first["visible_object_mask"]) == 7
    assert set(last["discovered_object_mask"]) <= {0, 1} and sum(last["discovered_object_mask"]) >= sum(
        first["visible_object_mask"])
    with av.open(str(tmp_path / "head.mp4")) as c:
        frames = sum(1 for _ in c.decode(video=0))
        assert (c.streams.video[0].width, c.streams.video[0].height) == (512, 384)
    assert frames == len(lines)
    assert "target lifted" in capsys.readouterr().out
