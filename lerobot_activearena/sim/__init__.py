"""MuJoCo simulator core: embodiment, workspaces, objects, scene assembly, control, sensing."""
