"""LeRobot policy types shipped by the plugin (config / modeling / processor per policy): the scripted
expert and the ActiveArena-VLA heads (OFT, GR00T, FAST, Plan's planner and executor) on their shared
base ``activearena_vla``, and ``activearena_remote`` (a policy served by another process)."""
