"""ActiveArena-VLA's planned run (`oft_subtask_planned_12_ws`). So far its prompts, targets,
retrieval labels, answer parser and run-time memory bank (``planning``); the planner and executor
policy types and their run-time loop are not built yet."""
