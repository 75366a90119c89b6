"""Gymnasium env and the LeRobot ``activearena`` env config."""
