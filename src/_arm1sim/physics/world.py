"""The pybullet world: physics settings, static scenery, robots, stepping and reset."""

import logging
import math
import os

import pybullet as p

from ..description.surface import Surface
from .robot import Robot, RobotLoadError
from .surface_combiner import SurfaceCombiner

log = logging.getLogger('_arm1sim.physics')

# pybullet's shared-memory state holds at most this many joints of one body: with more,
# getBasePositionAndOrientation and the joint states fail (measured, pybullet 3.2).
MAX_BODY_JOINTS = 127


def connect(gui):
    """A pybullet client: a window when asked and a display exists, headless otherwise."""
    if gui:
        if not os.environ.get('DISPLAY'):
            log.warning('gui requested but no DISPLAY is set: running headless')
        else:
            client = p.connect(p.GUI)
            if client >= 0:
                return client, True
            log.warning(
                'could not open the pybullet window on %s: running headless', os.environ['DISPLAY']
            )
    return p.connect(p.DIRECT), False


class World:
    def __init__(self, config, gui=False, on_connect=None):
        """``config`` is a sdf_world.WorldConfig; ``on_connect(client)`` runs before any body
        is built (pybullet's EGL render plugin draws only bodies loaded after it)."""
        self.client, self.gui = connect(gui)
        cid = self.client
        if on_connect is not None:
            on_connect(cid)
        p.setTimeStep(config.max_step_size, physicsClientId=cid)
        p.setGravity(*config.gravity, physicsClientId=cid)
        # Joint stops as ODE's (stop ERP 0.2): Bullet corrects a joint limit's overshoot with
        # its ERP (0.2) only while the overshoot is shallower than the split-impulse threshold
        # (0.04 rad or m); a deeper one goes to the split impulse, which Bullet's multibodies
        # never apply, so the joint stayed past its stop. Only joint limits read this setting
        # in a world of multibodies (their contacts ignore it).
        p.setPhysicsEngineParameter(useSplitImpulse=0, physicsClientId=cid)
        if self.gui:
            p.configureDebugVisualizer(p.COV_ENABLE_GUI, 0, physicsClientId=cid)
            p.resetDebugVisualizerCamera(0.35, 45, -30, (0, 0, 0.05), physicsClientId=cid)
        # Friction and bounce as ODE combines two surfaces (the smaller), not pybullet's product
        self.surfaces = SurfaceCombiner(cid)
        self.scenery = [self._build(m) for m in config.models]
        self.robots = []

    def _build(self, model):
        cid = self.client
        quat = p.getQuaternionFromEuler(model.pose[3:])
        bodies = []
        for s in model.shapes:
            if s.kind == 'plane':
                col = _ground_shape(s.size, cid)
                vis = p.createVisualShape(
                    p.GEOM_BOX, halfExtents=(50, 50, 0.0005), rgbaColor=s.color, physicsClientId=cid
                )
            elif s.kind == 'box':
                half = [v / 2 for v in s.size]
                col = p.createCollisionShape(p.GEOM_BOX, halfExtents=half, physicsClientId=cid)
                vis = p.createVisualShape(
                    p.GEOM_BOX, halfExtents=half, rgbaColor=s.color, physicsClientId=cid
                )
            elif s.kind == 'sphere':
                col = p.createCollisionShape(p.GEOM_SPHERE, radius=s.size[0], physicsClientId=cid)
                vis = p.createVisualShape(
                    p.GEOM_SPHERE, radius=s.size[0], rgbaColor=s.color, physicsClientId=cid
                )
            else:
                col = p.createCollisionShape(
                    p.GEOM_CYLINDER, radius=s.size[0], height=s.size[1], physicsClientId=cid
                )
                vis = p.createVisualShape(
                    p.GEOM_CYLINDER,
                    radius=s.size[0],
                    length=s.size[1],
                    rgbaColor=s.color,
                    physicsClientId=cid,
                )
            pos, orn = p.multiplyTransforms(
                model.pose[:3], quat, s.pose[:3], p.getQuaternionFromEuler(s.pose[3:])
            )
            bodies.append(p.createMultiBody(0, col, vis, pos, orn, physicsClientId=cid))
            # Before any manifold with it is made: a manifold keeps the threshold it was made with
            p.changeDynamics(
                bodies[-1],
                -1,
                contactProcessingThreshold=SCENERY_CONTACT_WITHIN,
                physicsClientId=cid,
            )
            surface = getattr(model, 'surface', None) or Surface()
            self.surfaces.add(bodies[-1], -1, surface.friction, surface.restitution)
        return bodies

    def load_robot(self, urdf_path, position, orientation, fixed_base, options=None):
        """``options``: description.gazebo_tags.BodyOptions of the URDF, None for none."""
        before = _bodies(self.client)
        try:
            robot = Robot(self.client, urdf_path, position, orientation, fixed_base, options)
        except BaseException as exc:  # whole or not at all: no half-built body stays
            built = _bodies(self.client) - before
            joints = max((p.getNumJoints(b, physicsClientId=self.client) for b in built), default=0)
            for body in built:
                p.removeBody(body, physicsClientId=self.client)
            if isinstance(exc, p.error):
                if joints > MAX_BODY_JOINTS:
                    raise RobotLoadError(
                        'pybullet cannot simulate a body of %d joints: it reports no state for '
                        'more than %d joints in one body (fixed joints count unless lumped)'
                        % (joints, MAX_BODY_JOINTS)
                    )
                raise RobotLoadError('pybullet could not build the robot (%s)' % exc)
            raise
        self.robots.append(robot)
        surfaces = options.surfaces if options is not None else {}
        for name, index in robot.link_index.items():
            surface = surfaces.get(name) or Surface()
            self.surfaces.add(robot.body, index, surface.friction, surface.restitution)
        return robot

    def remove_robot(self, robot):
        self.robots.remove(robot)
        self.surfaces.forget(robot.body)
        robot.remove()

    def step(self):
        gravity = None
        for robot in self.robots:
            if robot.mimics:
                robot.follow_mimics()
            if robot.gravity_off:
                if gravity is None:
                    gravity = _gravity(self.client)
                _cancel_weight(robot, gravity)
        self.surfaces.update()
        p.stepSimulation(physicsClientId=self.client)
        for robot in self.robots:
            if robot.mimics:
                robot.measure_mimics()

    def reset(self):
        for robot in self.robots:
            robot.reset()

    def close(self):
        if p.isConnected(self.client):
            p.disconnect(self.client)


GROUND_HALF_SIZE = 500.0  # m: the ground's reach from its origin (Gazebo's plane is infinite)
GROUND_HALF_DEPTH = 0.5  # m: deep enough that nothing falling onto it passes through
# m: how far apart a contact point with the world's static scenery is still solved. ODE makes
# a contact at depth >= 0; Bullet also solves a manifold's points up to 2 cm apart, each a
# normal and two friction rows every iteration: arm1 lying on the ground as launched had one
# touching point and six 1.2 mm apart. A manifold takes the smaller of its two bodies'
# thresholds, so this reaches contacts with scenery only: between two moving bodies (a
# gripper's fingers on a can, whose points flicker about zero) Bullet's default stays.
SCENERY_CONTACT_WITHIN = 0.0005


def _ground_shape(normal, client):
    """A plane as a thick slab whose top face is the plane: pybullet gives a plane an infinite
    bounding box, so every convex piece of every concave mesh is tested against it each step;
    a slab's finite bounds leave those above the ground out. A convex hull of the slab's
    corners, not a GEOM_BOX: Bullet's box-box contact left a body resting on it jittering
    (a 1 kg payload's ft_sensor read 9.8 +- 0.07 N, step to step; exact on the plane)."""
    n = [float(v) for v in normal]
    axis = (-n[1], n[0], 0.0)  # z turned onto the normal
    norm = sum(v * v for v in n) ** 0.5
    angle = math.acos(max(-1.0, min(1.0, n[2] / norm)))
    turn = (
        p.getQuaternionFromAxisAngle(axis, angle)
        if abs(axis[0]) + abs(axis[1]) > 1e-12
        else p.getQuaternionFromEuler((math.pi if n[2] < 0 else 0.0, 0, 0))
    )
    offset, _ = p.multiplyTransforms((0, 0, 0), turn, (0, 0, -GROUND_HALF_DEPTH), (0, 0, 0, 1))
    h, d = GROUND_HALF_SIZE, GROUND_HALF_DEPTH
    return p.createCollisionShape(
        p.GEOM_MESH,
        vertices=[(x, y, z) for x in (-h, h) for y in (-h, h) for z in (-d, d)],
        collisionFramePosition=offset,
        collisionFrameOrientation=turn,
        physicsClientId=client,
    )


def _bodies(client):
    return {
        p.getBodyUniqueId(i, physicsClientId=client)
        for i in range(p.getNumBodies(physicsClientId=client))
    }


def _gravity(client):
    """The world's gravity now (set_physics_properties may have changed it)."""
    params = p.getPhysicsEngineParameters(physicsClientId=client)
    return (
        params['gravityAccelerationX'],
        params['gravityAccelerationY'],
        params['gravityAccelerationZ'],
    )


def _cancel_weight(robot, gravity):
    """Gazebo's per-link gravity off (pybullet has none): -m g at each such link's centre of
    mass, for the next step only (pybullet clears external forces after a step)."""
    cid = robot.client
    for index, mass in robot.gravity_off:
        if index == -1:
            com = p.getBasePositionAndOrientation(robot.body, physicsClientId=cid)[0]
        else:
            com = p.getLinkState(
                robot.body, index, computeForwardKinematics=True, physicsClientId=cid
            )[0]
        force = (-mass * gravity[0], -mass * gravity[1], -mass * gravity[2])
        p.applyExternalForce(robot.body, index, force, com, p.WORLD_FRAME, physicsClientId=cid)
