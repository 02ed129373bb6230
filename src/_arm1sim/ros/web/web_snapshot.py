"""What the browser view shows of the world, read on the physics thread between two steps.

The view's threads never touch pybullet or the simulation: they ask for a snapshot
(``WorldSnapshots.request``) and the physics thread fills one in before its next step
(``before_step`` hook), or, while physics is paused, through a hand-over call. A
snapshot is plain tuples and floats: link frame poses, joint positions beside their
controllers' commands, controller states, and, for a model the view has not seen yet,
its visual shapes as pybullet parsed them from the URDF (geometry, mesh file, scale,
local pose, material colour).
"""

from __future__ import annotations

import threading
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence, Tuple

import pybullet as p

from ...control.controller import Controller
from ...physics.renderers import _link_frame
from ...sim.simulation import Model, Simulation
from ..world.sim_thread import SimThreadCalls
from ..world.world_loop import WorldLoop

Pose = Tuple[Tuple[float, float, float], Tuple[float, float, float, float]]  # xyz, xyzw


@dataclass(frozen=True)
class Visual:
    """One visual shape of a link: pybullet's getVisualShapeData, as plain values."""

    link: int  # -1: the base
    kind: str  # 'box' | 'sphere' | 'cylinder' | 'capsule' | 'mesh'
    size: Tuple[float, ...]  # box: x y z; sphere: radius; cylinder, capsule: length radius;
    # mesh: scale x y z
    mesh: str  # the mesh file ('' for a primitive)
    pose: Pose  # in the link's frame
    rgba: Tuple[float, float, float, float]


@dataclass(frozen=True)
class JointView:
    """A joint commanded by a running controller: where it is and where it is told to be."""

    name: str
    position: float
    command: Optional[float]
    lower: float
    upper: float


@dataclass(frozen=True)
class ControllerView:
    name: str
    type: str
    state: str
    joints: Tuple[JointView, ...]  # running position or trajectory controllers only


@dataclass(frozen=True)
class ModelView:
    name: str
    token: int  # a new token: a new model of that name (spawned again)
    links: Tuple[str, ...]  # by pybullet index + 1 (the base first)
    poses: Tuple[Pose, ...]  # each link's frame, world, same order
    namespace: str  # the controller manager's, '' without one
    controllers: Tuple[ControllerView, ...]
    static: bool = False


@dataclass
class Snapshot:
    time_ns: int
    paused: bool
    rtf: Optional[float]
    models: Dict[str, ModelView]
    visuals: Dict[int, List[Visual]] = field(default_factory=dict)  # by token, for new ones


_KINDS = {
    p.GEOM_BOX: 'box',
    p.GEOM_SPHERE: 'sphere',
    p.GEOM_CYLINDER: 'cylinder',
    p.GEOM_CAPSULE: 'capsule',
    p.GEOM_MESH: 'mesh',
}
POSITION_COMMANDED = ('JointPositionController', 'JointGroupPositionController')
TRAJECTORY = 'JointTrajectoryController'


def visuals_of(client: int, body: int, stand_ins: Optional[Dict[str, str]] = None) -> List[Visual]:
    """A body's visual shapes (pybullet's parse of the URDF: ``<visual>``, ``<material>``);
    a mesh pybullet was handed a stand-in for is named by its own file (``stand_ins``)."""
    out = []
    for d in p.getVisualShapeData(body, physicsClientId=client):
        _, link, kind, dims, mesh, pos, orn, rgba = d[:8]
        name = _KINDS.get(kind)
        if name is None:
            continue
        if name == 'sphere':
            size: Tuple[float, ...] = (float(dims[0]),)
        elif name in ('cylinder', 'capsule'):
            size = (float(dims[0]), float(dims[1]))
        else:
            size = tuple(float(v) for v in dims[:3])
        path = mesh.decode() if isinstance(mesh, bytes) else str(mesh)
        path = (stand_ins or {}).get(path, path)
        out.append(
            Visual(
                link,
                name,
                size,
                path if name == 'mesh' else '',
                (_vec3(pos), _quat(orn)),
                (float(rgba[0]), float(rgba[1]), float(rgba[2]), float(rgba[3])),
            )
        )
    return out


def _vec3(v: Sequence[float]) -> Tuple[float, float, float]:
    return (float(v[0]), float(v[1]), float(v[2]))


def _quat(q: Sequence[float]) -> Tuple[float, float, float, float]:
    return (float(q[0]), float(q[1]), float(q[2]), float(q[3]))


def link_poses(client: int, body: int, count: int) -> Tuple[Pose, ...]:
    """The base's and each link's frame (what visual shapes are placed in), world."""
    base = _link_frame(client, body, -1)
    poses: List[Pose] = [(_vec3(base[0]), _quat(base[1]))]
    if count:
        states = p.getLinkStates(
            body, list(range(count)), computeForwardKinematics=1, physicsClientId=client
        )
        poses.extend((_vec3(s[4]), _quat(s[5])) for s in states)
    return tuple(poses)


def command_of(controller: Controller, index: int) -> Optional[float]:
    """What a position or trajectory controller holds its ``index``-th joint to."""
    target = getattr(controller, 'target', None)
    if isinstance(target, float):
        return target
    commands = getattr(controller, 'commands', None)
    if commands is not None and index < len(commands):
        return float(commands[index])
    trajectory = getattr(controller, 'trajectory', None)
    if trajectory and index < len(trajectory) and trajectory[index]:
        last = trajectory[index][-1]
        return float(last.sample(last.end)[0])
    return None


def _limits(model: Model, joint: str) -> Tuple[float, float]:
    j = model.description.joints.get(joint)
    lim = getattr(j, 'limits', None)
    lower, upper = getattr(lim, 'lower', None), getattr(lim, 'upper', None)
    if j is None or getattr(j, 'type', '') == 'continuous' or lower is None or upper is None:
        return -3.14159, 3.14159
    if upper <= lower:
        return -3.14159, 3.14159
    return float(lower), float(upper)


def controllers_of(model: Model) -> Tuple[ControllerView, ...]:
    manager = model.controller_manager
    if manager is None:
        return ()
    out = []
    for name, type_name, state, _ in manager.list_controllers():
        joints: Tuple[JointView, ...] = ()
        controller = manager.controller(name)
        commanded = type_name.endswith(POSITION_COMMANDED) or type_name.endswith(TRAJECTORY)
        if controller is not None and state == 'running' and commanded:
            handles = getattr(controller, 'joints', [])
            joints = tuple(
                JointView(
                    h.name, float(h.position), command_of(controller, i), *_limits(model, h.name)
                )
                for i, h in enumerate(handles)
            )
        out.append(ControllerView(name, type_name, str(state), joints))
    return tuple(out)


class WorldSnapshots:
    """Snapshots of ``sim`` for another thread, taken on the physics thread when asked."""

    def __init__(self, sim: Simulation, calls: SimThreadCalls, loop: WorldLoop) -> None:
        self.sim, self.calls, self.loop = sim, calls, loop
        self._wanted = False
        self._ready = threading.Event()
        self._latest: Optional[Snapshot] = None
        self._tokens: Dict[int, int] = {}  # id(Model) -> token (physics thread)
        # tokens whose visuals the view has (set by the view's thread, read here)
        self.known: frozenset = frozenset()
        self._next_token = 1
        sim.before_step.append(self._before_step)

    def close(self) -> None:
        if self._before_step in self.sim.before_step:
            self.sim.before_step.remove(self._before_step)

    # -- the view's thread -----------------------------------------------------------
    def take(self, timeout: float = 0.1) -> Optional[Snapshot]:
        """A fresh snapshot: from the next step, or (paused, or no step within ``timeout``)
        through a hand-over call. None if the world is shutting down."""
        if not self.loop.paused:
            self._ready.clear()
            self._wanted = True
            if self._ready.wait(timeout):
                return self._latest
        self._wanted = False
        try:
            return self.calls.call(self._snapshot)
        except Exception:  # shutting down (rospy.ServiceException)
            return None

    # -- the physics thread ----------------------------------------------------------
    def _before_step(self, now_ns: int) -> None:
        if self._wanted:
            self._wanted = False
            self._latest = self._snapshot()
            self._ready.set()

    def _token(self, model: Model) -> int:
        token = self._tokens.get(id(model))
        if token is None:
            token = self._tokens[id(model)] = self._next_token
            self._next_token += 1
        return token

    def _snapshot(self) -> Snapshot:
        sim = self.sim
        client = sim.world.client
        snap = Snapshot(sim.time_ns, self.loop.paused, self.loop.clock.rtf.value, {})
        live = set()
        for name, model in sim.models.items():
            robot = model.robot
            token = self._token(model)
            live.add(id(model))
            count = p.getNumJoints(robot.body, physicsClientId=client)
            links = [''] * (count + 1)
            for link, index in robot.link_index.items():
                links[index + 1] = link
            snap.models[name] = ModelView(
                name,
                token,
                tuple(links),
                link_poses(client, robot.body, count),
                model.namespace if model.controller_manager is not None else '',
                controllers_of(model),
            )
            if token not in self.known:
                snap.visuals[token] = visuals_of(client, robot.body, model.visual_stand_ins)
        scenery = zip(sim.config.models, getattr(sim.world, 'scenery', []))
        for index, (static, bodies) in enumerate(scenery):
            # the world file's static models: one body per shape, never moving
            token = -1 - index
            shapes: List[Visual] = []
            poses: List[Pose] = []
            for k, body in enumerate(bodies):
                pos, orn = p.getBasePositionAndOrientation(body, physicsClientId=client)
                poses.append((_vec3(pos), _quat(orn)))
                shapes.extend(
                    Visual(k - 1, v.kind, v.size, v.mesh, v.pose, v.rgba)
                    for v in visuals_of(client, body)
                )
            snap.models[static.name] = ModelView(
                static.name,
                token,
                tuple('link%d' % k for k in range(len(bodies))),
                tuple(poses),
                '',
                (),
                static=True,
            )
            if token not in self.known:
                snap.visuals[token] = shapes
        self._tokens = {k: v for k, v in self._tokens.items() if k in live}
        return snap


def pose_of(view: ModelView) -> Pose:
    """The model's frame (its base link's), world."""
    return view.poses[0]


def shown_pose(pose: Pose) -> Sequence[float]:
    (x, y, z), q = pose
    r, pi, yw = p.getEulerFromQuaternion(q)
    return (x, y, z, r, pi, yw)


def ros_names(namespace: str, controller: str) -> str:
    """A controller's command topic, as a user's node names it."""
    return '%s/%s/command' % (namespace.rstrip('/'), controller)
