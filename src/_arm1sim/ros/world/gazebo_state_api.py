"""gazebo_ros's state and property services and topics (upstream: gazebo_ros_api_plugin).

Requests are checked on rospy's threads as far as they can be without the world; what
reads or moves bodies runs on the physics thread (SimThreadCalls). /gazebo/model_states
and /gazebo/link_states go out before every step, from the physics thread, only while
someone subscribes (as Gazebo's WorldUpdateBegin connection).
"""

from __future__ import annotations

import collections
import threading
import time
from typing import Any, Callable, Deque, Dict, List, Optional, Tuple

import rospy
from gazebo_msgs.msg import LinkState, LinkStates, ModelState, ModelStates
from gazebo_msgs.srv import (
    ApplyBodyWrench,
    ApplyJointEffort,
    BodyRequest,
    GetJointProperties,
    GetLinkProperties,
    GetLinkState,
    GetModelProperties,
    GetModelState,
    GetPhysicsProperties,
    GetWorldProperties,
    JointRequest,
    SetJointProperties,
    SetLinkState,
    SetModelState,
    SetPhysicsProperties,
)
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3

from ...sim import model_state as ms
from ...sim.model_state import State, StateError
from ...sim.simulation import Simulation
from ...sim.wrenches import JointEfforts, Wrenches
from ..common.publishers import subscribed
from .sim_thread import SimThreadCalls
from .world_loop import WorldLoop


def state_from_msg(pose: Pose, twist: Twist) -> State:
    p, o = pose.position, pose.orientation
    return State((p.x, p.y, p.z), (o.x, o.y, o.z, o.w), _vec(twist.linear), _vec(twist.angular))


def pose_msg(state: State) -> Pose:
    return Pose(Point(*state.position), Quaternion(*state.orientation))


def twist_msg(state: State) -> Twist:
    return Twist(Vector3(*state.linear), Vector3(*state.angular))


def _vec(v: Any) -> Tuple[float, float, float]:
    return (v.x, v.y, v.z)


def states_msg(cls: Any, names: List[str], states: List[State]) -> Any:
    return cls(names, [pose_msg(s) for s in states], [twist_msg(s) for s in states])


MESSAGES_PER_SECOND = 2000.0  # wall-time cap of each states topic: twice real time's 1 kHz
BURST = 4  # readings the budget lets through back to back (the world runs 2 steps a wake-up)


class RateBudget:
    """A token bucket in wall time: at real time every step gets its message (as in Gazebo);
    faster than that, at most ``rate`` a second, so that a subscriber to /gazebo/model_states
    cannot halve the world's top speed (Python builds and sends each message)."""

    def __init__(
        self, rate: float, burst: int, clock: Callable[[], float] = time.monotonic
    ) -> None:
        self.rate, self.burst, self.clock = rate, float(burst), clock
        self._tokens = float(burst)
        self._last = clock()

    def take(self) -> bool:
        now = self.clock()
        self._tokens = min(self.burst, self._tokens + (now - self._last) * self.rate)
        self._last = now
        if self._tokens < 1.0:
            return False
        self._tokens -= 1.0
        return True


class LatestPublisher:
    """Builds and publishes states messages on its own thread, so the physics thread only
    reads pybullet, and only within its RateBudget. If publishing lags, the oldest readings
    are dropped."""

    def __init__(self, publisher: Any, cls: Any) -> None:
        self.publisher, self.cls = publisher, cls
        self.budget = RateBudget(MESSAGES_PER_SECOND, BURST)
        self._cond = threading.Condition()
        self._pending: Deque[Tuple[List[str], List[State]]] = collections.deque(maxlen=BURST)
        self._stopped = False
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def wanted(self) -> bool:
        """Subscribed, and within the budget (physics thread, before gathering a reading)."""
        return subscribed(self.publisher) and self.budget.take()

    def put(self, reading: Tuple[List[str], List[State]]) -> None:
        with self._cond:
            self._pending.append(reading)
            self._cond.notify()

    def stop(self) -> None:
        with self._cond:
            self._stopped = True
            self._cond.notify()

    def _run(self) -> None:
        while True:
            with self._cond:
                while not self._pending and not self._stopped:
                    self._cond.wait()
                if self._stopped:
                    return
                reading = self._pending.popleft()
            try:
                self.publisher.publish(states_msg(self.cls, *reading))
            except rospy.ROSException:
                return  # shutting down


class GazeboStateApi:
    def __init__(
        self,
        sim: Simulation,
        calls: SimThreadCalls,
        loop: WorldLoop,
        on_update_rate: Optional[Callable[[float], None]] = None,
    ) -> None:
        self.sim, self.calls, self.loop = sim, calls, loop
        self.on_update_rate = on_update_rate
        self.wrenches = Wrenches()
        self.efforts = JointEfforts()
        self._seq: Dict[str, int] = {}  # get_model_state's header.seq, per model as upstream
        self._services = [
            rospy.Service('~get_model_state', GetModelState, self._get_model_state),
            rospy.Service('~set_model_state', SetModelState, self._set_model_state),
            rospy.Service('~get_link_state', GetLinkState, self._get_link_state),
            rospy.Service('~get_model_properties', GetModelProperties, self._model_properties),
            rospy.Service('~get_world_properties', GetWorldProperties, self._world_properties),
            rospy.Service('~get_link_properties', GetLinkProperties, self._link_properties),
            rospy.Service('~get_joint_properties', GetJointProperties, self._joint_properties),
            rospy.Service('~apply_body_wrench', ApplyBodyWrench, self._apply_body_wrench),
            rospy.Service('~clear_body_wrenches', BodyRequest, self._clear_body_wrenches),
            rospy.Service('~set_link_state', SetLinkState, self._set_link_state),
            rospy.Service('~apply_joint_effort', ApplyJointEffort, self._apply_joint_effort),
            rospy.Service('~clear_joint_forces', JointRequest, self._clear_joint_forces),
            rospy.Service('~set_joint_properties', SetJointProperties, self._set_joint_props),
            rospy.Service('~get_physics_properties', GetPhysicsProperties, self._get_physics),
            rospy.Service('~set_physics_properties', SetPhysicsProperties, self._set_physics),
        ]
        self.model_states = rospy.Publisher('~model_states', ModelStates, queue_size=10)
        self.link_states = rospy.Publisher('~link_states', LinkStates, queue_size=10)
        self._model_out = LatestPublisher(self.model_states, ModelStates)
        self._link_out = LatestPublisher(self.link_states, LinkStates)
        self._subscribers = [
            rospy.Subscriber(
                '~set_model_state', ModelState, self._set_model_state_topic, queue_size=10
            )
        ]
        sim.before_step.append(self._before_step)

    def shutdown(self) -> None:
        for s in self._services:
            s.shutdown()
        for sub in self._subscribers:
            sub.unregister()
        self._model_out.stop()
        self._link_out.stop()
        if self._before_step in self.sim.before_step:
            self.sim.before_step.remove(self._before_step)

    # Physics thread, before every step.
    def _before_step(self, now_ns: int) -> None:
        if self.wrenches.jobs:
            self.wrenches.apply(self.sim, now_ns)
        if self.efforts.jobs:
            self.efforts.apply(self.sim, now_ns)
        if self._model_out.wanted():
            self._model_out.put(ms.model_states(self.sim))
        if self._link_out.wanted():
            self._link_out.put(ms.link_states(self.sim))

    def _get_model_state(self, req: Any) -> Any:
        res = GetModelState._response_class()
        res.header.frame_id = req.relative_entity_name
        try:
            state = self.calls.call(
                ms.get_model_state, self.sim, req.model_name, req.relative_entity_name
            )
        except StateError as exc:
            res.success, res.status_message = False, str(exc)
            return res
        self._seq[req.model_name] = self._seq.get(req.model_name, 0) + 1
        res.header.seq = self._seq[req.model_name]
        res.header.stamp = rospy.Time.now()
        res.pose, res.twist = pose_msg(state), twist_msg(state)
        res.success, res.status_message = True, 'GetModelState: got properties'
        return res

    def _set(self, m: Any) -> Tuple[bool, str]:
        try:
            self.calls.call(
                ms.set_model_state,
                self.sim,
                m.model_name,
                state_from_msg(m.pose, m.twist),
                m.reference_frame,
            )
        except StateError as exc:
            return False, str(exc)
        return True, 'SetModelState: set model state done'

    def _set_model_state(self, req: Any) -> Tuple[bool, str]:
        return self._set(req.model_state)

    def _set_model_state_topic(self, msg: Any) -> None:
        ok, message = self._set(msg)  # upstream discards the result; we log a refusal
        if not ok:
            rospy.logwarn(message)

    def _set_link(self, m: Any) -> Tuple[bool, str]:
        try:
            self.calls.call(
                ms.set_link_state,
                self.sim,
                m.link_name,
                state_from_msg(m.pose, m.twist),
                m.reference_frame,
            )
        except StateError as exc:
            return False, str(exc)
        return True, 'SetLinkState: success'

    def _set_link_state(self, req: Any) -> Tuple[bool, str]:
        return self._set_link(req.link_state)

    def _set_link_state_topic(self, msg: Any) -> None:
        ok, message = self._set_link(msg)
        if not ok:
            rospy.logwarn(message)

    def _apply_joint_effort(self, req: Any) -> Tuple[bool, str]:
        try:
            self.calls.call(
                self.efforts.add,
                self.sim,
                req.joint_name,
                req.effort,
                req.start_time.to_nsec(),
                req.duration.to_nsec(),
            )
        except StateError as exc:
            return False, str(exc)
        return True, 'ApplyJointEffort: effort set'

    def _clear_joint_forces(self, req: Any) -> List[Any]:
        self.calls.call(self.efforts.clear, req.joint_name)
        return []

    def _get_link_state(self, req: Any) -> Any:
        res = GetLinkState._response_class()
        try:
            state = self.calls.call(ms.get_link_state, self.sim, req.link_name, req.reference_frame)
        except StateError as exc:
            res.success, res.status_message = False, str(exc)
            return res
        res.link_state = LinkState(
            req.link_name, pose_msg(state), twist_msg(state), req.reference_frame
        )
        res.success, res.status_message = True, 'GetLinkState: got state'
        return res

    def _model_properties(self, req: Any) -> Any:
        res = GetModelProperties._response_class()
        try:
            props = self.calls.call(ms.get_model_properties, self.sim, req.model_name)
        except StateError as exc:
            res.success, res.status_message = False, str(exc)
            return res
        res.body_names, res.joint_names = props.body_names, props.joint_names
        res.geom_names = ['%s_collision' % b for b in props.body_names]
        res.is_static = props.is_static
        res.success, res.status_message = True, 'GetModelProperties: got properties'
        return res

    def _world_properties(self, req: Any) -> Any:
        names, t = self.calls.call(lambda: (ms.model_names(self.sim), self.sim.time_ns))
        return GetWorldProperties._response_class(
            t * 1e-9, names, True, True, 'GetWorldProperties: got properties'
        )

    def _link_properties(self, req: Any) -> Any:
        res = GetLinkProperties._response_class()
        try:
            mass, com, inertia = self.calls.call(ms.get_link_properties, self.sim, req.link_name)
        except StateError as exc:
            res.success, res.status_message = False, str(exc)
            return res
        res.com = Pose(Point(*com), Quaternion(0, 0, 0, 1))
        res.gravity_mode, res.mass = True, mass
        res.ixx, res.iyy, res.izz = inertia
        res.success, res.status_message = True, 'GetLinkProperties: got properties'
        return res

    def _joint_properties(self, req: Any) -> Any:
        res = GetJointProperties._response_class()
        try:
            position, rate = self.calls.call(ms.get_joint_properties, self.sim, req.joint_name)
        except StateError as exc:
            res.success, res.status_message = False, str(exc)
            return res
        res.type = GetJointProperties._response_class.REVOLUTE  # always 0 upstream
        res.position, res.rate = [position], [rate]
        res.success, res.status_message = True, 'GetJointProperties: got properties'
        return res

    def _set_joint_props(self, req: Any) -> Tuple[bool, str]:
        c = req.ode_joint_config
        try:
            self.calls.call(
                ms.set_joint_properties, self.sim, req.joint_name, c.damping, c.loStop, c.hiStop
            )
        except StateError as exc:
            return False, str(exc)
        ignored = [
            f
            for f in ('erp', 'cfm', 'stop_erp', 'stop_cfm', 'fudge_factor', 'fmax', 'vel')
            if getattr(c, f)
        ]
        if ignored:
            rospy.logwarn(
                'SetJointProperties: %s of joint [%s] not applied (pybullet has no such setting)',
                ', '.join(ignored),
                req.joint_name,
            )
        return True, 'SetJointProperties: properties set'

    def _apply_body_wrench(self, req: Any) -> Tuple[bool, str]:
        w = req.wrench
        try:
            self.calls.call(
                self.wrenches.add,
                self.sim,
                req.body_name,
                req.reference_frame,
                _vec(req.reference_point),
                _vec(w.force),
                _vec(w.torque),
                req.start_time.to_nsec(),
                req.duration.to_nsec(),
            )
        except StateError as exc:
            return False, str(exc)
        return True, ''

    def _clear_body_wrenches(self, req: Any) -> List[Any]:
        self.calls.call(self.wrenches.clear, req.body_name)
        return []

    def _get_physics(self, req: Any) -> Any:
        props = self.calls.call(ms.get_physics_properties, self.sim)
        res = GetPhysicsProperties._response_class()
        res.time_step, res.pause = props.time_step, self.loop.paused
        res.max_update_rate, res.gravity = props.max_update_rate, Vector3(*props.gravity)
        res.success, res.status_message = True, 'GetPhysicsProperties: got properties'
        return res

    def _set_physics(self, req: Any) -> Tuple[bool, str]:
        props = ms.PhysicsProperties(req.time_step, req.max_update_rate, _vec(req.gravity))
        try:
            self.calls.call(ms.set_physics_properties, self.sim, props)
        except StateError as exc:
            return False, str(exc)
        if self.on_update_rate is not None:
            self.calls.call(self.on_update_rate, props.max_update_rate)
        return True, 'physics engine updated'
