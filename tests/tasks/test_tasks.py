"""Task registry, scene sampling (ID/OOD, determinism, design principles) and success checks."""

import math
from pathlib import Path

import numpy as np
import pytest

from lerobot_activearena.sim.assets import ASSETS
from lerobot_activearena.tasks import CATEGORIES, TASKS, get_task, task_names
from lerobot_activearena.tasks.base import TaskScene
from lerobot_activearena.tasks.draft import SamplingError, SceneDraft, id_clutter_pool
from lerobot_activearena.tasks.sampling import derived_rng, principle_violations, sample_scene

FIRST_FIVE = {
    "click_bell_rotate_view": ("SS", "Press the bell's top center using the left arm."),
    "place_empty_cup_rotate_view": ("SL", "Place the empty cup on the coaster."),
    "blocks_ranking_rgb_rotate_view": ("ML", "Arrange the red, green, and blue blocks from left to right."),
    "count_target_press_button": ("MD", "Count the target blocks and press the matching button."),
    "check_block_color": ("IA", "Inspect the gray block's hidden color and place it on the matching pad."),
}


def test_registry_has_the_paper_tasks_with_categories_and_instructions():
    task_names()  # loads the task modules
    for name, (cat, instr) in FIRST_FIVE.items():
        t = get_task(name)
        assert (t.category, t.instruction) == (cat, instr)
        assert [s.id for s in t.subtasks] == list(range(1, len(t.subtasks) + 1))
    limits = {n: get_task(n).max_episode_steps for n in FIRST_FIVE}  # the paper's release
    assert limits == {
        "click_bell_rotate_view": 137,
        "place_empty_cup_rotate_view": 199,
        "blocks_ranking_rgb_rotate_view": 351,
        "count_target_press_button": 152,
        "check_block_color": 296,
    }


def test_task_selectors():
    assert "click_bell_rotate_view" in task_names("SS") and all(
        get_task(n).category == "SS" for n in task_names("SS")
    )
    assert set(task_names("all")) == set(TASKS)
    assert task_names("check_block_color,click_bell_rotate_view,IA")[:2] == [
        "check_block_color",
        "click_bell_rotate_view",
    ]
    with pytest.raises(ValueError, match="unknown task selector 'nope'"):
        task_names("nope")
    with pytest.raises(ValueError, match="unknown ActiveArena task"):
        get_task("click_bell")


def _layout(scene):
    return {
        o.name: np.round(np.asarray(scene.model.body(o.body).pos), 6).tolist()
        for o in scene.info.objects + scene.info.clutter
    }


def test_same_seed_same_scene_and_different_seed_different_scene():
    task = get_task("place_empty_cup_rotate_view")
    a, b, c = sample_scene(task, 5, "id"), sample_scene(task, 5, "id"), sample_scene(task, 6, "id")
    assert _layout(a) == _layout(b) and a.params == b.params and a.attempt == b.attempt
    assert _layout(a) != _layout(c)


def test_id_clutter_uses_only_distractors_and_ood_changes_the_look_and_density():
    task = get_task("click_bell_rotate_view")
    n_id, n_ood, looks_id, looks_ood = [], [], [], []
    for seed in range(6):
        sid, sood = sample_scene(task, seed, "id"), sample_scene(task, seed, "ood")
        assert all(ASSETS[o.category].role == "distractor" for o in sid.info.clutter)
        families = [ASSETS[o.category].family for o in sood.info.clutter + sood.info.objects]
        assert len(families) == len(set(families)), "OOD clutter repeats a family already in the scene"
        n_id.append(len(sid.info.clutter))
        n_ood.append(len(sood.info.clutter))
        looks_id.append(_look(sid))
        looks_ood.append(_look(sood))
    assert np.mean(n_ood) > np.mean(n_id)
    assert len({lk[0] for lk in looks_id}) == 1, "ID scenes share one light"
    assert len(set(looks_id)) < len(looks_id), "ID scenes draw from a small fixed set of materials"
    assert len(set(looks_ood)) == len(looks_ood), "OOD looks must vary per seed"
    assert not {lk[0] for lk in looks_ood} & {lk[0] for lk in looks_id}


def _look(scene) -> tuple[bytes, bytes]:
    """(key light, surface textures) of a compiled scene, as bytes."""
    m = scene.model
    light = m.light("key_light")
    lighting = np.concatenate([np.ravel(light.diffuse), np.ravel(light.dir), m.vis.headlight.ambient])
    textures = b"".join(
        m.tex_data[m.tex_adr[m.tex(name).id] : m.tex_adr[m.tex(name).id] + 3 * 64].tobytes()
        for name in ("table", "floor", "wall")
    )
    return np.round(lighting, 6).tobytes(), textures


def test_principle_check_rejects_a_bell_in_plain_view():
    task = get_task("click_bell_rotate_view")
    draft = SceneDraft("id", derived_rng(task.name, 0, "id", 0))
    draft.place("bell", "bell", "bell", r=0.5, angle=90.0)
    model, info = draft.builder.compile()
    scene = TaskScene(task.name, 0, "id", 0, model, info, ["bell"], ["bell"], search_targets=[0])
    assert principle_violations(task, scene) == ["initial view already shows every task-relevant object"]


def test_check_block_color_patch_faces_away_at_reset():
    task = get_task("check_block_color")
    for seed in range(3):
        scene = sample_scene(task, seed, "id")
        assert task.information_hidden_at_start(scene)
        info = scene.info.objects[scene.objects.index("gray_block")]
        yaw = math.atan2(*np.asarray(scene.model.body("gray_block").quat)[[3, 0]]) * 2
        pos = scene.model.body("gray_block").pos
        outward = math.atan2(pos[1], pos[0])
        assert abs((yaw - outward + math.pi) % (2 * math.pi) - math.pi) < 0.3
        assert info.attributes["patch_color"] == scene.params["patch_color"]


def test_principle_check_rejects_an_object_out_of_reach():
    task = get_task("click_bell_rotate_view")
    draft = SceneDraft("id", derived_rng(task.name, 0, "id", 0))
    draft.place(
        "bell", "bell", "bell", r=0.95, angle=30.0, arms=("left",)
    )  # hidden, but far beyond the left arm
    model, info = draft.builder.compile()
    scene = TaskScene(
        task.name, 0, "id", 0, model, info, ["bell"], ["bell"], search_targets=[0], reach={"bell": ("left",)}
    )
    assert principle_violations(task, scene) == ["bell is out of reach of the left arm"]


def test_hidden_objects_go_to_both_sides_out_of_the_home_view():
    """Initially hidden task objects land left and right of the torso heading, never in view."""
    from lerobot_activearena.tasks.draft import in_home_view

    task = get_task("click_bell_rotate_view")
    sides = set()
    for seed in range(12):
        scene = sample_scene(task, seed, "id")
        (p,) = [q for q in scene.params["placements"] if q["name"] == "bell"]
        assert p["hidden"] and abs(p["angle"] - 90.0) >= 38.5
        assert not in_home_view(scene.model.body("bell").pos[:2], 0.06)
        sides.add("left" if p["angle"] > 90 else "right")
    assert sides == {"left", "right"}


def test_home_view_is_symmetric_about_the_torso_heading():
    from lerobot_activearena.tasks.draft import in_home_view

    for r in (0.35, 0.45, 0.7):
        for off in (10.0, 30.0, 45.0, 60.0):
            a, b = np.radians(90 + off), np.radians(90 - off)
            assert in_home_view((r * np.cos(a), r * np.sin(a)), 0.0) == in_home_view(
                (r * np.cos(b), r * np.sin(b)), 0.0
            )


def test_task_modules_are_discovered_without_a_list():
    import pkgutil

    from lerobot_activearena.tasks import inventory

    modules = {m.name for m in pkgutil.iter_modules(inventory.__path__) if not m.name.startswith("_")}
    assert modules == set(task_names("all"))


def test_readme_task_table_is_the_registry():
    """The README's task table lists exactly the registered tasks, each with its category, step
    limit and instruction (the paper's sentence), in category order."""
    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text()
    rows = [line for line in readme.splitlines() if line.startswith("| `") and line.count("|") == 5]
    table = {}
    for line in rows:
        name, cat, limit, instruction = (c.strip() for c in line.strip("|").split("|"))
        table[name.strip("`")] = (cat, int(limit), instruction)
    names = task_names("all")
    assert sorted(table) == sorted(names), set(table) ^ set(names)
    for name in names:
        t = get_task(name)
        cat, limit, instruction = table[name]
        assert (cat, limit) == (t.category, t.max_episode_steps), name
        assert instruction.startswith(t.instruction), (name, instruction)
    order = [list(CATEGORIES).index(table[n][0]) for n in [r.split("`")[1] for r in rows]]
    assert order == sorted(order), "README rows are grouped by category (SS, SL, ML, MD, IA)"


def test_templated_instructions_name_the_episode_values():
    """Every templated task fills its sentence from the scene it sampled (the stapler's mat colour
    is the mat's), the sentence varies across seeds, and its paper sentence is one instance."""
    templated = [n for n in task_names("all") if get_task(n).instruction_template is not None]
    assert "move_stapler_pad_rotate_view" in templated
    for name in templated:
        task = get_task(name)
        seen = set()
        for seed in range(6):
            scene = sample_scene(task, seed, "id")
            assert scene.instruction == task.instruction_for(scene.params)
            for key, values in task.instruction_values.items():
                assert scene.params[key] in values and scene.params[key] in scene.instruction
            seen.add(scene.instruction)
        assert len(seen) > 1, f"{name}: six seeds gave one instruction {seen}"
    stapler = sample_scene(get_task("move_stapler_pad_rotate_view"), 3, "id")
    assert stapler.obj("mat").attributes["color_name"] == stapler.params["mat_color"]


def test_an_instruction_template_must_have_the_paper_sentence_as_an_instance():
    from lerobot_activearena.tasks.base import check_instruction_template

    class Bad:
        instruction = "Move the stapler onto the black mat."
        instruction_template = "Move the stapler onto the {mat_color} pad."
        instruction_values = {"mat_color": ("black", "red")}

    with pytest.raises(TypeError, match="not an instance"):
        check_instruction_template(Bad)
    Bad.instruction_template = "Move the stapler onto the {color} mat."
    with pytest.raises(TypeError, match="fields"):
        check_instruction_template(Bad)
    Bad.instruction_template, Bad.instruction_values = "Move the stapler onto the {c} mat.", {"c": ("black",)}
    check_instruction_template(Bad)  # the paper's sentence is the instance c = black


def test_docs_tables_cover_the_registry():
    """docs/tasks.md's task table (name, category, step limit), docs/eval.md's validity summary
    and docs/tasks.md's expert table (both splits) list exactly the registered tasks."""
    import re

    docs = Path(__file__).resolve().parents[2] / "docs"
    tasks_md, eval_md = (docs / "tasks.md").read_text(), (docs / "eval.md").read_text()
    rows = dict(re.findall(r"^\| `(\w+)` \((\w\w, \d+)\) \|", tasks_md, re.M))
    names = task_names("all")
    assert sorted(rows) == sorted(names), set(rows) ^ set(names)
    for name in names:
        t = get_task(name)
        assert rows[name] == f"{t.category}, {t.max_episode_steps}", name
    summary = set(re.findall(r"^\| (\w+) \| \d+/50", eval_md, re.M))
    assert summary == set(names), summary ^ set(names)
    expert = set(re.findall(r"^\| (\w+) \| (id|ood) \| \d+/\d+ \(", tasks_md, re.M))
    assert expert == {(n, s) for n in names for s in ("id", "ood")}, expert ^ {
        (n, s) for n in names for s in ("id", "ood")
    }


def test_id_clutter_never_uses_a_category_that_some_task_uses():
    """Over every task's scenes: what a task places is a task category, and ID clutter is drawn from
    distractors whose family no task category shares (the paper's restricted ID pool)."""
    task_families = {ASSETS[c].family for c in ASSETS if ASSETS[c].role == "task"}
    pool = set(id_clutter_pool())
    assert pool and not {ASSETS[c].family for c in pool} & task_families
    placed_by_tasks = set()
    for name in task_names("all"):
        task = get_task(name)
        for seed in range(12):
            draft = SceneDraft("id", derived_rng(name, seed, "id", 0), task.workspace)
            try:
                task.layout(draft)
            except SamplingError:
                continue
            draft.add_clutter()
            placed = {o.category for o in draft.builder.info.objects}
            assert all(ASSETS[c].role == "task" for c in placed), (
                f"{name} places a non-task category: {placed}"
            )
            clutter = {o.category for o in draft.builder.info.clutter}
            assert clutter <= pool, f"{name} seed {seed}: ID clutter {clutter - pool} is not in the ID pool"
            placed_by_tasks |= placed
    assert {"toy_car", "mouse", "shoe", "bell"} <= placed_by_tasks
