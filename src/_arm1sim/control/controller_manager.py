"""The controller manager of ros_control: loads, switches and updates controllers. ROS-free.

Load/unload/switch are called from service threads; ``update`` runs on the
simulation thread. A switch is queued and takes effect at the next update, and
the caller waits for it (so while physics is paused it waits, as in Gazebo).

Whether a controller runs is the controller's own ``state`` (as in ros_control's
ControllerBase); the manager changes it only through start_request / stop_request.
"""

from __future__ import annotations

import logging
import math
import re
import threading
from typing import Callable, Dict, List, Optional, Sequence, Set, Tuple

from .controller import Controller, ControllerError, State
from .interfaces import NodeFactory, NodeHandle, RobotHW
from .registry import CONTROLLER_TYPES, cpp_only

log = logging.getLogger('_arm1sim.control')

BASE_CLASS = 'controller_interface::ControllerBase'

BEST_EFFORT, STRICT = 1, 2
# A controller name is a relative ROS graph name (it becomes the controller's namespace).
CONTROLLER_NAME = re.compile(r'[A-Za-z][A-Za-z0-9_]*(/[A-Za-z][A-Za-z0-9_]*)*\Z')
MAX_NAME_LENGTH = 255
MAX_LISTED = 5  # names a message lists before it says how many more


def shown(name: str, width: int = 60) -> str:
    """A name as a message quotes it: cut to ``width`` characters, control characters escaped."""
    text = name if name.isprintable() else repr(name)[1:-1]
    return text if len(text) <= width else '%s...(%d characters)' % (text[: width - 20], len(name))


def listed(names: Sequence[str]) -> str:
    """At most MAX_LISTED quoted names, then how many more."""
    out = ', '.join("'%s'" % shown(n) for n in names[:MAX_LISTED])
    return out + (' and %d more' % (len(names) - MAX_LISTED) if len(names) > MAX_LISTED else '')


class ControllerManagerError(Exception):
    """A request to the manager failed; the message says why, naming the controller."""


class _Loaded:
    __slots__ = ('name', 'type', 'controller', 'nodes')

    def __init__(
        self, name: str, type_name: str, controller: Controller, nodes: Tuple[NodeHandle, ...]
    ) -> None:
        self.name, self.type, self.controller, self.nodes = name, type_name, controller, nodes

    @property
    def state(self) -> State:
        return self.controller.state


class _Switch:
    """A switch request waiting for the next update."""

    __slots__ = ('start', 'stop', 'restart', 'done', 'result')

    def __init__(
        self, start: List[_Loaded], stop: List[_Loaded], restart: Sequence[_Loaded] = ()
    ) -> None:
        self.start, self.stop, self.restart = start, stop, list(restart)
        self.done = threading.Event()
        self.result: List[bool] = []  # filled once, by the update thread or by shutdown


# A run of consecutive running controllers of one type and that type's update_group.
_Group = Tuple[Callable[[Sequence[Controller], int, int], None], Tuple[Controller, ...]]


def _grouped(running: Sequence[Controller]) -> Tuple[_Group, ...]:
    """``running`` cut into runs of consecutive controllers of one type, each to be updated by
    its type's update_group: one call per run rather than per controller, in the same order.
    A controller whose ``update`` was replaced on the instance (instrumented, as the bench's
    latency probe does) is updated alone through that ``update``."""
    groups: List[_Group] = []
    for c in running:
        kind = None if 'update' in vars(c) else type(c)
        if groups and kind is not None and type(groups[-1][1][0]) is kind:
            update_group, run = groups[-1]
            if update_group == kind.update_group:
                groups[-1] = (update_group, run + (c,))
                continue
        groups.append(((kind or Controller).update_group, (c,)))
    return tuple(groups)


# One row of list_controllers: name, type, state, claimed resources.
ControllerInfo = Tuple[str, str, State, List[Tuple[str, List[str]]]]


class ControllerManager:
    def __init__(self, robot_hw: RobotHW, node_factory: NodeFactory, namespace: str) -> None:
        """``node_factory(namespace)`` returns a node handle (control/interfaces.py)."""
        self.robot_hw = robot_hw
        self.node_factory = node_factory
        self.namespace = namespace.rstrip('/')
        self._lock = threading.Lock()
        self._loaded: Dict[str, _Loaded] = {}  # in load order
        self._running: Tuple[Controller, ...] = ()  # snapshot the update thread iterates
        self._groups: Tuple[_Group, ...] = ()  # _running as runs of one type (see _grouped)
        self._loading: Set[str] = set()  # names being initialised: a second load is refused
        self._pending: List[_Switch] = []  # in order of request

    # -- requests (any thread) ------------------------------------------------
    def controller_types(self) -> List[str]:
        return sorted(CONTROLLER_TYPES)

    def load_controller(self, name: str) -> Controller:
        if (
            not isinstance(name, str)
            or len(name) > MAX_NAME_LENGTH
            or not CONTROLLER_NAME.match(name)
        ):
            raise ControllerManagerError(
                "Could not load controller '%s': %s"
                % (
                    shown(str(name)),
                    'the name is empty'
                    if not name
                    else 'not a valid controller name (a relative ROS name of at '
                    'most %d characters: letters, digits, _ and /)' % MAX_NAME_LENGTH,
                )
            )
        with self._lock:
            if name in self._loaded or name in self._loading:
                raise ControllerManagerError(
                    "A controller named '%s' was already loaded inside "
                    "the controller manager" % name
                )
            self._loading.add(name)
        try:
            return self._load(name)
        finally:
            with self._lock:
                self._loading.discard(name)

    def _load(self, name: str) -> Controller:
        ns = '%s/%s' % (self.namespace, name)
        controller_nh = self.node_factory(ns)
        type_name = controller_nh.params.get('type')
        if not type_name:
            controller_nh.shutdown()
            raise ControllerManagerError(
                "Could not load controller '%s' because the type was not specified. Did you load "
                "the controller configuration on the parameter server (namespace: '%s')?"
                % (name, ns)
            )
        cls = CONTROLLER_TYPES.get(type_name)
        if cls is None and cpp_only(str(type_name)):
            controller_nh.shutdown()
            raise ControllerManagerError(
                "Could not load controller '%s': type '%s' is a C++ controller plugin of %s, "
                "which cannot load into arm1's Python controller manager (its controller "
                'types: %s)'
                % (name, type_name, cpp_only(str(type_name)), ', '.join(self.controller_types()))
            )
        if cls is None:
            controller_nh.shutdown()
            raise ControllerManagerError(
                "Could not load controller '%s' because controller type '%s' does not exist. "
                "Known types: %s" % (name, type_name, ', '.join(self.controller_types()))
            )
        controller = cls()
        controller.name = name
        root_nh = self.node_factory(self.namespace)
        try:
            controller.init_request(self.robot_hw, root_nh, controller_nh)
        except ControllerError as exc:
            controller_nh.shutdown()
            root_nh.shutdown()
            raise ControllerManagerError("Initializing controller '%s' failed: %s" % (name, exc))
        with self._lock:
            self._loaded[name] = _Loaded(name, type_name, controller, (controller_nh, root_nh))
        return controller

    def unload_controller(self, name: str) -> None:
        with self._lock:
            entry = self._loaded.get(name)
            if entry is None:
                raise ControllerManagerError(
                    "Could not unload controller with name '%s' because no controller with this "
                    "name exists" % shown(str(name))
                )
            if entry.state == 'running':
                raise ControllerManagerError(
                    "Could not unload controller with name '%s' because it is still running" % name
                )
            del self._loaded[name]
        for nh in entry.nodes:
            nh.shutdown()

    def switch_controller(
        self,
        start: Sequence[str],
        stop: Sequence[str],
        strictness: int = STRICT,
        timeout: Optional[float] = 0.0,
    ) -> bool:
        """Start and stop controllers at the next update; True when it happened.

        ``timeout`` in wall seconds; 0, negative, non-finite or beyond what a wait can take
        mean none (the caller waits for the next update, as ros_control's 0 does)."""
        if strictness not in (BEST_EFFORT, STRICT):
            log.warning(
                'switch_controller: strictness %s is neither BEST_EFFORT (1) nor STRICT '
                '(2); defaulting to BEST_EFFORT',
                strictness,
            )
            strictness = BEST_EFFORT
        if timeout is None or not (math.isfinite(timeout) and 0 < timeout < threading.TIMEOUT_MAX):
            timeout = None
        with self._lock:
            checked = self._checked(start, stop, strictness)
            if checked is None:
                return False
            to_start, to_stop, restart = checked
            conflict = self._resource_conflict(to_start + restart, to_stop)
            if conflict:
                log.error('Could not switch controllers: %s', conflict)
                return False
            if not to_start and not to_stop and not restart:
                return True
            request = _Switch(to_start, to_stop, restart)
            self._pending.append(request)
        if request.done.wait(timeout):
            return request.result[0]
        with self._lock:
            self._pending = [r for r in self._pending if r is not request]
        if request.result:  # applied between the timeout and the withdrawal
            return request.result[0]
        log.error('Switching controllers timed out after %.3f s (is physics paused?)', timeout)
        return False

    def _checked(
        self, start: Sequence[str], stop: Sequence[str], strictness: int
    ) -> Optional[Tuple[List[_Loaded], List[_Loaded], List[_Loaded]]]:
        """(to start, to stop, to start again) by controller_manager.cpp's rules (lock held);
        None, logged, when the switch is refused. Unknown names: STRICT refuses, BEST_EFFORT
        skips. Stopping a controller that is not running: STRICT refuses, BEST_EFFORT skips.
        Starting one already running: STRICT refuses, BEST_EFFORT starts it again (its
        ``starting`` runs once more, with no ``stopping``: ControllerBase::startRequest from
        RUNNING). A running controller named in both lists is refused whatever the strictness;
        one not running named in both is, under BEST_EFFORT, started."""
        skipped: Dict[str, List[str]] = {}  # why -> names: a long list of bad names, one message
        for verb, names in (('start', start), ('stop', stop)):
            for name in names:
                if name in self._loaded:
                    continue
                if strictness == STRICT:
                    log.error("Could not %s controller '%s': it is not loaded", verb, shown(name))
                    return None
                skipped.setdefault('%s: is not loaded' % verb, []).append(name)
        start_set, stop_set = set(start), set(stop)
        to_start: List[_Loaded] = []
        to_stop: List[_Loaded] = []
        restart: List[_Loaded] = []
        for entry in self._loaded.values():  # in load order, as upstream
            running = entry.controller.running
            in_stop, in_start = entry.name in stop_set, entry.name in start_set
            if in_stop and not running:
                if strictness == STRICT:
                    log.error("Could not stop controller '%s': it is not running", entry.name)
                    return None
                skipped.setdefault('stop: is not running', []).append(entry.name)
                in_stop = False
            if in_start and running and not in_stop:
                if strictness == STRICT:
                    log.error("Could not start controller '%s': it is already running", entry.name)
                    return None
                log.warning(
                    "Controller '%s' is already running: starting it again (BEST_EFFORT)",
                    entry.name,
                )
                restart.append(entry)
                continue
            if in_stop and in_start:
                log.error(
                    "Could not start or stop controller '%s' because of conflicting switching "
                    'command (it is named in both lists)',
                    entry.name,
                )
                return None
            if in_stop:
                to_stop.append(entry)
            elif in_start:
                to_start.append(entry)
        for key, bad in skipped.items():
            verb, why = key.split(': ')
            log.warning(
                'Not %s controller%s %s: %s %s',
                'starting' if verb == 'start' else 'stopping',
                's' if len(bad) > 1 else '',
                listed(bad),
                'it' if len(bad) == 1 else 'they',
                why.replace('is ', 'are ') if len(bad) > 1 else why,
            )
        return to_start, to_stop, restart

    def _resource_conflict(self, start: List[_Loaded], stop: List[_Loaded]) -> Optional[str]:
        owners: Dict[Tuple[str, str], str] = {}
        for entry in self._loaded.values():
            if (entry.controller.running and entry not in stop) or entry in start:
                for iface, joints in entry.controller.claimed_resources():
                    for joint in joints:
                        if (iface, joint) in owners:
                            return "joint '%s' would be claimed by both '%s' and '%s'" % (
                                joint,
                                owners[(iface, joint)],
                                entry.name,
                            )
                        owners[(iface, joint)] = entry.name
        return None

    def reload_controller_libraries(self, force_kill: bool) -> bool:
        """reload_controller_libraries as controller_manager.cpp: refused while any controller
        is loaded, unless ``force_kill``, which stops (BEST_EFFORT, waiting for the next update)
        and unloads every controller first. Controller types are compiled in: there is no
        library to reload after that."""
        with self._lock:
            names = list(self._loaded)
            running = [n for n in names if self._loaded[n].controller.running]
        if names and not force_kill:
            log.error(
                'Cannot reload controller libraries because there are still %d controllers '
                'loaded (%s); unload them first or ask with force_kill',
                len(names),
                listed(names),
            )
            return False
        if names:
            log.info('Killing all running controllers to reload controller libraries')
            if not self.switch_controller([], running, BEST_EFFORT):
                log.error('Cannot reload controller libraries: failed to stop running controllers')
                return False
            for name in names:
                try:
                    self.unload_controller(name)
                except ControllerManagerError as exc:
                    log.error('Cannot reload controller libraries: %s', exc)
                    return False
        return True

    def list_controllers(self) -> List[ControllerInfo]:
        """``[(name, type, state, claimed_resources)]`` in load order."""
        with self._lock:
            return [
                (e.name, e.type, e.state, e.controller.claimed_resources())
                for e in self._loaded.values()
            ]

    def controller(self, name: str) -> Optional[Controller]:
        entry = self._loaded.get(name)
        return entry.controller if entry else None

    # -- simulation thread ----------------------------------------------------
    def update(self, time_ns: int, period_ns: int, reset_controllers: bool = False) -> None:
        """One control cycle at ``time_ns``, ``period_ns`` of sim time after the last one."""
        if self._pending:
            self._apply_switches(time_ns)
        if reset_controllers:
            for c in self._running:
                c.stop_request(time_ns)
                c.start_request(time_ns)
        for update_group, controllers in self._groups:
            update_group(controllers, time_ns, period_ns)

    def _apply_switches(self, time_ns: int) -> None:
        with self._lock:
            requests, self._pending = self._pending, []
            for request in requests:
                # Checked again here: an earlier request may have claimed the same joints.
                conflict = self._resource_conflict(request.start + request.restart, request.stop)
                if conflict:
                    log.error('Could not switch controllers: %s', conflict)
                    request.result.append(False)
                    continue
                request.result.append(True)
                for entry in request.stop:
                    if entry.controller.running:  # as stopControllers: only what runs
                        entry.controller.stop_request(time_ns)
                for entry in request.start + request.restart:
                    entry.controller.start_request(time_ns)
                # RobotHW::doSwitch: every RobotHWSim has one; a plain RobotHW (the
                # tuner's, a test's) may not, as upstream's default does nothing
                do_switch = getattr(self.robot_hw, 'do_switch', None)
                if do_switch is not None:
                    do_switch(
                        [e.controller.claimed_resources() for e in request.start],
                        [e.controller.claimed_resources() for e in request.stop],
                    )
            self._running = tuple(
                e.controller for e in self._loaded.values() if e.controller.running
            )
            self._groups = _grouped(self._running)
        for request in requests:
            request.done.set()

    def shutdown(self) -> None:
        """The model is being deleted: stop every controller, release every node handle, and
        answer switch requests still waiting (they fail), so the same names can come back."""
        with self._lock:
            entries, self._loaded = list(self._loaded.values()), {}
            pending, self._pending = self._pending, []
            self._running, self._groups = (), ()
        for request in pending:
            request.result.append(False)
            request.done.set()
        for entry in entries:
            if entry.controller.running:
                entry.controller.stop_request(0)
            for nh in entry.nodes:
                nh.shutdown()
