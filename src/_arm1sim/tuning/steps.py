"""Step responses of a robot's position controllers on a headless Simulation at top speed.

The robot runs exactly as under ``roslaunch arm1 gazebo.launch``: the same
Simulation (pybullet world from the world file), DefaultRobotHWSim with its effort
saturation, ControllerManager, JointPositionController and Pid. Only the node
handles differ: parameters come from the controllers yaml and topics are
in-process (local_ros), and nothing waits for the wall clock.

The step protocol, for one joint at a time (the others hold their start):

1. every joint is put at rest at the start pose and the controllers restart
   (each holds where it is, the PID is reset), with the gains under test;
2. ``settle`` s of holding; then the command jumps by ``step`` rad ("out"),
   upwards unless that would leave the joint's URDF range, then downwards;
3. ``hold`` s later it jumps back to the start ("back"); ``hold`` s more.

Both steps are measured (metrics.py). A protocol may name more start poses; the
runs are then repeated from each (Protocol.variants). For arm1 the start pose is
joint2 = 1.0 rad (upper arm raised 57 degrees, 0.57 rad below its upper limit) and
the others 0, and the second is joint2 = 0.6, joint3 = 0.5 (elbow bent up), so no
link touches the ground plane and no joint reaches a limit at either end of any
step; step 0.3 rad, settle 0.5 s, hold 2 s (4.5 s of simulated time per run).
"""

import copy
import math
from dataclasses import dataclass, field

from ..control.controller_manager import STRICT, ControllerManager
from ..control.joint_position_controller import JointPositionController
from ..control.switching import switch_while_updating
from ..description.sdf_world import WorldConfig, read_world
from ..sim.robot_hw_sim import DefaultRobotHWSim
from ..sim.simulation import Simulation
from .local_ros import LocalRos
from .metrics import FINAL_WINDOW, step_metrics

JPC = JointPositionController.type_name

ARM1_START = {'joint1': 0.0, 'joint2': 1.0, 'joint3': 0.0, 'joint4': 0.0}
# A second pose, elbow bent up: gains tuned at one pose alone can shake at another.
ARM1_POSES = [{'joint2': 0.6, 'joint3': 0.5}]


@dataclass
class Protocol:
    start: dict = field(default_factory=dict)  # joint -> rad; joints not named start at 0
    step: float = 0.3  # rad
    settle: float = 0.5  # s before the first step
    hold: float = 2.0  # s after each step
    poses: list = field(default_factory=list)  # more start poses the steps are repeated from

    def variants(self):
        """One single-pose Protocol per start pose, the main one first."""
        return [
            Protocol(dict(pose), self.step, self.settle, self.hold)
            for pose in [self.start] + list(self.poses)
        ]

    def describe(self):
        poses = ['(%d) %s' % (k + 1, pose_text(p.start)) for k, p in enumerate(self.variants())]
        return (
            'start pose%s: %s (at rest); hold %g s, step %g rad out (up unless that '
            'leaves the joint range), hold %g s, step back, hold %g s'
            % (
                's' if self.poses else '',
                '; '.join(poses) if self.poses else pose_text(self.start),
                self.settle,
                self.step,
                self.hold,
                self.hold,
            )
        )


def pose_text(pose):
    return ', '.join('%s %g' % kv for kv in sorted(pose.items())) or 'all joints 0'


@dataclass
class StepRun:
    """One run of the protocol for one joint: samples of that joint and the two steps."""

    joint: str
    gains: dict
    times: list  # s since the run began
    positions: list  # rad, the stepped joint
    efforts: list  # N m, the stepped joint, after saturation
    steps: list  # [(name, t_step, start position, target)] : 'out' then 'back'
    others_wobble: float  # rad, largest range of motion of the other joints
    others_jitter: float = 0.0  # rad, largest peak to peak of the other joints at the ends of holds
    metrics: list = field(default_factory=list)  # StepMetrics per step
    aborted: bool = False  # stopped early by the caller's abort rule


def gains_of(pid_params):
    """The ``pid`` parameter dict as the six gains the Pid uses (control_toolbox's rules)."""
    from ..control.pid import Pid

    return Pid.from_params(pid_params).gains()


def yaml_pid(gains):
    """Gains as a ``pid:`` block for a controllers yaml (i_clamp when symmetric)."""
    out = {'p': _round(gains['p']), 'i': _round(gains['i']), 'd': _round(gains['d'])}
    lo, hi = gains.get('i_clamp_min', 0.0), gains.get('i_clamp_max', 0.0)
    if lo or hi:
        if abs(lo + hi) < 1e-12:
            out['i_clamp'] = _round(hi)
        else:
            out['i_clamp_min'], out['i_clamp_max'] = _round(lo), _round(hi)
    if gains.get('antiwindup'):
        out['antiwindup'] = True
    return out


def _round(v):
    return float('%.4g' % v)


class StepRig:
    """One robot in one headless Simulation, its position controllers loaded and running."""

    def __init__(self, urdf_xml, params, world=None, find_package=None, model_name=None):
        """``params``: the parameter tree (a loaded controllers yaml); ``world``: a
        WorldConfig, a world file path, or None for an empty world."""
        if isinstance(world, str):
            world = read_world(world)
        self.ros = LocalRos(copy.deepcopy(params))
        self.sim = Simulation(world or WorldConfig())
        self._closed = False
        try:
            self._spawn(urdf_xml, find_package, model_name)
        except Exception:
            self.close()
            raise

    def _spawn(self, urdf_xml, find_package, model_name):
        from ..description.urdf_model import parse_urdf

        name = model_name or parse_urdf(urdf_xml).name or 'robot'
        self.model = self.sim.spawn_urdf(
            name,
            urdf_xml,
            find_package=find_package,
            controller_manager_factory=lambda hw, ns: ControllerManager(
                hw, self.ros.node_handle, ns
            ),
        )
        if self.model.controller_manager is None or self.model.hw is None:
            raise ValueError("robot '%s' has no gazebo_ros_control plugin: nothing to tune" % name)
        if not isinstance(self.model.hw, DefaultRobotHWSim):
            raise ValueError(
                "robot '%s': the tuner drives gazebo_ros_control's DefaultRobotHWSim only" % name
            )
        self.cm = self.model.controller_manager
        self.hw = self.model.hw
        self.namespace = self.model.namespace
        ns_params = self.ros.get_param(self.namespace)
        self.controllers = {}  # joint -> controller name
        for cname in sorted(ns_params):
            spec = ns_params[cname]
            if isinstance(spec, dict) and spec.get('type') == JPC:
                controller = self.cm.load_controller(cname)
                assert isinstance(controller, JointPositionController)  # its type says so
                self.controllers[controller.joint.name] = cname
        if not self.controllers:
            raise ValueError('no %s under %s in the controllers parameters' % (JPC, self.namespace))
        self.joints = sorted(self.controllers)
        self._switch(list(self.controllers.values()))
        self.initial_gains = {j: self.controller(j).pid.gains() for j in self.joints}
        self.gains = copy.deepcopy(self.initial_gains)

    def _switch(self, start):
        """controller_manager's switch (it waits for an update, as in Gazebo)."""
        self.hw.read()
        # Updates of period 0 at the present time: no effort, no physics step.
        ok, _ = switch_while_updating(
            self.cm, start, [], lambda: self.cm.update(self.sim.time_ns, 0), STRICT, deadline=None
        )
        if not ok:
            raise RuntimeError('could not start the controllers %s' % ', '.join(start))

    def controller(self, joint: str) -> JointPositionController:
        controller = self.cm.controller(self.controllers[joint])
        assert isinstance(controller, JointPositionController)
        return controller

    def limits(self, joint):
        lim = self.hw.handles[joint].limits
        return lim.lower, lim.upper

    def command_topic(self, joint):
        return '%s/%s/command' % (self.namespace, self.controllers[joint])

    def state_topic(self, joint):
        return '%s/%s/state' % (self.namespace, self.controllers[joint])

    def targets(self, joint, protocol):
        """(start, out target) of ``joint`` under ``protocol``."""
        start = float(protocol.start.get(joint, 0.0))
        lo, hi = self.limits(joint)
        out = start + protocol.step
        if hi is not None and out > hi:
            out = start - protocol.step
        if lo is not None and out < lo:
            raise ValueError(
                '%s: a %g rad step from %g does not fit in [%g, %g]'
                % (joint, protocol.step, start, lo, hi)
            )
        return start, out

    def restart(self, protocol, gains=None):
        """Every joint at rest at the start pose, controllers restarted with ``gains``
        (joint -> gains dict; the rig's current gains for joints not named)."""
        for joint in self.joints:
            g = dict(self.gains[joint])
            g.update((gains or {}).get(joint, {}))
            self.controller(joint).set_gains(g)  # applied at the next update, as a reconfigure
        pose = {
            j: float(protocol.start.get(j, 0.0))
            for j in self.model.robot.joint_index
            if j in self.hw.handles
        }
        self.sim.set_model_configuration(self.model.name, list(pose), list(pose.values()))
        self.hw.read()
        # gazebo_ros_control's reset: stop and start the running controllers
        self.cm.update(self.sim.time_ns, 0, reset_controllers=True)

    def run(self, joint, protocol, gains=None, abort=None):
        """One protocol run for ``joint``; ``gains`` overrides that joint's gains.

        ``abort(t, position, out_target)`` may stop the run early (then no metrics)."""
        start, out = self.targets(joint, protocol)
        all_gains = {joint: gains} if gains else {}
        self.restart(protocol, all_gains)
        handle = self.hw.handles[joint]
        others = [self.hw.handles[j] for j in self.joints if j != joint]
        lo_o = [h.position for h in others]
        hi_o = list(lo_o)
        dt = self.sim.period
        n_settle = int(round(protocol.settle / dt))
        n_hold = int(round(protocol.hold / dt))
        topic = self.command_topic(joint)
        times, positions, efforts = [], [], []
        steps = []
        step = self.sim.step
        k = 0
        aborted = False
        n_final = int(round(FINAL_WINDOW / dt))
        others_jitter = 0.0
        for phase, target, n in (
            ('settle', start, n_settle),
            ('out', out, n_hold),
            ('back', start, n_hold),
        ):
            if phase != 'settle':
                steps.append((phase, k * dt, handle.position, target))
                self.ros.publish(topic, target)
            tail_lo = tail_hi = None
            for m in range(n):
                step()
                k += 1
                if phase != 'settle' and m >= n - n_final:
                    now = [h.position for h in others]
                    if tail_lo is None or tail_hi is None:
                        tail_lo, tail_hi = list(now), list(now)
                    else:
                        tail_lo = [min(a, b) for a, b in zip(tail_lo, now)]
                        tail_hi = [max(a, b) for a, b in zip(tail_hi, now)]
                times.append(k * dt)
                positions.append(handle.position)
                efforts.append(handle.effort)
                for i, h in enumerate(others):
                    if h.position < lo_o[i]:
                        lo_o[i] = h.position
                    elif h.position > hi_o[i]:
                        hi_o[i] = h.position
                if (
                    abort is not None
                    and phase != 'settle'
                    and not k % 50
                    and abort(k * dt, handle.position, out)
                ):
                    aborted = True
                    break
            if tail_lo is not None and tail_hi is not None:
                others_jitter = max([others_jitter] + [hi - lo for hi, lo in zip(tail_hi, tail_lo)])
            if aborted:
                break
        wobble = max([hi - lo for hi, lo in zip(hi_o, lo_o)] or [0.0])
        used = dict(self.gains[joint])
        used.update(gains or {})
        run = StepRun(
            joint, used, times, positions, efforts, steps, wobble, others_jitter, aborted=aborted
        )
        if not aborted:
            run.metrics = measure(run)
        return run

    def close(self):
        if not self._closed:
            self._closed = True
            self.sim.close()


def measure(run):
    """StepMetrics of each step of a StepRun."""
    out = []
    bounds = [s[1] for s in run.steps[1:]] + [math.inf]
    for (name, t_step, start, target), t_end in zip(run.steps, bounds):
        seg = [(t, x) for t, x in zip(run.times, run.positions) if t_step < t <= t_end + 1e-12]
        ts = [t_step] + [t for t, _ in seg]
        xs = [start] + [x for _, x in seg]
        out.append(step_metrics(ts, xs, target, start=start, t_step=t_step))
    return out
