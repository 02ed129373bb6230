"""gazebo_ros_p3d: a link's ground-truth pose and twist, as upstream reports them.

Pose of the link frame in the world, or relative to another link of the model (position in
that link's axes, orientation q·q_F⁻¹ as upstream composes it); twist of the link origin in
world axes, or the difference to the frame link's turned by R_F (not R_Fᵀ), never in the
child frame. Then ``xyzOffset`` is added and ``rpyOffset`` pre-multiplied; noise goes on the
twist only (gazebo_plugins/src/gazebo_ros_p3d.cpp).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Sequence

from ..description.pose_math import conjugate, multiply, normalized
from .link_motion import (
    Frame,
    Quat,
    Vec3,
    add,
    gaussian,
    point_state,
    quaternion_from_rpy,
    rotate,
    sub,
    unrotate,
)
from .robot import Robot
from .sim_sensor import SimSensor

WORLD_FRAMES = ('world', '/world', 'map', '/map')


@dataclass
class P3dReading:
    position: Vec3
    orientation: Quat
    linear: Vec3
    angular: Vec3
    noise: float  # gaussianNoise: covariance diagonals are its square


class P3d(SimSensor):
    kind = 'gazebo_ros_p3d'
    child_frame_id = ''  # bodyName

    def __init__(
        self,
        model: str,
        name: str,
        robot: Robot,
        body: int,
        body_offset: Frame,  # the body's frame in the pybullet link (identity unless lumped)
        update_rate: float,
        frame: Optional[int] = None,  # link index of frameName, None for the world
        frame_offset: Optional[Frame] = None,
        xyz_offset: Sequence[float] = (0.0, 0.0, 0.0),
        rpy_offset: Sequence[float] = (0.0, 0.0, 0.0),
        noise: float = 0.0,
    ) -> None:
        super().__init__(model, name, update_rate)
        self.robot, self.body, self.body_offset = robot, body, body_offset
        self.frame, self.frame_offset = frame, frame_offset
        self.xyz_offset = tuple(xyz_offset)
        self.rpy_offset = quaternion_from_rpy(rpy_offset)
        self.noise = noise

    def measure(self, now_ns: int) -> P3dReading:
        pos, orn, v, w = point_state(self.robot, self.body, self.body_offset)
        if self.frame is not None:
            assert self.frame_offset is not None
            f_pos, f_orn, f_v, f_w = point_state(self.robot, self.frame, self.frame_offset)
            pos = unrotate(f_orn, sub(pos, f_pos))
            orn = multiply(orn, conjugate(f_orn))
            v = rotate(f_orn, sub(v, f_v))
            w = rotate(f_orn, sub(w, f_w))
        pos = add(pos, self.xyz_offset)
        orn = normalized(multiply(self.rpy_offset, orn))
        n = self.noise
        return P3dReading(
            pos,
            orn,
            (v[0] + gaussian(n), v[1] + gaussian(n), v[2] + gaussian(n)),
            (w[0] + gaussian(n), w[1] + gaussian(n), w[2] + gaussian(n)),
            n,
        )
