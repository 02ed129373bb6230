"""What the browser view costs the world, and the camera's delivered rate: one launch of
``gazebo.launch gui:=false web:=true`` at real time, measured with no page open, then with
the page open in headless Chromium (session/browser.py), then with the camera subscribed."""

from __future__ import annotations

import time
from typing import Any, Dict, List, Tuple

from .launched import PROBE, launch_and_wait, record_clock
from .probes import cpu_seconds

ASKED_HZ = 30.0  # arm1's camera (urdf/arm1.gazebo.xacro)


def _window(clock: List[Tuple[float, float]], world: List[int], seconds: float) -> Dict[str, float]:
    cpu0, w0, c0 = cpu_seconds(world), time.perf_counter(), clock[-1]
    time.sleep(seconds)
    cpu1, w1, c1 = cpu_seconds(world), time.perf_counter(), clock[-1]
    return {'rtf': (c1[1] - c0[1]) / (c1[0] - c0[0]), 'cpu': (cpu1 - cpu0) / (w1 - w0)}


def web_view(seconds: float) -> Dict[str, Any]:
    import rospy
    from sensor_msgs.msg import Image

    from ..session.browser import Browser
    from ..session.launcher import RosSession, node_pid

    session = RosSession()
    session.activate()
    with session:
        launch_and_wait(session, 'web:=true', 'web_port:=0')
        clock = record_clock()
        rospy.wait_for_message('/arm1/joint_states', rospy.AnyMsg, timeout=60)
        deadline = time.time() + 30
        while not rospy.has_param('/gazebo/web_url') and time.time() < deadline:
            time.sleep(0.2)
        url = rospy.get_param('/gazebo/web_url')
        world = [node_pid('/gazebo', caller=PROBE)]
        time.sleep(2.0)
        closed = _window(clock, world, seconds)
        browser = Browser()
        try:
            browser.open(url)
            browser.wait_js("document.body && document.body.innerText.includes('sim time')", 120)
            time.sleep(3.0)  # the page's first scene and camera image are sent
            opened = _window(clock, world, seconds)
        finally:
            browser.close()
        time.sleep(2.0)
        stamps: List[float] = []
        sub = rospy.Subscriber(
            '/rgb_camera/image_raw',
            Image,
            lambda m: stamps.append(m.header.stamp.to_sec()),
            queue_size=100,
            buff_size=1 << 24,
        )
        rospy.wait_for_message('/rgb_camera/image_raw', rospy.AnyMsg, timeout=60)
        time.sleep(2.0)
        n0 = len(stamps)
        time.sleep(seconds)
        window = stamps[n0:]
        sub.unregister()
        rospy.signal_shutdown('measured')
    return {
        'rtf_closed': closed['rtf'],
        'rtf_open': opened['rtf'],
        'cpu_closed': closed['cpu'],
        'cpu_open': opened['cpu'],
        'cpu_added': opened['cpu'] - closed['cpu'],
        'camera_asked_hz': ASKED_HZ,
        'camera_hz': (len(window) - 1) / (window[-1] - window[0]) if len(window) > 1 else 0.0,
    }
