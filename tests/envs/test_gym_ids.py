"""Plain gymnasium: every task is ``gym.make("ActiveArena/<task>-v0", ...)`` after importing the
package (or through gymnasium's ``module:ID`` syntax), with its step limit, and passes gymnasium's
own ``check_env``."""

from __future__ import annotations

import subprocess
import sys
import warnings

import gymnasium as gym
import pytest
from gymnasium.utils.env_checker import check_env

import lerobot_activearena  # noqa: F401  (registers the IDs)
from lerobot_activearena.envs.gym_ids import STEP_LIMITS, gym_id
from lerobot_activearena.tasks import get_task, task_names


def test_every_task_has_an_id_with_its_step_limit():
    ids = {s for s in gym.registry if s.startswith("ActiveArena/")}
    assert ids == {gym_id(t) for t in task_names("all")}
    for task in task_names("all"):
        assert gym.spec(gym_id(task)).max_episode_steps == get_task(task).max_episode_steps


def test_the_static_table_is_the_task_registry():
    """The IDs are registered from a table so that importing the package stays cheap; it must
    name every task with its step limit."""
    assert {t: get_task(t).max_episode_steps for t in task_names("all")} == STEP_LIMITS


def _python(code: str) -> subprocess.CompletedProcess:
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    return out


def test_importing_the_package_loads_no_task_simulator_or_ik():
    out = _python(
        "import sys, lerobot_activearena, gymnasium as gym; "
        "heavy = ('mujoco', 'mink', 'torch', 'lerobot', 'lerobot_activearena.tasks', 'lerobot_activearena.sim.scene'); "
        "print(sorted(m for m in heavy if m in sys.modules), "
        "sum(s.startswith('ActiveArena/') for s in gym.registry))"
    )
    assert out.stdout.split() == ["[]", str(len(STEP_LIMITS))]


def test_gymnasium_first_then_the_package_runs_an_episode_without_a_warning():
    """A gymnasium user's normal order (gymnasium loads numpy before the package)."""
    out = _python(
        "import gymnasium as gym; import lerobot_activearena; "
        "env = gym.make('ActiveArena/click_bell_rotate_view-v0'); env.reset(seed=0); "
        "env.step(env.unwrapped.sim.home_action()); env.close(); print('ok')"
    )
    assert out.stdout.split()[-1] == "ok"
    assert "warn" not in out.stderr.lower(), out.stderr[-2000:]


def _one_task_per_workspace() -> list[str]:
    """The env class is one for all tasks and their spaces are the same; what differs is the scene
    and its workspace. Every ID resolves (above) and every task resets and steps in
    test_task_contract.py, so the full checker runs once per workspace (it resets ~8 times)."""
    first: dict[str, str] = {}
    for t in task_names("all"):
        first.setdefault(get_task(t).workspace, t)
    return sorted(first.values())


@pytest.mark.parametrize("task", _one_task_per_workspace())
def test_check_env_passes_through_gym_make(task):
    env = gym.make(gym_id(task), split="ood", render_mode="rgb_array")
    try:
        with warnings.catch_warnings():
            # gymnasium's advice, not API errors: our actions are joint targets in radians and the
            # state is unbounded joint positions (LeRobot's convention), kept as they are.
            warnings.filterwarnings("error", module="gymnasium")
            warnings.filterwarnings("ignore", message=".*(symmetric and normalized|infinity)")
            check_env(env.unwrapped)
        obs, info = env.reset(seed=3)
        assert env.unwrapped.split == "ood" and info["scene_seed"] == 3
        assert obs["pixels"]["head"].shape == (*env.unwrapped.render().shape[:2], 3)
    finally:
        env.close()


def test_the_step_limit_truncates_through_gym_make():
    env = gym.make(gym_id("click_bell_rotate_view"), max_episode_steps=3)
    env.reset(seed=0)
    home = env.unwrapped.sim.home_action()
    results = [env.step(home) for _ in range(3)]
    assert [r[3] for r in results] == [False, False, True]  # truncated on the limit's step
    assert not any(r[2] for r in results)
    env.close()


def test_bad_arguments_name_the_problem():
    with pytest.raises(ValueError, match="split"):
        gym.make(gym_id("click_bell_rotate_view"), split="test")
    with pytest.raises(gym.error.NameNotFound):
        gym.make("ActiveArena/no_such_task-v0")


def test_module_id_syntax_imports_the_package():
    code = (
        "import gymnasium as gym, sys; "
        "env = gym.make('lerobot_activearena:ActiveArena/click_bell_rotate_view-v0'); "
        "obs, _ = env.reset(seed=1); print(env.spec.max_episode_steps, obs['agent_pos'].shape)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split()[-2:] == ["137", "(18,)"], out.stderr[-2000:]
