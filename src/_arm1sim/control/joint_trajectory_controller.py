"""effort_controllers/JointTrajectoryController, as ros_controllers' joint_trajectory_controller.

Trajectories arrive on the ``command`` topic and the ``follow_joint_trajectory`` action
(any thread); ``update`` runs on the physics thread. One lock guards the trajectory, the
active goal and the time data; ``update`` needs it every step, so a new trajectory is
validated and its segments built outside it (from a snapshot of the time data, as
upstream builds from its realtime buffer) and only swapped in under it. A second lock lets
one trajectory be built at a time. Goal handles are told their fate from the callbacks
under the lock (actionlib calls them without its own lock, as its C++ server does), but
from ``update`` only after it is released.
"""

from __future__ import annotations

import logging
import math
import threading
from typing import Any, ClassVar, Dict, List, Mapping, NamedTuple, Optional, Sequence, Tuple

from .angles import shortest_angular_distance
from .controller import Controller, ControllerError, require_param
from .hardware_interface import (
    EFFORT_JOINT_INTERFACE,
    POSITION_JOINT_INTERFACE,
    VELOCITY_JOINT_INTERFACE,
)
from .interfaces import Fields, GoalHandle, NodeHandle, Publisher, RobotHW
from .message_types import (
    FOLLOW_JOINT_TRAJECTORY_GOAL,
    QUERY_TRAJECTORY_STATE,
    STAMPED,
    TRAJECTORY,
    TRAJECTORY_STATE,
    register_action,
    register_message,
    register_service,
)
from .pid import Pid, PidConfigError
from .trajectory import (
    JointTrajectory,
    Segment,
    State,
    Tolerance,
    Tolerances,
    find_segment,
    hold_segment,
    sample,
    wrap_offset,
)

log = logging.getLogger('_arm1sim.control')

register_message('control_msgs/JointTrajectoryControllerState', TRAJECTORY_STATE)
register_message('trajectory_msgs/JointTrajectory', STAMPED, TRAJECTORY)  # the command
register_action(
    'control_msgs/FollowJointTrajectory', FOLLOW_JOINT_TRAJECTORY_GOAL, TRAJECTORY_STATE
)
register_service('control_msgs/QueryTrajectoryState', QUERY_TRAJECTORY_STATE)

# control_msgs/FollowJointTrajectoryResult error codes
SUCCESSFUL = 0
INVALID_GOAL = -1
INVALID_JOINTS = -2
OLD_HEADER_TIMESTAMP = -3  # never used, as upstream
PATH_TOLERANCE_VIOLATED = -4
GOAL_TOLERANCE_VIOLATED = -5
ERROR_CODE_NAMES = {  # for reports: code -> the constant's name in the message
    SUCCESSFUL: 'SUCCESSFUL',
    INVALID_GOAL: 'INVALID_GOAL',
    INVALID_JOINTS: 'INVALID_JOINTS',
    OLD_HEADER_TIMESTAMP: 'OLD_HEADER_TIMESTAMP',
    PATH_TOLERANCE_VIOLATED: 'PATH_TOLERANCE_VIOLATED',
    GOAL_TOLERANCE_VIOLATED: 'GOAL_TOLERANCE_VIOLATED',
}

NS = 1e-9


class TrajectoryError(ValueError):
    """A trajectory that cannot be taken; the message says why, as upstream's log does."""

    def __init__(self, message: str, code: int = INVALID_GOAL) -> None:
        super().__init__(message)
        self.code = code


def _float(value: Any, what: str, ns: str) -> float:
    try:
        f = float(value)
    except (TypeError, ValueError):
        raise ControllerError('%s/%s: %r is not a number' % (ns, what, value))
    if not math.isfinite(f):
        raise ControllerError('%s/%s: %r is not finite' % (ns, what, value))
    return f


class _Now(NamedTuple):
    """The time data and trajectory a new trajectory is built against (taken under the lock)."""

    time_ns: int
    period_ns: int
    uptime: float
    trajectory: List[JointTrajectory]
    generation: int  # starting() counts up: a build across a restart is stale


class JointTrajectoryController(Controller):
    type_name = 'effort_controllers/JointTrajectoryController'
    interface = EFFORT_JOINT_INTERFACE
    # The hardware_interface_adapter: velocity and effort joints get velocity_ff * v + PID
    # per joint (gains required); position joints the desired position (gains ignored).
    commands_position: ClassVar[bool] = False

    _state_pub: Publisher

    def __init__(self) -> None:
        super().__init__()
        self.joint_names: List[str] = []
        self.pids: List[Pid] = []
        self.velocity_ff: List[float] = []
        self.default_tolerances: List[Tolerances] = []
        self.continuous: List[bool] = []
        self.state_publish_period = 1 / 50.0
        self.action_monitor_period = 1 / 20.0
        self.stop_trajectory_duration = 0.0
        self.allow_partial = False
        self._lock = threading.Lock()
        self._build_lock = threading.Lock()  # one new trajectory built at a time
        self._generation = 0
        self.trajectory: List[JointTrajectory] = []
        self._active: Optional[GoalHandle] = None
        self._done: List[bool] = []
        # Time data: ROS time of the last update and its period (ns), uptime (s).
        self._time_ns = 0
        self._period_ns = 0
        self.uptime = 0.0
        self._last_state_pub = 0.0
        self._last_feedback = 0.0
        self._feedback: Optional[Dict[str, Any]] = None

    # -- init ------------------------------------------------------------------------------
    def init(self, robot_hw: RobotHW, root_nh: NodeHandle, controller_nh: NodeHandle) -> None:
        ns, params = controller_nh.namespace, controller_nh.params
        joints = require_param(params, 'joints', ns)
        if not (isinstance(joints, list) and joints and all(isinstance(j, str) for j in joints)):
            raise ControllerError(
                "%s: the 'joints' parameter is not a non-empty array of strings: %r" % (ns, joints)
            )
        if len(set(joints)) != len(joints):
            raise ControllerError('%s: joints %r name a joint twice' % (ns, joints))
        self.joint_names = list(joints)
        self.joints = [robot_hw.get_handle(j, self.interface, ns) for j in joints]
        self.continuous = [h.type == 'continuous' for h in self.joints]
        gains = params.get('gains', {})
        ff = params.get('velocity_ff', {})
        if not isinstance(gains, dict) or not isinstance(ff, dict):
            raise ControllerError("%s: 'gains' and 'velocity_ff' must be maps by joint" % ns)
        try:
            self.pids = [
                Pid()
                if self.commands_position
                else Pid.from_params(gains.get(j), '%s/gains/%s' % (ns, j))
                for j in joints
            ]
        except PidConfigError as exc:  # upstream loads half-built and crashes later
            raise ControllerError(str(exc))
        self.velocity_ff = [_float(ff.get(j, 0.0), 'velocity_ff/' + j, ns) for j in joints]
        constraints = params.get('constraints', {})
        if not isinstance(constraints, dict):
            raise ControllerError("%s: 'constraints' must be a map" % ns)
        goal_time = _float(constraints.get('goal_time', 0.0), 'constraints/goal_time', ns)
        stopped = _float(
            constraints.get('stopped_velocity_tolerance', 0.01),
            'constraints/stopped_velocity_tolerance',
            ns,
        )
        self.default_tolerances = []
        for j in joints:
            c = constraints.get(j, {})
            if not isinstance(c, dict):
                raise ControllerError("%s: 'constraints/%s' must be a map" % (ns, j))
            self.default_tolerances.append(
                Tolerances(
                    path=Tolerance(
                        position=_float(
                            c.get('trajectory', 0.0), 'constraints/%s/trajectory' % j, ns
                        )
                    ),
                    goal=Tolerance(
                        position=_float(c.get('goal', 0.0), 'constraints/%s/goal' % j, ns),
                        velocity=stopped,
                    ),
                    goal_time=goal_time,
                )
            )
        for key, attr in (
            ('state_publish_rate', 'state_publish_period'),
            ('action_monitor_rate', 'action_monitor_period'),
        ):
            rate = _float(params.get(key, 50.0 if key == 'state_publish_rate' else 20.0), key, ns)
            if rate <= 0:
                raise ControllerError('%s/%s must be positive, not %g' % (ns, key, rate))
            setattr(self, attr, 1.0 / rate)
        self.stop_trajectory_duration = max(
            0.0, _float(params.get('stop_trajectory_duration', 0.0), 'stop_trajectory_duration', ns)
        )
        self.allow_partial = bool(params.get('allow_partial_joints_goal', False))
        self._state_pub = controller_nh.advertise(
            'state', 'control_msgs/JointTrajectoryControllerState', 1
        )
        controller_nh.subscribe('command', 'trajectory_msgs/JointTrajectory', self.on_command)
        controller_nh.action_server(
            'follow_joint_trajectory',
            'control_msgs/FollowJointTrajectory',
            self.on_goal,
            self.on_cancel,
        )
        controller_nh.serve('query_state', 'control_msgs/QueryTrajectoryState', self.query_state)

    # -- run state -------------------------------------------------------------------------
    def starting(self, time_ns: int) -> None:
        with self._lock:
            self._time_ns, self._period_ns, self.uptime = time_ns, 0, 0.0
            self._generation += 1
            self._last_state_pub = self._last_feedback = 0.0
            self.trajectory = []  # desired = measured on start, not a previous run's
            self.trajectory = [[self._hold(i)] for i in range(len(self.joints))]
            self._done = [False] * len(self.joints)
            for pid, j in zip(self.pids, self.joints):
                pid.reset()
                j.command = j.position if self.commands_position else 0.0

    def stopping(self, time_ns: int) -> None:
        with self._lock:
            active, self._active = self._active, None
        if active is not None:
            active.cancel(dict(error_code=SUCCESSFUL, error_string=''))
        if not self.commands_position:  # no effort or velocity left behind
            for j in self.joints:
                j.command = 0.0

    def _hold(
        self, i: int, goal: Optional[GoalHandle] = None, tolerances: Optional[Tolerances] = None
    ) -> Segment:
        """Joint i's hold from now on (upstream's setHoldPosition; lock held)."""
        if self.stop_trajectory_duration > 0 and self.trajectory:
            _, (p, v, _) = sample(self.trajectory[i], self.uptime)
        else:
            p, v = self.joints[i].position, self.joints[i].velocity
        seg = hold_segment(self.uptime, p, v, self.stop_trajectory_duration)
        seg.goal, seg.tolerances = goal, tolerances or self.default_tolerances[i]
        return seg

    # -- new trajectories (any thread) -----------------------------------------------------
    def on_command(self, msg: Fields) -> None:
        """The ``command`` topic: errors are logged, an accepted one preempts the goal."""
        preempted = None
        with self._build_lock:
            now = self._now()
            if now is None:
                log.error("%s: Can't accept new commands. Controller is not running.", self.name)
                return
            try:
                built = self._build(msg, None, None, now)
            except TrajectoryError as exc:
                log.error('%s: %s', self.name, exc)
                return
            with self._lock:
                if not self._commit(built, None, None, now):
                    log.error('%s: controller stopped or restarted: command dropped', self.name)
                    return
                preempted, self._active = self._active, None
        if preempted is not None:  # outside the lock: this thread holds no actionlib lock
            preempted.cancel(dict(error_code=SUCCESSFUL, error_string=''))

    def on_goal(self, gh: GoalHandle) -> None:
        """A FollowJointTrajectory goal: accepted (preempting the active one) or rejected."""
        with self._build_lock:
            now = self._now()
            if now is None:
                gh.reject(
                    dict(
                        error_code=INVALID_GOAL,
                        error_string="Can't accept new action goals. Controller is not running.",
                    )
                )
                return
            try:
                goal = gh.goal
                traj = goal.get('trajectory') or {}
                self._check_joints(list(traj.get('joint_names') or []))
                tolerances = self._goal_tolerances(goal)
                built = self._build(traj, gh, tolerances, now)
            except TrajectoryError as exc:
                log.error('%s: rejecting goal: %s', self.name, exc)
                gh.reject(dict(error_code=exc.code, error_string=str(exc)))
                return
            with self._lock:
                if not self._commit(built, gh, tolerances, now):
                    gh.reject(
                        dict(
                            error_code=INVALID_GOAL,
                            error_string='The controller stopped or restarted while the goal '
                            'was being taken.',
                        )
                    )
                    return
                previous, self._active = self._active, gh
                self._done = [False] * len(self.joints)
                if previous is not None:
                    previous.cancel(dict(error_code=SUCCESSFUL, error_string=''))
                gh.accept()

    def _now(self) -> Optional[_Now]:
        with self._lock:
            if not self.running:
                return None
            return _Now(
                self._time_ns, self._period_ns, self.uptime, self.trajectory, self._generation
            )

    def _commit(
        self,
        built: Optional[List[JointTrajectory]],
        gh: Optional[GoalHandle],
        tolerances: Optional[List[Tolerances]],
        now: _Now,
    ) -> bool:
        """Swap in a built trajectory (None: hold from now on; lock held); False when the
        controller stopped or restarted since ``now``."""
        if not self.running or self._generation != now.generation:
            return False
        if built is None:
            tol = tolerances or self.default_tolerances
            built = [[self._hold(i, gh, tol[i])] for i in range(len(self.joints))]
        self.trajectory = built
        return True

    def on_cancel(self, gh: GoalHandle) -> None:
        """Cancelling the active goal holds the arm (PREEMPTED); any other: nothing."""
        with self._lock:
            if self._active is None or self._active.id != gh.id:
                return
            self.trajectory = [[self._hold(i)] for i in range(len(self.joints))]
            self._active = None
            gh.cancel(dict(error_code=SUCCESSFUL, error_string=''))

    def _check_joints(self, names: Sequence[str]) -> None:
        unknown = [n for n in names if n not in self.joint_names]
        if unknown:
            raise TrajectoryError(
                'Joint(s) %s are not controlled by %s (its joints: %s)'
                % (', '.join(map(repr, unknown)), self.name, ', '.join(self.joint_names)),
                INVALID_JOINTS,
            )
        dup = sorted({n for n in names if list(names).count(n) > 1})
        if dup:
            raise TrajectoryError(
                'Joint(s) %s named more than once' % ', '.join(dup), INVALID_JOINTS
            )
        if not self.allow_partial and len(names) != len(self.joint_names):
            missing = [n for n in self.joint_names if n not in names]
            raise TrajectoryError(
                'Cannot create trajectory from message. It does not contain '
                'the expected joints (missing: %s; allow_partial_joints_goal '
                'is false).' % ', '.join(missing),
                INVALID_JOINTS,
            )

    def _goal_tolerances(self, goal: Fields) -> List[Tolerances]:
        """The defaults, overridden by the goal: > 0 sets, < 0 erases, 0 keeps."""
        out = [
            Tolerances(Tolerance(**vars(t.path)), Tolerance(**vars(t.goal)), t.goal_time)
            for t in self.default_tolerances
        ]

        def merge(tol: Tolerance, given: Mapping[str, Any]) -> None:
            for key in ('position', 'velocity', 'acceleration'):
                value = float(given.get(key, 0.0))
                if not math.isfinite(value):
                    raise TrajectoryError(
                        'tolerance %s of joint %s is %r' % (key, given.get('name'), value)
                    )
                if value > 0:
                    setattr(tol, key, value)
                elif value < 0:
                    setattr(tol, key, 0.0)

        for field, pick in (
            ('path_tolerance', lambda t: t.path),
            ('goal_tolerance', lambda t: t.goal),
        ):
            entries: Sequence[Mapping[str, Any]] = goal.get(field) or []
            for entry in entries:
                name = entry.get('name')
                if name not in self.joint_names:
                    raise TrajectoryError(
                        '%s names joint %r, which %s does not control' % (field, name, self.name),
                        INVALID_JOINTS,
                    )
                merge(pick(out[self.joint_names.index(name)]), entry)
        gtt = goal.get('goal_time_tolerance', 0) * NS
        for t in out:
            if gtt > 0:
                t.goal_time = gtt
            elif gtt < 0:
                t.goal_time = 0.0
        return out

    def _build(
        self,
        msg: Fields,
        gh: Optional[GoalHandle],
        tolerances: Optional[List[Tolerances]],
        now: _Now,
    ) -> Optional[List[JointTrajectory]]:
        """Validate ``msg`` and merge it into the trajectory of ``now`` (no lock held: this is
        the long part for a long trajectory). None for an empty trajectory (hold); raises
        TrajectoryError when it cannot be taken."""
        points: List[Mapping[str, Any]] = list(msg.get('points') or [])
        tol = tolerances or self.default_tolerances
        if not points:  # an empty trajectory means: hold
            return None
        times = [int(p.get('time_from_start', 0)) for p in points]
        if any(b <= a for a, b in zip(times, times[1:])):
            raise TrajectoryError(
                'Trajectory message contains waypoints that are not strictly increasing in time.'
            )
        names = list(msg.get('joint_names') or [])
        self._check_joints(names)
        n = len(names)
        for k, point in enumerate(points):
            pos = list(point.get('positions') or [])
            vel = list(point.get('velocities') or [])
            acc = list(point.get('accelerations') or [])
            if not pos:
                raise TrajectoryError(
                    "Quintic spline segment can't be constructed: Endpoint "
                    "positions can't be empty (point %d)." % k
                )
            if len(pos) != n:
                raise TrajectoryError(
                    'Point %d has %d positions for %d joints (%s).'
                    % (k, len(pos), n, ', '.join(names))
                )
            if (vel and len(vel) != n) or (acc and len(acc) != n):
                raise TrajectoryError(
                    'Size mismatch in trajectory point position, velocity or '
                    'acceleration data (point %d).' % k
                )
            for field, values in (('positions', pos), ('velocities', vel), ('accelerations', acc)):
                for j, v in enumerate(values):
                    if not math.isfinite(float(v)):
                        raise TrajectoryError(
                            'Point %d: %s of joint %s is %r.' % (k, field, names[j], v)
                        )
        # Times in uptime: the next update happens at uptime + period, ROS time time + period.
        next_ros = now.time_ns + now.period_ns
        next_up = now.uptime + now.period_ns * NS
        stamp = int(msg.get('stamp', 0))
        start_up = next_up + ((stamp - next_ros) * NS if stamp else 0.0)
        first = next((k for k, t in enumerate(times) if start_up + t * NS > next_up), None)
        if first is None:
            raise TrajectoryError(
                'Dropping all %d trajectory point(s), as they occur before the '
                'current time.\nLast point is %fs in the past.'
                % (len(points), next_up - (start_up + times[-1] * NS))
            )
        if first > 0 and not (first == 1 and times[0] == 0 and not stamp):
            log.warning(
                '%s: dropping first %d trajectory point(s) out of %d, as they occur '
                'before the current time.',
                self.name,
                first,
                len(points),
            )
        new: List[JointTrajectory] = [list(t) for t in now.trajectory]
        bridge_start = max(start_up, next_up)
        for j, name in enumerate(names):
            i = self.joint_names.index(name)
            cur = now.trajectory[i]
            k0 = max(find_segment(cur, next_up), 0)
            k1 = max(find_segment(cur, start_up), 0)
            kept = cur[k0 : max(k0, k1) + 1]
            _, (p, v, a) = sample(kept, bridge_start)
            states = [_state(pt, j) for pt in points[first:]]
            if self.continuous[i]:
                off = wrap_offset(states[0].position, p)
                for s in states:
                    s.position += off
            joint_traj = list(kept)
            t_prev, s_prev = bridge_start, State(p, v, a)
            for pt_time, s in zip(times[first:], states):
                t = start_up + pt_time * NS
                seg = Segment(t_prev, s_prev, t, s, gh, tol[i])
                seg.start_point_time = t_prev - start_up
                joint_traj.append(seg)
                t_prev, s_prev = t, s
            new[i] = joint_traj
        return new

    # -- the control cycle (physics thread) ------------------------------------------------
    def update(self, time_ns: int, period_ns: int) -> None:
        outcomes: List[Tuple[GoalHandle, str, Dict[str, Any]]] = []
        feedback: Optional[Tuple[GoalHandle, Dict[str, Any]]] = None
        with self._lock:
            self._time_ns, self._period_ns = time_ns, max(period_ns, 0)
            self.uptime += self._period_ns * NS
            dt = self._period_ns * NS
            desired: List[Tuple[float, float, float]] = []
            errors: List[Tuple[float, float]] = []
            seg_time = 0.0
            for i, joint in enumerate(self.joints):
                traj = self.trajectory[i]
                k, (p, v, a) = sample(traj, self.uptime)
                seg = traj[k]
                seg_time = seg.start_point_time
                e_pos = shortest_angular_distance(joint.position, p)
                e_vel = v - joint.velocity
                desired.append((p, v, a))
                errors.append((e_pos, e_vel))
                if self.commands_position:
                    joint.command = p
                else:
                    joint.command = self.velocity_ff[i] * v + self.pids[i].compute_command(
                        e_pos, dt, e_vel
                    )
                active = self._active
                if active is None or seg.goal is None or seg.goal.id != active.id:
                    continue
                tol = seg.tolerances
                if self.uptime < seg.end:
                    if not tol.path.holds(e_pos, e_vel):
                        outcomes.append(
                            _abort(
                                active, PATH_TOLERANCE_VIOLATED, 'path', self.joint_names[i], e_pos
                            )
                        )
                        self._active = None
                elif k == len(traj) - 1:
                    if tol.goal.holds(e_pos, e_vel):
                        self._done[i] = True
                    elif self.uptime >= seg.end + tol.goal_time and not self._done[i]:
                        outcomes.append(
                            _abort(
                                active, GOAL_TOLERANCE_VIOLATED, 'goal', self.joint_names[i], e_pos
                            )
                        )
                        self._active = None
            active = self._active
            if active is not None and all(
                self._goal_joint_done(i, active) for i in range(len(self.joints))
            ):
                outcomes.append((active, 'succeed', dict(error_code=SUCCESSFUL, error_string='')))
                self._active = None
            if self._active is None:
                self._done = [False] * len(self.joints)
            state = self._state_fields(time_ns, desired, errors, seg_time)
            if self.uptime - self._last_state_pub >= self.state_publish_period - 1e-9:
                self._last_state_pub = self.uptime
                self._state_pub.publish(state)
            if (
                self._active is not None
                and self.uptime - self._last_feedback >= self.action_monitor_period - 1e-9
            ):
                self._last_feedback = self.uptime
                feedback = (self._active, state)
        for gh, what, result in outcomes:  # outside the lock: see the module docstring
            getattr(gh, what)(result)
        if feedback is not None:
            feedback[0].publish_feedback(feedback[1])

    def _goal_joint_done(self, i: int, active: GoalHandle) -> bool:
        """A joint the goal does not move (a partial goal) counts as done."""
        if self._done[i]:
            return True
        # A goal's segments end every trajectory it moves: the last one tells (a scan of a
        # 100 000-segment trajectory each step would not do).
        last = self.trajectory[i][-1].goal
        return last is None or last.id != active.id

    def _state_fields(
        self,
        time_ns: int,
        desired: Sequence[Tuple[float, float, float]],
        errors: Sequence[Tuple[float, float]],
        seg_time: float,
    ) -> Dict[str, Any]:
        actual_time = seg_time  # upstream: start waypoint time + time in segment
        return dict(
            stamp=time_ns,
            joint_names=list(self.joint_names),
            desired=dict(
                positions=[d[0] for d in desired],
                velocities=[d[1] for d in desired],
                accelerations=[d[2] for d in desired],
                time_from_start=seg_time,
            ),
            actual=dict(
                positions=[j.position for j in self.joints],
                velocities=[j.velocity for j in self.joints],
                time_from_start=actual_time,
            ),
            error=dict(
                positions=[e[0] for e in errors],
                velocities=[e[1] for e in errors],
                time_from_start=0.0,
            ),
        )

    # -- query_state (any thread) ----------------------------------------------------------
    def query_state(self, request: Fields) -> Dict[str, Any]:
        with self._lock:
            if not self.running:
                raise ValueError("Can't sample trajectory. Controller is not running.")
            t = self.uptime + (int(request.get('time', 0)) - self._time_ns) * NS
            out: Dict[str, Any] = dict(
                name=list(self.joint_names), position=[], velocity=[], acceleration=[]
            )
            for traj in self.trajectory:
                if not traj or t < traj[0].start:
                    raise ValueError('Requested sample time precedes trajectory start time.')
                _, (p, v, a) = sample(traj, t)
                out['position'].append(p)
                out['velocity'].append(v)
                out['acceleration'].append(a)
            return out


def _abort(
    goal: GoalHandle, code: int, which: str, joint: str, error: float
) -> Tuple[GoalHandle, str, Dict[str, Any]]:
    """An abort outcome with upstream's error string ('<joint> path|goal error <e>')."""
    text = '%s %s error %f' % (joint, which, error)
    return goal, 'abort', dict(error_code=code, error_string=text)


def _state(point: Mapping[str, Any], j: int) -> State:
    vel = point.get('velocities') or []
    acc = point.get('accelerations') or []
    return State(
        float(point['positions'][j]),
        float(vel[j]) if vel else None,
        float(acc[j]) if acc and vel else None,
    )


class PositionJointTrajectoryController(JointTrajectoryController):
    type_name = 'position_controllers/JointTrajectoryController'
    interface = POSITION_JOINT_INTERFACE
    commands_position = True


class VelocityJointTrajectoryController(JointTrajectoryController):
    type_name = 'velocity_controllers/JointTrajectoryController'
    interface = VELOCITY_JOINT_INTERFACE
