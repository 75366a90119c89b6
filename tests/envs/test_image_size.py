"""The head image's size is an option (env, gym IDs, dataset builds): the camera renders at that
size, the intrinsics and pixel-space annotations follow it, and what the benchmark decides
(visibility, discovery, success) does not change."""

import gymnasium as gym
import numpy as np
import pytest

from lerobot_activearena.cli.build_dataset import make_plan, parser
from lerobot_activearena.datasets_build.features import IMAGE_KEY, dataset_features
from lerobot_activearena.datasets_build.recipe import load_recipe
from lerobot_activearena.envs.configs import ActiveArenaEnvConfig
from lerobot_activearena.envs.gym_env import ActiveArenaEnv
from lerobot_activearena.envs.gym_ids import gym_id
from lerobot_activearena.episodes.rollout import run_expert_episode
from lerobot_activearena.sim.head_camera import validate_head_size

TASK = "click_bell_rotate_view"


@pytest.fixture(scope="module")
def both_sizes():
    frames = {}
    for size in ((384, 512), (96, 128)):
        shapes = []
        result = run_expert_episode(
            TASK,
            0,
            "id",
            on_frame=lambda t, sim, frame, action, shapes=shapes: shapes.append(sim.render_head().shape),
            image_size=size,
        )
        frames[size] = (result, shapes)
    return frames


def test_an_expert_episode_sees_the_same_at_96x128_as_at_384x512(both_sizes):
    (big, big_shapes), (small, small_shapes) = both_sizes[(384, 512)], both_sizes[(96, 128)]
    assert big.success and small.success
    assert set(big_shapes) == {(384, 512, 3)} and set(small_shapes) == {(96, 128, 3)}
    # the same physics and the same expert: identical actions, states and length
    np.testing.assert_array_equal(big.actions, small.actions)
    np.testing.assert_array_equal(big.states, small.states)
    # 96x128 is a quarter of 384x512 in each axis, a power of two: the projection scales exactly,
    # so no frame's visibility differs (a frame that did would need an explanation here)
    differing = [
        t
        for t, (a, b) in enumerate(zip(big.frames, small.frames, strict=True))
        if any(
            not np.array_equal(a[k], b[k])
            for k in ("visible_object_mask", "discovered_object_mask", "focus_object_visible")
        )
    ]
    assert differing == []
    seen = sum(int(np.asarray(f["focus_object_visible"])) for f in big.frames)
    assert 0 < seen < len(big.frames)  # the comparison covers frames with and without the bell in view
    for a, b in zip(big.frames, small.frames, strict=True):
        np.testing.assert_allclose(
            np.asarray(b["intrinsic_cv"]), np.asarray(a["intrinsic_cv"]) * [[0.25], [0.25], [1]]
        )
        np.testing.assert_array_equal(a["extrinsic_cv"], b["extrinsic_cv"])
        np.testing.assert_allclose(a["target_uv_norm"], b["target_uv_norm"], atol=1e-6)  # normalised


def test_the_env_renders_at_the_requested_size():
    env = ActiveArenaEnv(TASK, observation_height=96, observation_width=128)
    obs, _ = env.reset(seed=1000)
    assert obs["pixels"]["head"].shape == (96, 128, 3) and env.observation_space.contains(obs)
    assert obs["pixels"]["head"].std() > 0  # a rendered image, not the black placeholder
    assert env.render().shape == (96, 128, 3)
    assert env.sim.head_camera()["intrinsic_cv"][0, 2] == 64.0
    env.close()
    small = gym.make(gym_id(TASK), observation_height=192, observation_width=256)
    assert small.observation_space["pixels"]["head"].shape == (192, 256, 3)
    small.close()


def test_larger_than_default_images_render():
    env = ActiveArenaEnv(TASK, observation_height=480, observation_width=640)
    obs, _ = env.reset(seed=1000)
    assert obs["pixels"]["head"].shape == (480, 640, 3)
    env.close()


@pytest.mark.parametrize("size", [(96, 96), (100, 128), (0, 0), (96.5, 128)])
def test_sizes_that_change_the_view_are_refused(size):
    with pytest.raises(ValueError, match="3:4|positive"):
        validate_head_size(*size)
    with pytest.raises(ValueError, match="observation_height"):
        ActiveArenaEnvConfig(task=TASK, observation_height=size[0], observation_width=size[1])


def test_the_env_config_declares_the_size():
    cfg = ActiveArenaEnvConfig(task=TASK, observation_height=96, observation_width=128)
    assert cfg.features["pixels/head"].shape == (96, 128, 3)
    assert cfg.gym_kwargs["observation_height"] == 96 and cfg.gym_kwargs["observation_width"] == 128
    assert ActiveArenaEnvConfig(task=TASK).features["pixels/head"].shape == (384, 512, 3)


def test_builds_take_the_size_from_the_flag_or_the_recipe(tmp_path):
    args = parser().parse_args(["--repo-id", "x/y", "--root", str(tmp_path), "--image-size", "96x128"])
    assert make_plan(args).image_size == (96, 128)
    assert dataset_features(image_size=(96, 128))[IMAGE_KEY]["shape"] == (96, 128, 3)
    recipe = tmp_path / "r.json"
    recipe.write_text('{"repo_id": "x/y", "episodes": 2, "image_size": "192x256"}')
    args = parser().parse_args(["--recipe", str(recipe), "--root", str(tmp_path)])
    assert make_plan(args, load_recipe(recipe)).image_size == (192, 256)
    assert make_plan(parser().parse_args(["--repo-id", "x/y", "--root", str(tmp_path)])).image_size == (
        384,
        512,
    )
    bad = parser().parse_args(["--repo-id", "x/y", "--root", str(tmp_path), "--image-size", "96by128"])
    with pytest.raises(ValueError, match="HEIGHTxWIDTH"):
        make_plan(bad)


def test_activearena_eval_names_the_size_a_policy_was_trained_at():
    from lerobot.configs.types import FeatureType, PolicyFeature
    from lerobot.policies.act.configuration_act import ACTConfig

    from lerobot_activearena.cli.eval import check_features, parse_env

    cfg = ACTConfig(
        input_features={
            "observation.images.head": PolicyFeature(type=FeatureType.VISUAL, shape=(3, 96, 128)),
            "observation.state": PolicyFeature(type=FeatureType.STATE, shape=(18,)),
        },
        output_features={"action": PolicyFeature(type=FeatureType.ACTION, shape=(18,))},
        pretrained_backbone_weights=None,
    )
    with pytest.raises(ValueError, match="--env.observation_height=96 --env.observation_width=128"):
        check_features(cfg, {}, fixed_view=False)
    options = parse_env(["--env.observation_height=96", "--env.observation_width=128"])
    assert options == {"observation_height": 96, "observation_width": 128}
    check_features(cfg, options, fixed_view=False)
