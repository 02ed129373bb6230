"""Model and link states and properties, and physics properties, of a Simulation, ROS-free.

What gazebo_ros_api_plugin's state services do, with its frames and status messages
(``StateError`` carries the message). Sim thread only: these read and move pybullet bodies.
Forces held over sim time (apply_body_wrench, apply_joint_effort) are wrenches.py's.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict, List, Optional, Sequence, Tuple

from ..description.pose_math import conjugate as q_inv
from ..description.pose_math import multiply as q_mul
from ..description.pose_math import normalized, quat_from_rpy, rotate
from ..physics import body_state
from .simulation import Model, Simulation

Vec = Tuple[float, float, float]
Quat = Tuple[float, float, float, float]
WORLD_NAMES = ('', 'world', 'map', '/map')


class StateError(ValueError):
    """A request the world refuses: the message is upstream's status_message."""


@dataclass
class State:
    """A frame's pose and its origin's twist, world axes unless said otherwise."""

    position: Vec = (0.0, 0.0, 0.0)
    orientation: Quat = (0.0, 0.0, 0.0, 1.0)
    linear: Vec = (0.0, 0.0, 0.0)
    angular: Vec = (0.0, 0.0, 0.0)


def _sub(a: Sequence[float], b: Sequence[float]) -> Vec:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _add(a: Sequence[float], b: Sequence[float]) -> Vec:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def relative(state: State, frame: State) -> State:
    """``state`` seen from ``frame``: pose F^-1*M, velocities R_F^T (v_M - v_F) (upstream has
    no w x r transport term)."""
    inv = q_inv(frame.orientation)
    return State(
        rotate(inv, _sub(state.position, frame.position)),
        q_mul(inv, state.orientation),
        rotate(inv, _sub(state.linear, frame.linear)),
        rotate(inv, _sub(state.angular, frame.angular)),
    )


def compose(frame: State, target: State) -> State:
    """``target`` given in ``frame``, in the world: pose F*T, velocities rotated by R_F only."""
    q = frame.orientation
    return State(
        _add(frame.position, rotate(q, target.position)),
        q_mul(q, target.orientation),
        rotate(q, target.linear),
        rotate(q, target.angular),
    )


def finite(*vectors: Sequence[float]) -> bool:
    return all(math.isfinite(v) for vec in vectors for v in vec)


# --- entities -------------------------------------------------------------------------------


def _link_state(model: Model, link: str) -> State:
    pos, orn, lin, ang = body_state.link_states(model.robot)[link]
    return State(pos, orn, lin, ang)


def model_state(model: Model) -> State:
    """The model frame (its root link's frame, pybullet's base) and that link's twist."""
    pos, orn, lin, ang = body_state.base_state(model.robot)
    return State(pos, orn, lin, ang)


def scenery(sim: Simulation) -> Dict[str, State]:
    """The world file's static models (ground_plane, ...): fixed poses, no twist."""
    out: Dict[str, State] = {}
    for m in sim.config.models:
        x, y, z, roll, pitch, yaw = (float(v) for v in m.pose)
        out[m.name] = State((x, y, z), quat_from_rpy(roll, pitch, yaw))
    return out


def model_names(sim: Simulation) -> List[str]:
    """As Gazebo lists them: the world file's models, then the spawned ones, in order."""
    return [m.name for m in sim.config.models] + list(sim.models)


def find_link(sim: Simulation, name: str) -> Optional[Tuple[Model, str]]:
    """``model::link`` or a bare link name (the first model, in spawn order, that has it)."""
    if '::' in name:
        model_name, _, link = name.partition('::')
        model = sim.models.get(model_name)
        if model is not None and link in model.robot.link_index:
            return model, link
        return None
    for model in sim.models.values():
        # A URDF's root link 'world' is Gazebo's world, no link of the model (URDF -> SDF).
        if name == 'world' == model.description.root_link:
            continue
        if name in model.robot.link_index:
            return model, name
    return None


def frame_state(sim: Simulation, name: str) -> Optional[State]:
    """The state of the entity ``name``; None for the world; KeyError if there is none."""
    model = sim.models.get(name)
    if model is not None:
        return model_state(model)
    found = find_link(sim, name)
    if found is not None:
        return _link_state(*found)
    static = scenery(sim).get(name)
    if static is not None:
        return static
    if name in WORLD_NAMES:
        return None
    raise KeyError(name)


def get_model_state(sim: Simulation, name: str, reference: str) -> State:
    model = sim.models.get(name)
    static = scenery(sim).get(name) if model is None else None
    if model is None and static is None:
        raise StateError('GetModelState: model [%s] does not exist' % name)
    try:
        frame = frame_state(sim, reference)
    except KeyError:
        raise StateError(
            'GetModelState: reference relative_entity_name [%s] not found, did you '
            'forget to scope the body by model name?' % reference
        )
    state = model_state(model) if model is not None else static
    assert state is not None
    return state if frame is None else relative(state, frame)


def set_model_state(sim: Simulation, name: str, target: State, reference: str) -> None:
    model = sim.models.get(name)
    if model is None:
        raise StateError('SetModelState: model [%s] does not exist' % name)
    if not finite(target.position, target.orientation, target.linear, target.angular):
        raise StateError("SetModelState: model [%s]'s state is not all finite numbers" % name)
    try:
        frame = frame_state(sim, reference)
    except KeyError:
        raise StateError(
            'SetModelState: specified reference frame entity [%s] does not exist' % reference
        )
    target = State(target.position, normalized(target.orientation), target.linear, target.angular)
    world = target if frame is None else compose(frame, target)
    body_state.set_base_state(
        model.robot, world.position, world.orientation, world.linear, world.angular
    )


def get_link_state(sim: Simulation, link: str, reference: str) -> State:
    found = find_link(sim, link)
    if found is None:
        raise StateError(
            'GetLinkState: link [%s] not found, did you forget to scope the link by '
            'model name?' % link
        )
    try:
        frame = frame_state(sim, reference)
    except KeyError:
        raise StateError(
            'GetLinkState: reference reference_frame [%s] not found, did you forget '
            'to scope the link by model name?' % reference
        )
    state = _link_state(*found)
    return state if frame is None else relative(state, frame)


def set_link_state(sim: Simulation, link: str, target: State, reference: str) -> None:
    """As upstream for a model's root link; pybullet moves other links only through their
    joints, so those are refused by name (upstream moves the one link alone)."""
    found = find_link(sim, link)
    if found is None:
        raise StateError('SetLinkState: link [%s] does not exist' % link)
    if not finite(target.position, target.orientation, target.linear, target.angular):
        raise StateError("SetLinkState: link [%s]'s state is not all finite numbers" % link)
    frame: Optional[State] = None
    frame_link = find_link(sim, reference)
    if frame_link is not None:
        frame = _link_state(*frame_link)
    elif reference not in WORLD_NAMES:
        raise StateError('SetLinkState: failed: reference_frame [%s] is not a link' % reference)
    model, name = found
    if model.robot.link_index[name] != -1:
        raise StateError(
            'SetLinkState: link [%s] is not the root of its model: pybullet moves it only '
            'through its joints (set the model state or the joint positions instead)' % link
        )
    world = State(target.position, normalized(target.orientation), target.linear, target.angular)
    if frame is not None:
        q = frame.orientation
        world = State(
            _add(frame.position, rotate(q, target.position)),
            q_mul(q, world.orientation),
            _sub(target.linear, frame.linear),
            _sub(target.angular, frame.angular),
        )
    body_state.set_base_state(
        model.robot, world.position, world.orientation, world.linear, world.angular
    )


def model_states(sim: Simulation) -> Tuple[List[str], List[State]]:
    """Every model's name and state, for /gazebo/model_states (static scenery first)."""
    static = scenery(sim)
    names = list(static) + list(sim.models)
    return names, list(static.values()) + [model_state(m) for m in sim.models.values()]


def link_states(sim: Simulation) -> Tuple[List[str], List[State]]:
    """Every link, scoped ``model::link``, for /gazebo/link_states."""
    names: List[str] = []
    states: List[State] = []
    for model in sim.models.values():
        for link, (pos, orn, lin, ang) in body_state.link_states(model.robot).items():
            names.append('%s::%s' % (model.name, link))
            states.append(State(pos, orn, lin, ang))
    return names, states


# --- properties ------------------------------------------------------------------------------


@dataclass
class ModelProperties:
    body_names: List[str]
    joint_names: List[str]
    is_static: bool


def get_model_properties(sim: Simulation, name: str) -> ModelProperties:
    model = sim.models.get(name)
    if model is None and name in scenery(sim):
        return ModelProperties([], [], True)  # pybullet keeps no links of scenery
    if model is None:
        raise StateError('GetModelProperties: model [%s] does not exist' % name)
    return ModelProperties(
        list(model.robot.link_index),
        list(model.robot.joint_index),
        model.description.root_link == 'world',
    )


def find_joint(sim: Simulation, name: str) -> Optional[Tuple[Model, str]]:
    """Bare or ``model::joint``; the first model, in spawn order, that has it."""
    for model in sim.models.values():
        bare = name[len(model.name) + 2 :] if name.startswith(model.name + '::') else name
        if bare in model.robot.joint_index:
            return model, bare
    return None


def get_joint_properties(sim: Simulation, name: str) -> Tuple[float, float]:
    """Position and rate of the joint's first axis."""
    found = find_joint(sim, name)
    if found is None:
        raise StateError('GetJointProperties: joint [%s] not found' % name)
    model, joint = found
    return body_state.joint_state(model.robot, joint)


def set_joint_properties(
    sim: Simulation,
    name: str,
    damping: Sequence[float],
    lo_stop: Sequence[float],
    hi_stop: Sequence[float],
) -> None:
    """Axis 0 of damping and the stops (empty arrays change nothing, as upstream); pybullet
    has no per-joint erp, cfm, fudge factor or ODE motor, so those fields are not applied."""
    found = find_joint(sim, name)
    if found is None:
        raise StateError('SetJointProperties: joint [%s] not found' % name)
    values = [list(a[:1]) for a in (damping, lo_stop, hi_stop)]
    if not finite(*values):
        raise StateError('SetJointProperties: joint [%s]: values must be finite' % name)
    d, lo, hi = (v[0] if v else None for v in values)
    if d is not None and d < 0:
        raise StateError('SetJointProperties: joint [%s]: damping %g is negative' % (name, d))
    model, joint = found
    body_state.set_joint_dynamics(model.robot, joint, d, lo, hi)


def get_link_properties(sim: Simulation, name: str) -> Tuple[float, Vec, Vec]:
    """Mass, centre of mass in the link frame, inertia diagonal."""
    found = find_link(sim, name)
    if found is None:
        raise StateError(
            'GetLinkProperties: link [%s] not found, did you forget to scope the '
            'link by model name?' % name
        )
    return body_state.link_properties(found[0].robot, found[1])


# --- physics properties --------------------------------------------------------------------


@dataclass
class PhysicsProperties:
    time_step: float
    max_update_rate: float
    gravity: Vec


def get_physics_properties(sim: Simulation) -> PhysicsProperties:
    c = sim.config
    return PhysicsProperties(c.max_step_size, c.real_time_update_rate, tuple(c.gravity))


def set_physics_properties(sim: Simulation, props: PhysicsProperties) -> None:
    """Gravity goes to pybullet at once; the update rate is the pacer's (the ROS layer hands
    it on); the time step can only be kept."""
    if not (math.isfinite(props.time_step) and props.time_step > 0):
        raise StateError(
            'SetPhysicsProperties: time_step %r is not a positive number' % props.time_step
        )
    if not finite(props.gravity) or not math.isfinite(props.max_update_rate):
        raise StateError('SetPhysicsProperties: gravity and max_update_rate must be finite')
    if props.time_step != sim.config.max_step_size:
        # Controllers' periods and the hardware's were fixed at spawn from the step length.
        raise StateError(
            'SetPhysicsProperties: time_step %g differs from the running %g: this '
            'stand-in cannot change it while running (set <max_step_size> in the '
            'world file)' % (props.time_step, sim.config.max_step_size)
        )
    sim.config.gravity = tuple(props.gravity)
    sim.config.real_time_update_rate = props.max_update_rate
    body_state.set_gravity(sim.world.client, props.gravity)
