"""analysis/policies/handover_eval.py: what an inspect-and-place episode's object rests on at the end."""

from types import SimpleNamespace

from helpers.analysis_scripts import load


def _set_on(sim, scene, block, pad_name):
    import mujoco

    pad = sim.data.body(pad_name)
    top = pad.xpos + pad.xmat.reshape(3, 3)[:, 2] * scene.obj(pad_name).functional.support.top
    adr = sim.model.jnt_qposadr[sim.model.body(block.body).jntadr[0]]
    sim.data.qpos[adr : adr + 3] = top
    mujoco.mj_forward(sim.model, sim.data)


def test_the_end_names_the_pad_the_reading_names_another_pad_or_none():
    from lerobot_activearena.sim.simulator import ActiveArenaSim
    from lerobot_activearena.tasks import get_task
    from lerobot_activearena.tasks.sampling import sample_scene

    script = load("analysis/policies/handover_eval.py")
    task = get_task("check_block_color")
    scene = sample_scene(task, 3, "id")
    sim = ActiveArenaSim(scene.model, scene.info)
    env = SimpleNamespace(spec_task=task, scene=scene, sim=sim)
    block = scene.obj("gray_block")
    named = task.read(scene, block.attributes).destination

    row = script.where_it_rests(env)
    assert row == {"rests_on": None, "destination": named}  # spawned on the table
    assert script.end_place(row) == "no support"

    _set_on(sim, scene, block, named)
    row = script.where_it_rests(env)
    assert row["rests_on"] == named and script.end_place(row) == "the named one"

    other = next(n for n in ("red_pad", "green_pad", "blue_pad") if n != named)
    _set_on(sim, scene, block, other)
    row = script.where_it_rests(env)
    assert row == {"rests_on": other, "destination": named}
    assert script.end_place(row) == "another support"
