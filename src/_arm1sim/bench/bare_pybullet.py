"""The ceiling: arm1 in bare pybullet with an inline PD, no ROS and none of our classes."""

from __future__ import annotations

import os
import tempfile
import time
from typing import Dict

from .arm import JOINTS, STEP, arm1_urdf


def bare(seconds: float) -> Dict[str, float]:
    """Read joints, PID, apply torques, step: steps per wall second over ``seconds``."""
    import pybullet as p

    from ..description.urdf_model import resolve_mesh_uris
    from ..ros.common.packages import find_package

    xml = resolve_mesh_uris(arm1_urdf(), find_package)
    with tempfile.NamedTemporaryFile('w', suffix='.urdf', delete=False) as f:
        f.write(xml)
    cid = p.connect(p.DIRECT)
    p.setTimeStep(STEP, physicsClientId=cid)
    p.setGravity(0, 0, -9.8, physicsClientId=cid)
    p.createMultiBody(
        0, p.createCollisionShape(p.GEOM_PLANE, physicsClientId=cid), physicsClientId=cid
    )
    body = p.loadURDF(
        f.name, useFixedBase=True, flags=p.URDF_USE_INERTIA_FROM_FILE, physicsClientId=cid
    )
    os.unlink(f.name)
    index = {
        p.getJointInfo(body, i, physicsClientId=cid)[1].decode(): i
        for i in range(p.getNumJoints(body, physicsClientId=cid))
    }
    idx = [index[j] for j in JOINTS]
    p.setJointMotorControlArray(body, idx, p.VELOCITY_CONTROL, forces=[0] * 4, physicsClientId=cid)
    target, kp, kd = [0.5, 1.2, 0.0, 0.0], 1.0, 0.002
    last_err = [0.0] * 4
    steps, start, cpu = 0, time.perf_counter(), time.process_time()
    deadline = start + seconds
    while True:
        for _ in range(1000):
            states = p.getJointStates(body, idx, physicsClientId=cid)
            efforts = []
            for k in range(4):
                err = target[k] - states[k][0]
                u = kp * err + kd * (err - last_err[k]) / STEP
                last_err[k] = err
                efforts.append(max(-1.0, min(1.0, u)))
            p.setJointMotorControlArray(
                body, idx, p.TORQUE_CONTROL, forces=efforts, physicsClientId=cid
            )
            p.stepSimulation(physicsClientId=cid)
        steps += 1000
        now = time.perf_counter()
        if now >= deadline:
            return {
                'steps_per_s': steps / (now - start),
                'cpu_us_per_step': (time.process_time() - cpu) / steps * 1e6,
            }
