"""Gymnasium IDs for plain-gymnasium users: every task is

    gym.make("ActiveArena/<task>-v0", split="id" | "ood", fixed_view=False, render_mode="rgb_array")

with the task's step limit (``env.spec.max_episode_steps``), after ``import lerobot_activearena``
(which calls ``register_gym_envs``) or through gymnasium's ``"lerobot_activearena:ActiveArena/<task>-v0"``.
``reset(seed=s)`` plays scene seed ``s``; the evaluation protocol's manifest seeds are
``use_manifest=True`` (as ``lerobot-eval --env.type=activearena`` plays them).

The IDs come from a static table, so registering them imports neither the tasks nor MuJoCo nor mink
(``tests/envs/test_gym_ids.py`` holds the table against the task registry).
"""

from __future__ import annotations

import gymnasium as gym

NAMESPACE = "ActiveArena"
ENTRY_POINT = "lerobot_activearena.envs.gym_env:ActiveArenaEnv"

# task -> the release's step limit (Task.max_episode_steps)
STEP_LIMITS = {
    "beat_block_hammer_rotate_view": 185,
    "blocks_ranking_rgb_fan_double": 480,
    "blocks_ranking_rgb_rotate_view": 351,
    "blocks_ranking_size_fan_double": 463,
    "blocks_ranking_size_rotate_view": 303,
    "check_block_color": 296,
    "check_cola_color": 270,
    "check_cola_date": 280,
    "click_bell_rotate_view": 137,
    "count_color_kinds_press_button": 150,
    "count_random_object_press_button": 152,
    "count_target_press_button": 152,
    "match_backside_two_blocks": 488,
    "move_pillbottle_pad_rotate_view": 183,
    "move_stapler_pad_rotate_view": 204,
    "place_a2b_left_rotate_view": 192,
    "place_a2b_right_rotate_view": 198,
    "place_cans_plasticbox_rotate_view": 350,
    "place_container_plate_rotate_view": 205,
    "place_empty_cup_rotate_view": 199,
    "place_fan_rotate_view": 179,
    "place_mouse_pad_rotate_view": 186,
    "place_object_basket_fan_double": 299,
    "place_object_scale_rotate_view": 204,
    "place_object_stand_rotate_view": 207,
    "place_shoe_rotate_view": 170,
    "press_stapler_rotate_view": 143,
    "put_block_on_upper_easy": 307,
    "put_block_on_upper_hard": 323,
    "rank_backside_rgb_blocks": 697,
    "shake_bottle_horizontally_rotate_view": 298,
    "shake_bottle_rotate_view": 249,
    "stack_blocks_two_rotate_view": 223,
    "stamp_seal_rotate_view": 188,
    "turn_switch_rotate_view": 143,
}


def gym_id(task: str) -> str:
    return f"{NAMESPACE}/{task}-v0"


def register_gym_envs() -> list[str]:
    """Register ``ActiveArena/<task>-v0`` for every task (again: a no-op); returns the IDs."""
    ids = []
    for name, limit in STEP_LIMITS.items():
        env_id = gym_id(name)
        if env_id not in gym.registry:
            gym.register(
                id=env_id,
                entry_point=ENTRY_POINT,
                max_episode_steps=limit,
                kwargs={"task": name, "use_manifest": False},
            )
        ids.append(env_id)
    return ids
