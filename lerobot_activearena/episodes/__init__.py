"""Running an episode: the stepper (``episode``: physics, health, success, perception), used by the
gym env and the expert, and the expert's episodes (``rollout``: ``run_expert_episode``, the driver)."""
