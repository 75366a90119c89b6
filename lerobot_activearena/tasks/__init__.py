"""The benchmark tasks: one module per task, registered by its paper name."""

from .base import CATEGORIES, TASKS, Subtask, Task, TaskScene
from .registry import get_task, task_names

__all__ = ["CATEGORIES", "TASKS", "Subtask", "Task", "TaskScene", "get_task", "task_names"]
