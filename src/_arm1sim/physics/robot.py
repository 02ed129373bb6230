"""A robot in the pybullet world: loaded from a URDF file, read and driven by joint effort."""

import itertools

import pybullet as p

from . import mimic
from .carry import CARRY_MIN_CHANGE, JumpCarrier

IDENTITY = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
# How near its last target (m or rad) a position-driven joint counts as having reached it.
REACHED = 1e-6
STATIC_GROUP = 2  # Bullet's StaticFilter: the group pybullet gives static bodies (mask: all but it)


class RobotLoadError(ValueError):
    """pybullet could not build the body; the message says what it reported."""


class Robot:
    def __init__(
        self,
        client,
        urdf_path,
        position=(0, 0, 0),
        orientation=(0, 0, 0, 1),
        fixed_base=False,
        options=None,
    ):
        """``options`` is a description.gazebo_tags.BodyOptions (lumped frames, per-link
        contact settings, selfCollide, gravity off), None for none."""
        self.client = client
        self.frames = dict(options.frames) if options is not None else {}
        self_collide = set(options.self_collide) if options is not None else set()
        # Inertia from the file: pybullet would otherwise derive it from the collision mesh.
        flags = p.URDF_USE_INERTIA_FROM_FILE
        if self_collide:
            # pybullet's default with this flag: every pair but parent and child collides.
            flags |= p.URDF_USE_SELF_COLLISION
        try:
            self.body = p.loadURDF(
                urdf_path,
                position,
                orientation,
                useFixedBase=fixed_base,
                flags=flags,
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
        if fixed_base:
            self._weld_to_static(client)
        movable = [
            i
            for i in self.joint_index.values()
            if p.getJointInfo(self.body, i, physicsClientId=client)[2] != p.JOINT_FIXED
        ]
        # <dynamics friction> by joint index: Gazebo applies it as the joint motor's fmax at
        # vel 0 (Coulomb friction); whoever turns a motor off should leave it this force.
        self.joint_friction = {
            i: abs(p.getJointInfo(self.body, i, physicsClientId=client)[7]) for i in movable
        }
        if movable:
            # Each joint's default velocity motor would hold it still: switch it off so effort
            # acts, except for its friction. pybullet reads the friction from the URDF but
            # applies none itself; it applies <dynamics damping> as Gazebo does (viscous).
            p.setJointMotorControlArray(
                self.body,
                movable,
                p.VELOCITY_CONTROL,
                targetVelocities=[0.0] * len(movable),
                forces=[self.joint_friction[i] for i in movable],
                physicsClientId=client,
            )
        self.movable = movable
        if not movable:
            # Static friction that holds, as ODE's does: without a friction anchor pybullet
            # lets a gripped object creep through the fingers (2-3 mm in 5 s). Bullet anchors
            # a contact if either body asks, so the objects' asking (bodies without joints:
            # boxes, cans, tables) covers every grip. Its own call: pybullet drops some
            # settings passed beside others.
            for i in range(-1, p.getNumJoints(self.body, physicsClientId=client)):
                p.changeDynamics(self.body, i, frictionAnchor=1, physicsClientId=client)
        # Links whose weight is cancelled before each step (turnGravityOff): (index, mass)
        self.gravity_off = []
        if options is not None:
            self._apply_link_options(options, self_collide)
        self.mimics = []  # physics.mimic.MimicJoint, one per follower
        self._position_targets = {}  # move_positions' last target by joint index

    def _weld_to_static(self, client):
        """Links welded to a fixed base (fixed joints all the way to it) cannot move, as the
        base cannot: they get the collision filter pybullet gives that base (a static body's),
        so they skip static bodies (ground, tables) as it does; dynamic bodies and the
        robot's other links still touch them. A concave mesh (physics/concave_meshes) is many
        pieces: on a base standing on the ground each piece was tested against it every step
        (arm1: twice the step's cost). A contact sensor on such a link sees no static body."""
        welded = {-1}
        for i in range(p.getNumJoints(self.body, physicsClientId=client)):
            info = p.getJointInfo(self.body, i, physicsClientId=client)
            if info[2] == p.JOINT_FIXED and info[16] in welded:  # parents come first
                welded.add(i)
                p.setCollisionFilterGroupMask(
                    self.body, i, STATIC_GROUP, ~STATIC_GROUP, physicsClientId=client
                )

    def _apply_link_options(self, options, self_collide):
        cid = self.client
        for name, kwargs in options.dynamics.items():
            if name in self.link_index:
                p.changeDynamics(self.body, self.link_index[name], physicsClientId=cid, **kwargs)
        for name in options.no_gravity:
            if name in self.link_index:
                i = self.link_index[name]
                mass = p.getDynamicsInfo(self.body, i, physicsClientId=cid)[0]
                self.gravity_off.append((i, mass))
        if self_collide:
            # Gazebo: two links collide when either has selfCollide, never across a joint.
            # Only links with collision shapes need a filter (pairs grow as their square).
            quiet = [
                i
                for n, i in self.link_index.items()
                if n not in self_collide
                and p.getCollisionShapeData(self.body, i, physicsClientId=cid)
            ]
            for a, b in itertools.combinations(sorted(quiet), 2):
                p.setCollisionFilterPair(self.body, self.body, a, b, 0, physicsClientId=cid)

    def frame(self, link_name):
        """Where a link's frame is carried: ``(pybullet link index, offset pose)``.

        A link of the body gives its own index and the identity; a link merged into its
        parent by fixed-joint lumping (gone from link_index, link_states and get_link_state,
        as in Gazebo) gives the index of the link it now lives on and the pose
        ``((x, y, z), (qx, qy, qz, qw))`` of its frame in that link's frame. Sensors and
        cameras attached to any URDF link resolve it through here. KeyError for a name
        the URDF does not have."""
        if link_name in self.link_index:
            return self.link_index[link_name], IDENTITY
        parent, offset = self.frames[link_name]
        return self.link_index[parent], offset

    def lumped_link(self, link_name):
        """``(link it was merged into, offset pose)`` for a lumped link, None otherwise."""
        return self.frames.get(link_name)

    def set_mimics(self, mimics):
        """``[(follower, leader, multiplier, offset, max_force, sensitiveness)]`` by joint name:
        each follower is driven toward leader * multiplier + offset before every step."""
        self.mimics = mimic.mimic_joints(
            self.body,
            self.client,
            [
                (self.joint_index[f], self.joint_index[lead], m, o, force, sens)
                for f, lead, m, o, force, sens in mimics
            ],
        )

    def set_mimic_pid(self, follower, law):
        """The follower (by joint name) driven by ``law(error) -> effort`` (hasPID)."""
        index = self.joint_index[follower]
        for m in self.mimics:
            if m.follower == index:
                mimic.set_pid(self.body, self.client, m, law)

    def follow_mimics(self):
        """Before a step: physics.mimic.follow (overrides any command given to a follower)."""
        mimic.follow(self.body, self.client, self.mimics)

    def measure_mimics(self):
        """After a step: physics.mimic.measure."""
        mimic.measure(self.body, self.client, self.mimics)

    def indices(self, joint_names):
        return [self.joint_index[n] for n in joint_names]

    def read(self, indices):
        """``[(position, velocity), ...]`` of the given joints."""
        return [s[:2] for s in self._joint_states(indices)]

    def joint_states(self, indices):
        """pybullet's state of each joint as it gives it, ``(position, velocity, ...)``: read
        without copying (the hardware's read every control update)."""
        return self._joint_states(indices)

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

    def move_positions(self, indices, positions, max_forces, dt):
        """Reach ``positions`` at the end of the next step (as Gazebo's Joint::SetPosition
        does) by moving there, so that contacts see the motion and friction carries what the
        links hold: a velocity motor at (target - position) / dt, capped at ``max_forces``
        (what the joint pushes an obstacle with). A joint that reached its last target moves
        freely: its velocity is set to that too, so its inertia costs no step; one held back
        (blocked, or its force too small) or just teleported (spawn, reset) gets the motor
        alone, not a kick into the obstacle. What the links grip takes the same jump (carry)."""
        if not indices:
            return
        cid = self.client
        states = p.getJointStates(self.body, indices, physicsClientId=cid)
        velocities, free, free_pos, free_vel = [], [], [], []
        targets = self._position_targets
        jump = 0.0
        for i, target, state in zip(indices, positions, states):
            position = state[0]
            velocity = (target - position) / dt
            velocities.append(velocity)
            last = targets.get(i)
            if last is not None and abs(position - last) <= REACHED:
                free.append(i)
                free_pos.append([position])
                free_vel.append([velocity])
                jump = max(jump, abs(velocity - state[1]))
            targets[i] = target
        if free:
            carrier = JumpCarrier(cid, self.body) if jump > CARRY_MIN_CHANGE else None
            p.resetJointStatesMultiDof(
                self.body,
                free,
                targetValues=free_pos,
                targetVelocities=free_vel,
                physicsClientId=cid,
            )
            if carrier is not None:
                carrier.after()
        p.setJointMotorControlArray(
            self.body,
            indices,
            p.VELOCITY_CONTROL,
            targetVelocities=velocities,
            forces=max_forces,
            physicsClientId=cid,
        )

    def set_joint_positions(self, positions):
        """``{joint name: position}``, at rest."""
        for name, value in positions.items():
            p.resetJointState(
                self.body, self.joint_index[name], value, 0.0, physicsClientId=self.client
            )
        self._forget_motion()

    def _forget_motion(self):
        """After a teleport: no last target reached, no mimic reaction from before it."""
        self._position_targets.clear()
        for m in self.mimics:
            m.last_effort = 0.0

    def reset(self):
        """Back to the spawn pose, every joint at zero and at rest."""
        p.resetBasePositionAndOrientation(
            self.body, *self.initial_pose, physicsClientId=self.client
        )
        p.resetBaseVelocity(self.body, [0, 0, 0], [0, 0, 0], physicsClientId=self.client)
        for i in self.movable:
            p.resetJointState(self.body, i, 0.0, 0.0, physicsClientId=self.client)
        self._forget_motion()

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
        """World position and quaternion of a link's frame (a lumped link's too: see frame)."""
        i, offset = self.frame(link_name)
        if i == -1:
            com = p.getBasePositionAndOrientation(self.body, physicsClientId=self.client)
            pose = p.multiplyTransforms(*com, *self._base_from_com)
        else:
            s = p.getLinkState(
                self.body, i, computeForwardKinematics=True, physicsClientId=self.client
            )
            pose = s[4], s[5]
        if offset is IDENTITY:
            return pose
        return p.multiplyTransforms(*pose, *offset)

    def remove(self):
        p.removeBody(self.body, physicsClientId=self.client)
