"""ActiveArena-VLA's GR00T run (`gr00t_subtask_action_12_ws`). So far its flow-matching DiT action
head (``flow_dit``); the ``activearena_groot`` policy type (configuration / modeling / processor on
the shared VLA base) is not built yet."""
