"""Rigid-body dynamics of a fixed-base robot from pybullet: what a vendor's model interface
serves (mass matrix, Coriolis and gravity torques, Jacobians, frame poses).

pybullet's calculate* functions take every movable joint of the body (its degrees of
freedom, in joint-index order); callers name the joints they want and get those rows and
columns. Poses and Jacobians are expressed in the frame of a chosen root link, as a robot's
controller gives them in its base frame (link0), not in the world.
"""

from __future__ import annotations

from typing import List, Sequence, Tuple

import pybullet as p

from ..description.lumping import matrix_quaternion
from .robot import IDENTITY, Robot

Vec3 = Tuple[float, float, float]
Quat = Tuple[float, float, float, float]
Pose = Tuple[Vec3, Quat]
Matrix = List[List[float]]


class BodyDynamics:
    """Dynamics of ``robot`` restricted to ``joints`` (names), in ``root_link``'s frame."""

    def __init__(self, robot: Robot, joints: Sequence[str], root_link: str) -> None:
        self.robot = robot
        self.client, self.body = robot.client, robot.body
        self.dofs = list(robot.movable)  # pybullet's degrees of freedom, in order
        indices = robot.indices(joints)
        missing = [j for j, i in zip(joints, indices) if i not in self.dofs]
        if missing:
            raise ValueError('joint(s) %s are not movable' % ', '.join(missing))
        self.columns = [self.dofs.index(i) for i in indices]
        self.root_link = root_link
        robot.frame(root_link)  # KeyError for a link the robot does not have

    # -- the whole body's state --------------------------------------------------------
    def state(self) -> Tuple[List[float], List[float]]:
        """Positions and velocities of every degree of freedom."""
        states = p.getJointStates(self.body, self.dofs, physicsClientId=self.client)
        return [s[0] for s in states], [s[1] for s in states]

    def _pick(self, values: Sequence[float]) -> List[float]:
        return [values[c] for c in self.columns]

    # -- the model interface -------------------------------------------------------------
    def mass_matrix(self, q: Sequence[float]) -> Matrix:
        """The joints' block of the joint-space inertia matrix at ``q`` (all dofs)."""
        full = p.calculateMassMatrix(self.body, list(q), physicsClientId=self.client)
        return [[full[r][c] for c in self.columns] for r in self.columns]

    def inverse_dynamics(
        self, q: Sequence[float], dq: Sequence[float], ddq: Sequence[float]
    ) -> List[float]:
        """The joints' torques that give ``ddq`` at ``(q, dq)``, gravity included (all dofs in)."""
        tau = p.calculateInverseDynamics(
            self.body, list(q), list(dq), list(ddq), physicsClientId=self.client
        )
        return self._pick(tau)

    def gravity(self, q: Sequence[float]) -> List[float]:
        """Torques that hold the body still at ``q`` against the world's gravity."""
        zero = [0.0] * len(self.dofs)
        return self.inverse_dynamics(q, zero, zero)

    def coriolis(self, q: Sequence[float], dq: Sequence[float]) -> List[float]:
        """Coriolis and centrifugal torques C(q, dq) dq (gravity taken out)."""
        zero = [0.0] * len(self.dofs)
        with_gravity = self.inverse_dynamics(q, dq, zero)
        return [a - b for a, b in zip(with_gravity, self.gravity(q))]

    def pose(self, link: str, offset: Pose = IDENTITY) -> Pose:
        """``offset`` on ``link``'s frame, in the root link's frame, at the current state."""
        world = self.robot.link_pose(link)
        if offset is not IDENTITY:
            world = p.multiplyTransforms(*world, *offset)
        root = p.invertTransform(*self.robot.link_pose(self.root_link))
        return p.multiplyTransforms(*root, *world)

    def jacobian(self, link: str, offset: Pose, q: Sequence[float]) -> Matrix:
        """6 x joints Jacobian (linear rows, then angular) of the point ``offset`` on
        ``link``, in the root link's frame, at ``q`` (all dofs; the state must be ``q``
        for the frame rotations)."""
        index, lumped = self.robot.frame(link)
        # The point in the frame of the pybullet link carrying it: pybullet 3.2's
        # calculateJacobian takes it there (measured: not about the centre of mass).
        local = p.multiplyTransforms(*lumped, *offset)[0] if lumped is not IDENTITY else offset[0]
        zero = [0.0] * len(self.dofs)
        linear, angular = p.calculateJacobian(
            self.body, index, list(local), list(q), zero, zero, physicsClientId=self.client
        )
        root_orn = self.robot.link_pose(self.root_link)[1]
        to_root = p.getMatrixFromQuaternion(p.invertTransform((0, 0, 0), root_orn)[1])
        rows = []
        for block in (linear, angular):
            for r in range(3):
                rows.append(
                    [sum(to_root[3 * r + k] * block[k][c] for k in range(3)) for c in self.columns]
                )
        return rows


def homogeneous(pose: Pose) -> List[float]:
    """A pose as a 4x4 homogeneous transform, column-major (16 values, Eigen's order)."""
    (x, y, z), quat = pose
    m = p.getMatrixFromQuaternion(quat)  # row-major 3x3
    return [m[0], m[3], m[6], 0.0, m[1], m[4], m[7], 0.0, m[2], m[5], m[8], 0.0, x, y, z, 1.0]


def pose_of(matrix: Sequence[float]) -> Pose:
    """The inverse of ``homogeneous``: a column-major 4x4 transform as (position, quaternion)."""
    rows = [[matrix[c * 4 + r] for c in range(3)] for r in range(3)]
    quat = matrix_quaternion(rows)  # type: ignore[arg-type]
    return (float(matrix[12]), float(matrix[13]), float(matrix[14])), quat
