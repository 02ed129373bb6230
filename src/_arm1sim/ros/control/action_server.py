"""actionlib's ActionServer behind the control core's GoalHandle (control/interfaces.py).

Python actionlib runs in the world's process, so what a client can make it do costs physics
time. Three of its habits are bounded here (``BoundedActionServer``), keeping its protocol:
it published the whole status list on every transition (a goal storm: ~1 000 entries, each
time), kept every finished goal in that list for ``status_list_timeout`` (5 s), and called
the controller's callbacks holding its lock (a long goal's build then blocked the physics
thread's feedback); a cancel naming a goal not yet seen, cancelled again, logged "Attempt to
get a goal id on an uninitialized ServerGoalHandle" and raised in the callback.
"""

from __future__ import annotations

import functools
import threading
import time
from typing import Any, Callable, Dict, List, Optional

import rospy

from ...control.interfaces import Fields
from .messages import Fill, action


class RosGoalHandle:
    """control/interfaces.py's GoalHandle over actionlib's ServerGoalHandle."""

    def __init__(
        self,
        gh: Any,
        goal: Callable[[], Dict[str, Any]],
        result_class: type,
        feedback_class: type,
        fill_feedback: Fill,
    ) -> None:
        self._gh, self._read = gh, goal
        self._goal: Optional[Dict[str, Any]] = None
        self.id = gh.get_goal_id().id
        self._result_class, self._feedback_class = result_class, feedback_class
        self._fill_feedback = fill_feedback

    @property
    def goal(self) -> Dict[str, Any]:
        """The goal's fields, read on first use: a cancel never converts a 100 000-point goal."""
        goal = self._goal
        if goal is None:
            goal = self._goal = self._read()
        return goal

    def _result(self, fields: Fields) -> Any:
        result = self._result_class()
        for key, value in fields.items():
            setattr(result, key, value)
        return result

    def accept(self) -> None:
        self._gh.set_accepted()

    def reject(self, result: Fields) -> None:
        self._gh.set_rejected(self._result(result), result.get('error_string', ''))

    def succeed(self, result: Fields) -> None:
        self._gh.set_succeeded(self._result(result), result.get('error_string', ''))

    def abort(self, result: Fields) -> None:
        self._gh.set_aborted(self._result(result), result.get('error_string', ''))

    def cancel(self, result: Fields) -> None:
        self._gh.set_canceled(self._result(result), result.get('error_string', ''))

    def publish_feedback(self, fields: Fields) -> None:
        feedback = self._feedback_class()
        self._fill_feedback(feedback, fields)
        self._gh.publish_feedback(feedback)


class ActionServer:
    """actionlib's ActionServer, withdrawn by unregister(). Its status timer is made anew
    with reset=True: rospy's Timer otherwise dies when sim time jumps back (reset_simulation)."""

    def __init__(
        self,
        name: str,
        type_name: str,
        on_goal: Callable[[Any], None],
        on_cancel: Callable[[Any], None],
    ) -> None:
        spec, goal_reader, result_class, feedback_class, fill_feedback = action(type_name)

        def wrap(gh: Any) -> RosGoalHandle:
            return RosGoalHandle(
                gh,
                lambda: goal_reader(gh.get_goal()),
                result_class,
                feedback_class,
                fill_feedback,
            )

        self.server = bounded_action_server_class()(
            name,
            spec,
            lambda gh: on_goal(wrap(gh)),
            lambda gh: on_cancel(wrap(gh)),
            auto_start=False,
        )
        self.server.start()
        timer = getattr(self.server, 'status_timer', None)
        if timer is not None:
            period = timer._period
            timer.shutdown()
            self._last_now = rospy.Time.now()
            self.server.status_timer = rospy.Timer(period, self._publish_status, reset=True)

    def _publish_status(self, event: Any) -> None:
        # After reset_simulation a cancel stamped before it would silently cancel every new
        # goal (actionlib cancels goals stamped at or before the newest cancel): forget it.
        now = rospy.Time.now()
        if now < self._last_now:
            with self.server.lock:
                self.server.last_cancel = rospy.Time()
        self._last_now = now
        self.server.publish_status_async(event)

    def unregister(self) -> None:
        s = self.server
        with s.lock:
            s.started = False  # a status flush still pending must not publish any more
        timer = getattr(s, 'status_timer', None)
        if timer is not None:
            timer.shutdown()
        for name in ('status_pub', 'result_pub', 'feedback_pub', 'goal_sub', 'cancel_sub'):
            handle = getattr(s, name, None)
            if handle is not None:
                handle.unregister()


STATUS_PERIOD = 0.05  # wall s: status messages at most 20 a second (the timer's 5 Hz besides)
MAX_FINISHED = 100  # finished goals (and cancels of unseen ones) the status list keeps


@functools.lru_cache(maxsize=None)
def bounded_action_server_class() -> type:
    """actionlib.ActionServer with the bounds of this module's docstring (made on first use:
    importing actionlib costs, and only a world with an action controller needs it)."""
    import actionlib
    from actionlib.handle_tracker_deleter import HandleTrackerDeleter
    from actionlib.server_goal_handle import ServerGoalHandle
    from actionlib.status_tracker import StatusTracker
    from actionlib_msgs.msg import GoalStatus

    class BoundedActionServer(actionlib.ActionServer):
        status_list: List[Any]
        last_cancel: Any
        _last_status = 0.0
        _flush: Optional[threading.Timer] = None

        def publish_status(self) -> None:
            """At most one status message per STATUS_PERIOD: a burst of transitions ends in
            one message with all of them, STATUS_PERIOD later at most."""
            with self.lock:
                wait = self._last_status + STATUS_PERIOD - time.monotonic()
                if wait > 0:
                    if self._flush is None:
                        self._flush = threading.Timer(wait, self._publish_deferred)
                        self._flush.daemon = True
                        self._flush.start()
                    return
                self._publish_now()

        def _publish_deferred(self) -> None:
            with self.lock:
                self._flush = None
                if self.started and not rospy.is_shutdown():
                    self._publish_now()

        def _publish_now(self) -> None:
            self._last_status = time.monotonic()
            finished = [st for st in self.status_list if st.handle_destruction_time != _ZERO]
            if len(finished) > MAX_FINISHED:  # the oldest go first
                drop = {id(st) for st in finished[:-MAX_FINISHED]}
                self.status_list = [st for st in self.status_list if id(st) not in drop]
            actionlib.ActionServer.publish_status(self)

        def internal_goal_callback(self, goal: Any) -> None:
            with self.lock:
                if not self.started:
                    return
                for st in self.status_list:
                    if st.status.goal_id.id != goal.goal_id.id:
                        continue
                    # Seen before: a cancel that came first recalls it; nothing else to do.
                    if st.status.status == GoalStatus.RECALLING:
                        st.status.status = GoalStatus.RECALLED
                        self.publish_result(st.status, self.ActionResultType())
                    if st.handle_tracker is None:
                        st.handle_destruction_time = rospy.Time.now()
                    return
                st = StatusTracker(None, None, goal)
                self.status_list.append(st)
                st.handle_tracker = HandleTrackerDeleter(self, st)
                gh = ServerGoalHandle(st, self, st.handle_tracker)
                stamp = goal.goal_id.stamp
                if stamp != _ZERO and stamp <= self.last_cancel:
                    gh.set_canceled(
                        None,
                        'This goal was canceled by the action server: its stamp is not after '
                        'that of the last cancel request',
                    )
                    return
            self.goal_callback(gh)  # without the lock, as actionlib's C++ server calls it

        def internal_cancel_callback(self, goal_id: Any) -> None:
            cancelled = []
            with self.lock:
                if not self.started:
                    return
                everything = goal_id.id == '' and goal_id.stamp == _ZERO
                found = False
                for st in list(self.status_list):
                    other = st.status.goal_id
                    if not (
                        everything
                        or goal_id.id == other.id
                        or (goal_id.stamp != _ZERO and other.stamp <= goal_id.stamp)
                    ):
                        continue
                    found = found or goal_id.id == other.id
                    if st.goal is None:  # a cancel's record of a goal not seen yet
                        continue
                    if st.handle_tracker is None:
                        st.handle_tracker = HandleTrackerDeleter(self, st)
                        st.handle_destruction_time = rospy.Time.now()
                    gh = ServerGoalHandle(st, self, st.handle_tracker)
                    if gh.set_cancel_requested():
                        cancelled.append(gh)
                if goal_id.id and not found:  # recall the goal should it come later
                    tracker = StatusTracker(goal_id, GoalStatus.RECALLING)
                    tracker.handle_destruction_time = rospy.Time.now()
                    self.status_list.append(tracker)
                if goal_id.stamp > self.last_cancel:
                    self.last_cancel = goal_id.stamp
            for gh in cancelled:  # without the lock, as actionlib's C++ server calls it
                self.cancel_callback(gh)

    return BoundedActionServer


_ZERO = rospy.Time()
