"""actionlib's ActionServer behind the control core's GoalHandle (control/interfaces.py)."""

from __future__ import annotations

from typing import Any, Callable, Dict

import rospy

from ...control.interfaces import Fields
from .messages import ACTIONS, Fill


class RosGoalHandle:
    """control/interfaces.py's GoalHandle over actionlib's ServerGoalHandle."""

    def __init__(
        self,
        gh: Any,
        goal: Dict[str, Any],
        result_class: type,
        feedback_class: type,
        fill_feedback: Fill,
    ) -> None:
        self._gh, self.goal = gh, goal
        self.id = gh.get_goal_id().id
        self._result_class, self._feedback_class = result_class, feedback_class
        self._fill_feedback = fill_feedback

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
        import actionlib

        spec, goal_reader, result_class, feedback_class, fill_feedback = ACTIONS[type_name]

        def wrap(gh: Any) -> RosGoalHandle:
            return RosGoalHandle(
                gh, goal_reader(gh.get_goal()), result_class, feedback_class, fill_feedback
            )

        self.server = actionlib.ActionServer(
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
        timer = getattr(s, 'status_timer', None)
        if timer is not None:
            timer.shutdown()
        for name in ('status_pub', 'result_pub', 'feedback_pub', 'goal_sub', 'cancel_sub'):
            handle = getattr(s, name, None)
            if handle is not None:
                handle.unregister()
