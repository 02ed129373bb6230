"""A robot in the pybullet world: loaded from a URDF file, read and driven by joint effort."""

import pybullet as p


class RobotLoadError(ValueError):
    """pybullet could not build the body; the message says what it reported."""


class Robot:
    def __init__(
        self, client, urdf_path, position=(0, 0, 0), orientation=(0, 0, 0, 1), fixed_base=False
    ):
        self.client = client
        # Inertia from the file: pybullet would otherwise derive it from the collision mesh.
        try:
            self.body = p.loadURDF(
                urdf_path,
                position,
                orientation,
                useFixedBase=fixed_base,
                flags=p.URDF_USE_INERTIA_FROM_FILE,
                physicsClientId=client,
            )
        except p.error as exc:
            raise RobotLoadError('pybullet could not build the robot (%s)' % exc)
        # pybullet poses a base by its centre of mass: keep that pose (not the link frame's)
        # for reset, and the link frame's offset from it for link_pose.
        self.initial_pose = p.getBasePositionAndOrientation(self.body, physicsClientId=client)
        inertial = p.getDynamicsInfo(self.body, -1, physicsClientId=client)[3:5]
        self._base_from_com = p.invertTransform(*inertial)
        self.joint_index = {}
        self.link_index = {p.getBodyInfo(self.body, physicsClientId=client)[0].decode(): -1}
        # Gazebo has no velocity damping: pybullet's default 0.04 would add some, to the base
        # (a free box slows down by itself) as to every link.
        for i in range(-1, p.getNumJoints(self.body, physicsClientId=client)):
            p.changeDynamics(
                self.body, i, linearDamping=0, angularDamping=0, physicsClientId=client
            )
            if i < 0:
                continue
            info = p.getJointInfo(self.body, i, physicsClientId=client)
            self.joint_index[info[1].decode()] = i
            self.link_index[info[12].decode()] = i
        movable = [
            i
            for i in self.joint_index.values()
            if p.getJointInfo(self.body, i, physicsClientId=client)[2] != p.JOINT_FIXED
        ]
        if movable:
            # Each joint's default velocity motor would hold it still: switch it off so effort acts.
            p.setJointMotorControlArray(
                self.body,
                movable,
                p.VELOCITY_CONTROL,
                forces=[0.0] * len(movable),
                physicsClientId=client,
            )
        self.movable = movable
        # (follower index, leader index, multiplier, offset, max force, sensitiveness)
        self.mimics = []

    def set_mimics(self, mimics):
        """``[(follower, leader, multiplier, offset, max_force, sensitiveness)]`` by joint name:
        each follower is driven toward leader * multiplier + offset before every step."""
        self.mimics = [
            (self.joint_index[f], self.joint_index[lead], m, o, force, sens)
            for f, lead, m, o, force, sens in mimics
        ]

    def follow_mimics(self):
        """A position motor per follower, capped at its max force: a stiff, physical link
        that pushes like a finger (a teleport would pass through what it grips), and,
        unlike a gear constraint, takes an offset. Set last before the step, it overrides any
        command the hardware interface gave the follower."""
        for follower, leader, multiplier, offset, force, sensitiveness in self.mimics:
            lead, lead_vel = p.getJointState(self.body, leader, physicsClientId=self.client)[:2]
            target = lead * multiplier + offset
            if sensitiveness > 0:
                pos = p.getJointState(self.body, follower, physicsClientId=self.client)[0]
                if abs(target - pos) < sensitiveness:
                    target = pos
            # positionGain 0.2 settles a light finger in a few steps; 1.0 oscillates.
            p.setJointMotorControl2(
                self.body,
                follower,
                p.POSITION_CONTROL,
                targetPosition=target,
                targetVelocity=lead_vel * multiplier,
                force=force,
                positionGain=0.2,
                velocityGain=1.0,
                physicsClientId=self.client,
            )

    def indices(self, joint_names):
        return [self.joint_index[n] for n in joint_names]

    def read(self, indices):
        """``[(position, velocity), ...]`` of the given joints."""
        return [s[:2] for s in self._joint_states(indices)]

    def _joint_states(self, indices):
        # pybullet answers None, not [], when asked for no joints (a body without joints).
        if not indices:
            return []
        return p.getJointStates(self.body, indices, physicsClientId=self.client)

    def apply_efforts(self, indices, efforts):
        # A TORQUE_CONTROL command lasts one stepSimulation: call this before every step.
        if not indices:
            return
        p.setJointMotorControlArray(
            self.body, indices, p.TORQUE_CONTROL, forces=efforts, physicsClientId=self.client
        )

    def set_velocity_motors(self, indices, velocities, max_forces):
        """Velocity motors (VELOCITY_CONTROL lasts until changed; a max force 0 turns one off)."""
        if not indices:
            return
        p.setJointMotorControlArray(
            self.body,
            indices,
            p.VELOCITY_CONTROL,
            targetVelocities=velocities,
            forces=max_forces,
            physicsClientId=self.client,
        )

    def set_positions(self, indices, positions):
        """Put joints there, at rest, for the next step (Gazebo's Joint::SetPosition)."""
        if not indices:
            return
        p.resetJointStatesMultiDof(
            self.body,
            indices,
            targetValues=[[v] for v in positions],
            targetVelocities=[[0.0]] * len(indices),
            physicsClientId=self.client,
        )

    def set_joint_positions(self, positions):
        """``{joint name: position}``, at rest."""
        for name, value in positions.items():
            p.resetJointState(
                self.body, self.joint_index[name], value, 0.0, physicsClientId=self.client
            )

    def reset(self):
        """Back to the spawn pose, every joint at zero and at rest."""
        p.resetBasePositionAndOrientation(
            self.body, *self.initial_pose, physicsClientId=self.client
        )
        p.resetBaseVelocity(self.body, [0, 0, 0], [0, 0, 0], physicsClientId=self.client)
        for i in self.movable:
            p.resetJointState(self.body, i, 0.0, 0.0, physicsClientId=self.client)

    def state(self):
        """Base pose and the positions of the movable joints: all a mirror needs to look alike."""
        pos, orn = p.getBasePositionAndOrientation(self.body, physicsClientId=self.client)
        return pos, orn, [s[0] for s in self._joint_states(self.movable)]

    def set_state(self, state):
        """Take on a ``state()`` of a robot loaded from the same URDF."""
        pos, orn, positions = state
        p.resetBasePositionAndOrientation(self.body, pos, orn, physicsClientId=self.client)
        for i, value in zip(self.movable, positions):
            p.resetJointState(self.body, i, value, physicsClientId=self.client)

    def link_pose(self, link_name):
        """World position and quaternion of a link's frame."""
        i = self.link_index[link_name]
        if i == -1:
            com = p.getBasePositionAndOrientation(self.body, physicsClientId=self.client)
            return p.multiplyTransforms(*com, *self._base_from_com)
        s = p.getLinkState(self.body, i, computeForwardKinematics=True, physicsClientId=self.client)
        return s[4], s[5]

    def remove(self):
        p.removeBody(self.body, physicsClientId=self.client)
