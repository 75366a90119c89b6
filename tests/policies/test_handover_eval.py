"""analysis/policies/handover_eval.py: what an inspect-and-place episode's object rests on at the end."""

from types import SimpleNamespace

import numpy as np
import pytest
from helpers.analysis_scripts import load


def _set_on(sim, scene, block, pad_name):
    import mujoco

    pad = sim.data.body(pad_name)
    top = pad.xpos + pad.xmat.reshape(3, 3)[:, 2] * scene.obj(pad_name).functional.support.top
    adr = sim.model.jnt_qposadr[sim.model.body(block.body).jntadr[0]]
    sim.data.qpos[adr : adr + 3] = top
    mujoco.mj_forward(sim.model, sim.data)


def _block_scene():
    """The script, a check_block_color scene as an env stand-in, its block and the pad it names."""
    from lerobot_activearena.sim.simulator import ActiveArenaSim
    from lerobot_activearena.tasks import get_task
    from lerobot_activearena.tasks.sampling import sample_scene

    task = get_task("check_block_color")
    scene = sample_scene(task, 3, "id")
    env = SimpleNamespace(spec_task=task, scene=scene, sim=ActiveArenaSim(scene.model, scene.info))
    block = scene.obj("gray_block")
    return (
        load("analysis/policies/handover_eval.py"),
        env,
        block,
        task.read(scene, block.attributes).destination,
    )


def test_the_end_names_the_pad_the_reading_names_another_pad_or_none():
    script, env, block, named = _block_scene()
    sim, scene = env.sim, env.scene

    row = script.where_it_rests(env)
    assert (row["rests_on"], row["destination"], row["held"]) == (None, named, False)  # on the table
    assert script.end_place(row) == "no support"
    assert set(row["offsets"]) == {"red_pad", "green_pad", "blue_pad"}
    assert min(row["offsets"].values()) > 0.05  # spawned apart from every pad
    summary = script.missed_places([row])
    assert "of the 1 on no support 0 still held" in summary
    assert f"{100 * row['offsets'][named]:.1f} cm from the named one" in summary

    _set_on(sim, scene, block, named)
    row = script.where_it_rests(env)
    assert row["rests_on"] == named and script.end_place(row) == "the named one"
    assert row["offsets"][named] < 0.005  # centred on it
    assert script.missed_places([row]) == ""

    other = next(n for n in ("red_pad", "green_pad", "blue_pad") if n != named)
    _set_on(sim, scene, block, other)
    row = script.where_it_rests(env)
    assert (row["rests_on"], row["destination"]) == (other, named)
    assert script.end_place(row) == "another support"


def test_release_watch_notes_where_the_object_was_let_go_against_the_named_destination():
    from lerobot_activearena.sim.action import TORSO_YAW
    from lerobot_activearena.tasks import predicates

    script, env, block, named = _block_scene()
    sim, scene = env.sim, env.scene

    watch = script.ReleaseWatch(env)
    watch(None)  # never held: nothing let go
    assert watch.row()["released_at"] is None
    assert script.release_angles([watch.row()]) == "; never let go"

    watch.held = True  # as if a gripper held it a step ago; now nothing does
    _set_on(sim, scene, block, named)
    watch(None)
    row = watch.row()
    assert row["destination_at"] == predicates.polar(sim.data.body(named).xpos[:2])
    assert abs(row["released_at"][1] - row["destination_at"][1]) < 1.0  # let go over the named pad
    assert not watch.held
    assert row["heading_at_release"] == pytest.approx(90.0 + np.degrees(sim.state()[TORSO_YAW]))
    far = dict(row, released_at=(0.4, row["destination_at"][1] + 30.0))
    assert script.release_angles([row, far, far]) == "; let go 30 deg round from the named one (median of 3)"
    # over pads at different angles: how the release and the torso's heading follow the named one
    turned = [
        dict(row, destination_at=(0.4, a), released_at=(0.4, a + 5.0), heading_at_release=h)
        for a, h in ((40.0, 90.0), (90.0, 80.0), (140.0, 100.0))
    ]
    assert script.release_angles(turned).endswith(
        "let go 5 deg round from the named one (median of 3), correlation with the named one's angle: "
        "release 1.00, torso heading 0.50"
    )


def test_span_watch_scores_the_decoded_decision_and_forces_the_true_one(tiny_vlm):
    from transformers import AutoTokenizer

    from lerobot_activearena.policies.activearena_vla.dataset_annotations import decision_clause

    script, env, block, named = _block_scene()
    tok = AutoTokenizer.from_pretrained(tiny_vlm)
    start, end = tok.convert_tokens_to_ids("<think>"), tok.convert_tokens_to_ids("</think>")
    reading = env.spec_task.read(env.scene, block.attributes).text
    truth = decision_clause(env.scene.params["placements"], reading, place=True, layout=True)
    other = next(f"place on the {c} pad" for c in ("red", "green", "blue") if f"the {c} pad" not in reading)
    wrong = decision_clause(env.scene.params["placements"], other, place=True, layout=True)
    decoded = {"text": wrong}

    def greedy_decode(encode_args, first, stop, *args, **kwargs):
        ids = tok(f"place the block; {decoded['text']}", add_special_tokens=False)["input_ids"]
        return [(*ids, end)], ["logits"], "first pass"

    def make_policy():
        return SimpleNamespace(
            greedy_decode=greedy_decode,
            text_tokenizer=tok,
            think_token_ids=lambda: (start, end),
            step=150,
            config=SimpleNamespace(decision_place=True, decision_layout=True, decision_where=False),
        )

    policy = make_policy()
    watch = script.SpanWatch(policy, env, force=True)
    assert policy.greedy_decode is watch  # the policy now decodes through the watch
    tokens, logits, first = policy.greedy_decode(None, [start], end, 48)
    assert tok.decode(tokens[0]) == f"place the block; {truth}</think>"  # the subtask kept, the rest true
    assert (logits, first) == (["logits"], "first pass")
    policy.step, decoded["text"] = 170, truth
    policy.greedy_decode(None, [start], end, 48)
    assert watch.last == f"{truth} -> forced: {truth}"
    assert watch.right_after(160) == (1, 1)  # only the decision at step 170 counts, and it was right
    assert watch.decisions == []

    plain = script.SpanWatch(make_policy(), env, force=False)
    decoded["text"] = wrong
    tokens, _, _ = plain(None, [start], end, 48)
    assert tok.decode(tokens[0]) == f"place the block; {wrong}</think>"  # decoded: left as it was
    assert plain.right_after(0) == (0, 1)
    assert truth != wrong


def test_span_watch_with_decision_where_forces_the_pick_place_and_scores_the_place_apart(tiny_vlm):
    """decision_where: a span that names the pick subtask is forced to where the block lies, one after
    the reading to the decision with its pad's place; the decision counts as right whatever cm and deg
    it gives, and how far those are off is kept apart."""
    from transformers import AutoTokenizer

    from lerobot_activearena.policies.activearena_vla.dataset_annotations import decision_clause, pick_clause

    script, env, block, named = _block_scene()
    placements = env.scene.params["placements"]
    tok = AutoTokenizer.from_pretrained(tiny_vlm)
    start, end = tok.convert_tokens_to_ids("<think>"), tok.convert_tokens_to_ids("</think>")
    reading = env.spec_task.read(env.scene, block.attributes).text
    pick_text = env.spec_task.subtasks[0].text
    decoded = {"text": f"{pick_text}; gray block at 1 cm, 2 deg"}

    def greedy_decode(encode_args, first, stop, *args, **kwargs):
        return [(*tok(decoded["text"], add_special_tokens=False)["input_ids"], end)], [], None

    policy = SimpleNamespace(
        greedy_decode=greedy_decode,
        text_tokenizer=tok,
        think_token_ids=lambda: (start, end),
        step=10,
        config=SimpleNamespace(decision_place=True, decision_layout=False, decision_where=True),
    )
    watch = script.SpanWatch(policy, env, force=True)
    tokens, _, _ = policy.greedy_decode(None, [start], end, 64)
    block_at = pick_clause(placements, "gray_block")
    assert tok.decode(tokens[0]) == f"{pick_text}; {block_at}</think>"
    truth = decision_clause(placements, reading, place=True, where_=True)
    policy.step, decoded["text"] = 120, f"place the block; {script.WHERE_TAIL.sub('', truth)} at 3 cm, 4 deg"
    policy.greedy_decode(None, [start], end, 64)
    pad = next(p for p in placements if p["name"] == named)
    assert watch.right_after(0) == (2, 2)  # both name the right object, whatever place they give
    (t_pick, block_name, pick_cm, pick_deg), (t_pad, pad_name, pad_cm, pad_deg) = watch.where_after(0)
    assert (t_pick, t_pad) == (10, 120)
    assert (block_name, pad_name) == ("gray_block", named)
    block_row = next(p for p in placements if p["name"] == "gray_block")
    assert pick_cm == pytest.approx(100 * block_row["r"] - 1) and pick_deg == pytest.approx(
        block_row["angle"] - 2
    )
    assert pad_cm == pytest.approx(100 * pad["r"] - 3) and pad_deg == pytest.approx(pad["angle"] - 4)
    assert script.where_error("place the block", placements) is None


def test_span_from_forces_the_readers_decision_and_feeds_it_every_observation_first(tiny_vlm):
    """--span-from: the acting policy's span keeps its subtask and takes the decision the reader decoded
    at the same step (not the truth); a decision the reader did not make at that step is counted. The
    wrapped preprocessor gives the reader each observation (a copy) before the policy's own, and the
    policy's reset and replan reach the reader too."""
    from transformers import AutoTokenizer

    from lerobot_activearena.policies.activearena_vla.dataset_annotations import decision_clause

    script, env, block, named = _block_scene()
    tok = AutoTokenizer.from_pretrained(tiny_vlm)
    start, end = tok.convert_tokens_to_ids("<think>"), tok.convert_tokens_to_ids("</think>")
    placements = env.scene.params["placements"]
    truth = decision_clause(placements, env.spec_task.read(env.scene, block.attributes).text, place=True)
    other = next(c for c in ("red", "green", "blue") if f"{c}_pad" != named)
    wrong = decision_clause(placements, f"place on the {other} pad", place=True)
    calls = []

    def make_policy(text, subtask, steps=16):
        def greedy_decode(encode_args, first, stop, *args, **kwargs):
            return [(*tok(f"{subtask}; {text}", add_special_tokens=False)["input_ids"], end)], [], None

        policy = SimpleNamespace(
            greedy_decode=greedy_decode,
            text_tokenizer=tok,
            think_token_ids=lambda: (start, end),
            step=40,
            config=SimpleNamespace(
                decision_place=True, decision_layout=False, decision_where=False, n_action_steps=steps
            ),
            reset=lambda: calls.append(f"{subtask} reset"),
            replan=lambda: calls.append(f"{subtask} replan"),
        )
        policy.select_action = lambda batch: calls.append((subtask, batch))
        return policy

    reader, actor = make_policy(wrong, "reader's subtask"), make_policy(truth, "place the block")
    read = script.SpanWatch(reader, env, force=False)
    acts = script.SpanWatch(actor, env, force=True, source=read)
    reader.greedy_decode(None, [start], end, 48)
    tokens, _, _ = actor.greedy_decode(None, [start], end, 48)
    assert tok.decode(tokens[0]) == f"place the block; {wrong}</think>"  # the reader's, not the truth
    assert (read.right_after(0), acts.right_after(0), acts.unmatched) == ((0, 1), (1, 1), 0)
    actor.step = 56  # the reader did not decide at step 56: its last span is used, and counted
    actor.greedy_decode(None, [start], end, 48)
    assert acts.unmatched == 1

    pre = script.SpanReader(actor, lambda obs: ("actor", obs), reader, lambda obs: ("reader", obs))
    obs = {"observation.state": [1.0]}
    assert pre(obs) == ("actor", obs)
    (who, (tag, seen)) = calls[-1]
    assert (who, tag) == ("reader's subtask", "reader") and seen == obs and seen is not obs
    actor.reset()
    actor.replan()
    assert calls[-4:] == ["reader's subtask reset", "place the block reset"] + [
        "reader's subtask replan",
        "place the block replan",
    ]
    with pytest.raises(ValueError, match="--n-action-steps"):
        script.SpanReader(make_policy(truth, "a", steps=8), None, reader, None)


def test_the_reach_line_counts_headings_off_and_the_misses_they_cost():
    """From the per-episode rows: the reach's correlations, and how many first chunks left the torso
    further off the expert's heading than the demonstrations' off-centre turns, how many were still
    that far off where the hand came nearest and how far those missed."""
    script = load("analysis/policies/handover_eval.py")
    rows = []
    for k, off in enumerate([1.0, -2.0, 15.0, 20.0, 3.0]):
        angle = np.radians(50.0 + 20 * k)
        start = [0.38 * np.cos(angle), 0.38 * np.sin(angle)]
        rows.append(
            {
                "object_start_xy": start,
                "hand_nearest_xy": [start[0] + 0.01 * k, start[1]],
                "reach_stage": "lift" if abs(off) < 5 else "reach",
                "reach_nearest_cm": 2.0 if abs(off) < 5 else 10.0 + k,
                "heading_off_after_first_chunk_deg": off,
                "heading_off_at_nearest_deg": off if k != 3 else 1.0,  # episode 3 turned back
            }
        )
    line = script.reach_line(rows)
    assert "over 6.9 in 2 of 5" in line
    assert "1 still that far off where the hand came nearest, missing by 12.0 cm" in line
    assert "furthest stage {'lift': 3, 'reach': 2}" in line
    assert script.reach_line(rows[:2]) == ""  # too few episodes to correlate


def test_records_name_a_training_checkpoint_by_run_and_step(tmp_path):
    """A lerobot-train checkpoint is named RUN/STEP in the records; any other path as given."""
    script = load("analysis/policies/handover_eval.py")
    ckpt = tmp_path / "outputs/train/block_run/checkpoints/001500/pretrained_model"
    assert script.checkpoint_label(ckpt) == "block_run/001500"
    assert script.checkpoint_label(tmp_path / "model") == str(tmp_path / "model")


def test_lifted_choices_split_a_wrong_decision_from_a_missed_set_down():
    script = load("analysis/policies/handover_eval.py")
    offsets = {"red_pad": 0.3, "green_pad": 0.2, "blue_pad": 0.4}

    def row(stage, named, rests_on):
        where = [[0, "gray_block", 1.0, 4.0]] + [[16 * (i + 1), n, 2.0, 8.0] for i, n in enumerate(named)]
        return {
            "reach_stage": stage,
            "span_where_errors": where,
            "offsets": offsets,
            "destination": "red_pad",
            "rests_on": rests_on,
        }

    rows = [
        row("reach", ["red_pad"], None),  # never lifted: not counted
        row("lift", ["blue_pad", "red_pad"], "red_pad"),  # changed its mind to the right pad, placed
        row("lift", ["red_pad"], None),  # right pad, set down off it
        row("lift", ["red_pad", "green_pad"], "green_pad"),  # last named the wrong pad
    ]
    assert script.lifted_choices(rows) == (
        "    of the 3 that lifted, the span last named the destination in 2, 1 of those set down on it"
    )
    assert script.lifted_choices(rows[:1]) == ""  # nothing lifted
    assert script.lifted_choices([dict(rows[1], span_where_errors=[])]) == ""  # no span to read


def test_the_reach_watch_tells_a_grasp_on_nothing_from_one_on_the_object_and_counts_retries():
    """Gripper states after the handover: each shut is on nothing when the gripper comes below
    GRIP_EMPTY, with the tool centre's distance from the object then; retry_line counts the episodes
    that shut again near the object after one on nothing, and their lifts."""
    script = load("analysis/policies/handover_eval.py")
    from lerobot_activearena.sim.action import LEFT_GRIPPER, RIGHT_GRIPPER

    watch = script.ReachWatch(env=None, handover=0, expert_states=[], chunk=16)
    state = np.zeros(max(LEFT_GRIPPER, RIGHT_GRIPPER) + 1)
    steps = [(1.0, 0.3), (0.5, 0.05), (0.05, 0.05), (0.6, 0.1), (1.0, 0.1), (0.6, 0.02), (0.42, 0.02)]
    for right, away in steps:  # shut on nothing 5 cm off, opened, shut on the block 2 cm off
        state[LEFT_GRIPPER], state[RIGHT_GRIPPER] = 1.0, right
        watch._grippers(state, [0.5, away])
    assert watch.closes == [[True, 5.0], [False, 2.0]]
    rows = [
        {"shuts": [[True, 5.0], [False, 2.0]], "reach_stage": "lift"},
        {"shuts": [[True, 5.0]], "reach_stage": "grasp"},  # shut on nothing, never again
        {"shuts": [[True, 5.0], [True, 40.0]], "reach_stage": "grasp"},  # shut again far off: no retry
        {"shuts": [[False, 2.0]], "reach_stage": "lift"},
        {"shuts": [[True, 8.0], [True, 3.0]], "reach_stage": "grasp"},
    ]
    assert script.retry_line(rows) == (
        "    a gripper shut on nothing in 4; in 2 of those one shut again within 6 cm of the object, "
        "1 of which lifted it"
    )
    assert script.retry_line(rows[3:4]) == ""
