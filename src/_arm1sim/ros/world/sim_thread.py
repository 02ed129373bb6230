"""Calls from rospy's threads run on the physics thread, between two steps.

pybullet is not thread-safe and the simulation is not locked: a service handler
hands its work over and waits for the answer; the world loop runs what waits.
"""

from __future__ import annotations

import collections
import threading
from typing import Any, Callable, Deque, Optional

import rospy


class SimThreadCalls:
    def __init__(self) -> None:
        self._calls: Deque[Callable[[], None]] = collections.deque()
        self._sim_thread = threading.main_thread()
        # Called after a call is handed over (the world loop's Pacer.wake: no batched sleep
        # holds it up).
        self.on_call: Optional[Callable[[], None]] = None

    def call(self, fn: Callable[..., Any], *args: Any) -> Any:
        """``fn(*args)`` on the physics thread; its result, or its exception raised here."""
        if threading.current_thread() is self._sim_thread:
            return fn(*args)
        done, box = threading.Event(), []

        def run() -> None:
            try:
                box.append((True, fn(*args)))
            except Exception as exc:  # handed back to the caller's thread
                box.append((False, exc))
            done.set()

        self._calls.append(run)
        if self.on_call is not None:
            self.on_call()
        while not done.wait(0.5):
            if rospy.is_shutdown():
                raise rospy.ServiceException('simulation shut down')
        ok, value = box[0]
        if not ok:
            raise value
        return value

    def run_pending(self) -> None:
        """Physics thread: run every call handed over so far."""
        calls = self._calls
        while calls:
            calls.popleft()()
