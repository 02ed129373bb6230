"""Switching controllers while the simulation keeps updating them.

``switch_controller`` waits for the next update, as in Gazebo, so a caller that is also the
one updating (a test, the tuner, a benchmark) must ask from another thread, the way a ROS
service thread does, and keep updating until the answer comes.
"""

from __future__ import annotations

import threading
import time
from typing import Callable, Optional, Sequence, Tuple

from .controller_manager import STRICT, ControllerManager


class SwitchTimeout(RuntimeError):
    """switch_controller did not return within the wall time given."""


class SwitchRequest:
    """``manager.switch_controller(start, stop, ...)`` called on a thread of its own."""

    def __init__(
        self,
        manager: ControllerManager,
        start: Sequence[str],
        stop: Sequence[str] = (),
        strictness: int = STRICT,
        timeout: float = 0.0,
    ) -> None:
        self.result: Optional[bool] = None  # what switch_controller returned, once it has
        self.error: Optional[BaseException] = None  # what it raised, if it did
        self._thread = threading.Thread(
            target=self._call,
            args=(manager, list(start), list(stop), strictness, timeout),
            name='switch_controller',
            daemon=True,
        )
        self._thread.start()

    def _call(
        self,
        manager: ControllerManager,
        start: Sequence[str],
        stop: Sequence[str],
        strictness: int,
        timeout: float,
    ) -> None:
        try:
            self.result = manager.switch_controller(start, stop, strictness, timeout)
        except BaseException as exc:  # handed to the waiting thread by wait()
            self.error = exc

    @property
    def waiting(self) -> bool:
        return self._thread.is_alive()

    def wait(self, seconds: Optional[float] = None) -> Optional[bool]:
        """Wait up to ``seconds`` of wall time (None: for ever): the result, None while it
        still waits; raises what switch_controller raised."""
        self._thread.join(seconds)
        if self.error is not None:
            raise self.error
        return None if self._thread.is_alive() else self.result


def switch_while_updating(
    manager: ControllerManager,
    start: Sequence[str],
    stop: Sequence[str],
    step: Callable[[], None],
    strictness: int = STRICT,
    timeout: float = 0.0,
    deadline: Optional[float] = 5.0,
    poll: float = 0.001,
) -> Tuple[bool, int]:
    """Switch from another thread while this one calls ``step()`` (an update or a physics
    step) every ``poll`` wall seconds until the switch returns.

    Returns what switch_controller returned and how many steps ran. Raises SwitchTimeout
    when it has not returned after ``deadline`` wall seconds (None: wait for ever).
    """
    request = SwitchRequest(manager, start, stop, strictness, timeout)
    end = None if deadline is None else time.monotonic() + deadline
    steps = 0
    while request.waiting and (end is None or time.monotonic() < end):
        step()
        steps += 1
        request.wait(poll)
    result = request.wait(0)
    if result is None:
        raise SwitchTimeout(
            'switch_controller(start=%s, stop=%s) did not return within %s s '
            'while %d steps ran' % (list(start), list(stop), deadline, steps)
        )
    return result, steps
