"""LeRobot discovers the installed plugin with no flags (real CLIs, fresh processes)."""

import shutil
import subprocess
import sys
from pathlib import Path


def test_lerobot_eval_help_lists_activearena_env():
    exe = shutil.which("lerobot-eval", path=str(Path(sys.executable).parent)) or shutil.which("lerobot-eval")
    assert exe, "lerobot-eval is not on PATH: is lerobot installed in this environment?"
    out = subprocess.run([exe, "--help"], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    choices = next(line for line in out.stdout.splitlines() if "--env.type {" in line)
    assert "activearena" in choices
    policies = next(line for line in out.stdout.splitlines() if "--policy.type {" in line)
    assert "activearena_expert" in policies and "activearena_oft" in policies


def test_plugin_registers_env_config_through_lerobot_discovery():
    code = (
        "from lerobot.utils.import_utils import register_third_party_plugins\n"
        "from lerobot.envs.configs import EnvConfig\n"
        "assert 'activearena' not in EnvConfig.get_known_choices()\n"
        "register_third_party_plugins()\n"
        "cfg = EnvConfig.get_choice_class('activearena')()\n"
        "print(cfg.type, cfg.fps, sorted(cfg.features_map.values()))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.split()[0:2] == ["activearena", "15"]
    assert "observation.images.head" in out.stdout and "observation.state" in out.stdout
