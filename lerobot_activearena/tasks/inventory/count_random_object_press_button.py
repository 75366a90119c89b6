"""count_random_object_press_button (MD): count the objects of the instructed category and press
the button of that number.

Task Description:
    1-3 objects of one category (cans, pill bottles, mice, staplers or bells; the instruction names
    it) and three objects of other categories are spread over the fan (one counted object out of
    the home view); three numbered buttons stand in the arms' band. Count the instructed objects,
    then press the button of that number.
Randomizations:
    Instructed category and count 1-3; distractor categories (the other four, repeats allowed);
    the first counted object out of the home view on a random side (0.36-0.8 m), the rest anywhere
    at 0.36-0.8 m; yaws and asset colours random; buttons anywhere in the arms' band; clutter
    (never of the instructed category) and (OOD) appearance.
Success Conditions:
    pressed_matching_button: the button of the count went below -0.005 m while a closed gripper
    touched it at its press point, after every counted object was seen. Failure: any other button
    pressed (ends the episode).
"""

from __future__ import annotations

from ..base import Subtask
from ..draft import Region
from ..shapes.counting import PRESS_SUBTASK, CountAndPressTask

CATEGORIES = {
    "can": "cans",
    "pill_bottle": "pill bottles",
    "mouse": "mice",
    "stapler": "staplers",
    "bell": "bells",
}
N_DISTRACTORS = 3
OBJECT_R = (0.36, 0.8)


class CountRandomObjectPressButton(CountAndPressTask):
    name = "count_random_object_press_button"
    category = "MD"
    instruction = "Count the instructed objects and press the matching button."
    subtasks = (
        Subtask(
            1,
            "count_random_target_objects",
            "scan the scene and count instances of the instructed category",
            0,
        ),
        PRESS_SUBTASK,
    )
    max_episode_steps = 152

    def instruction_for(self, params):
        return f"Count the {CATEGORIES[params['target_category']]} and press the matching button."

    def place_counted(self, draft, count):
        rng = draft.rng
        names = list(CATEGORIES)
        target = names[int(rng.integers(0, len(names)))]
        others = [c for c in names if c != target]
        draft.params["target_category"] = target
        for k in range(count):
            region = Region(r=OBJECT_R, hidden=True) if k == 0 else Region(r=OBJECT_R)
            draft.place(
                target, f"target_{target}_{k}", f"{target.replace('_', ' ')} {k + 1}", region, yaw="random"
            )
        for k in range(N_DISTRACTORS):
            cat = others[int(rng.integers(0, len(others)))]
            draft.place(cat, f"other_{cat}_{k}", cat.replace("_", " "), Region(r=OBJECT_R), yaw="random")

    def counted_objects(self, scene):
        return [i for i, n in enumerate(scene.objects) if n.startswith("target_")]

    def count_seen(self, ctx, scene, seen):
        target = scene.params["target_category"]
        return sum(1 for i in seen if ctx.obj(i).category == target)
