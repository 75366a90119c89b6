"""Physical grasping: a 0.3 kg can is lifted 15 cm and shaken without slipping out (no welds)."""

import numpy as np

from lerobot_activearena.expert.ik import ArmIK
from lerobot_activearena.expert.pick import pick_and_shake
from lerobot_activearena.sim.scene import SceneBuilder
from lerobot_activearena.sim.simulator import ActiveArenaSim


def test_can_lifted_and_shaken_stays_in_gripper():
    b = SceneBuilder()
    b.add_object("can", "can", 0.45, 65.0, mass=0.3)
    model, info = b.compile()
    assert model.neq == 6, "only the finger couplings are equality constraints: no weld"
    assert model.body("can").mass[0] > 0.29
    sim = ActiveArenaSim(model, info)
    z0 = sim.data.body("can").xpos[2]

    def can_in_tcp():
        tcp, can = sim.data.site("astribot_right_tcp"), sim.data.body("can")
        return tcp.xmat.reshape(3, 3).T @ (can.xpos - tcp.xpos)

    rel_lift, shake_disp = None, []
    for phase, action in pick_and_shake(sim, ArmIK(), "can", "right"):
        sim.step(action)
        if phase == "lift" and rel_lift is None:
            rel_lift = can_in_tcp()
        if phase == "shake":
            shake_disp.append(
                np.linalg.norm(sim.data.site("astribot_right_tcp").xpos - sim.data.body("can").xpos)
            )
    slip = np.linalg.norm(can_in_tcp() - rel_lift)
    assert sim.data.body("can").xpos[2] - z0 > 0.12, "can was not lifted"
    assert slip < 0.005, f"can slipped {slip * 1000:.1f} mm in the gripper"
    assert np.ptp(shake_disp) < 0.01
    assert 0.3 < sim.state()[15] < 0.9, "gripper should be stopped by the can, neither open nor closed"
