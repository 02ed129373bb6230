"""What the soak samples: /clock, joint_states and camera image stamps as a ROS subscriber, and the
world's memory, threads and CPU (and the machine's) from the process table."""

import os
import struct
import threading
import time
from typing import Dict, List, Optional, Tuple

SAMPLE_S = 2.0  # wall seconds between samples
FRAME_PERIOD = 1.0 / 30  # the camera's update rate in sim time (urdf/arm1.gazebo.xacro)


class Probe:
    """What the soak hears: /clock (with wall arrival), joint_states and camera image stamps."""

    def __init__(self) -> None:
        import rospy
        from rosgraph_msgs.msg import Clock
        from sensor_msgs.msg import JointState

        self.lock = threading.Lock()
        self.clock: Optional[Tuple[float, float]] = None  # (wall monotonic, sim s) of the last
        self.joint_states = 0
        self.images = 0
        self.images_late = 0  # a frame more than half a period after the one before
        self.last_image: Optional[float] = None
        rospy.Subscriber('/clock', Clock, self._on_clock, queue_size=10)
        rospy.Subscriber('/arm1/joint_states', JointState, self._on_state, queue_size=50)
        # AnyMsg: the stamp is read from the raw bytes, so 27 MB/s of pixels are never
        # deserialised in Python (the viewer should not load the machine it measures).
        rospy.Subscriber(
            '/rgb_camera/image_raw', rospy.AnyMsg, self._on_image, queue_size=10, buff_size=1 << 22
        )

    def _on_clock(self, msg) -> None:
        with self.lock:
            self.clock = (time.monotonic(), msg.clock.to_sec())

    def _on_state(self, msg) -> None:
        with self.lock:
            self.joint_states += 1

    def _on_image(self, msg) -> None:
        _, secs, nsecs = struct.unpack_from('<III', msg._buff, 0)  # std_msgs/Header first
        stamp = secs + nsecs * 1e-9
        with self.lock:
            if self.last_image is not None and stamp - self.last_image > 1.5 * FRAME_PERIOD:
                self.images_late += 1
            self.last_image = stamp
            self.images += 1

    def snapshot(self) -> Dict[str, float]:
        with self.lock:
            wall, sim = self.clock if self.clock else (float('nan'), float('nan'))
            return {
                'clock_wall': wall,
                'sim': sim,
                'joint_states': self.joint_states,
                'images': self.images,
                'images_late': self.images_late,
            }


class ProcessWatch:
    """RSS, threads and CPU of the world process (and its render processes), and of the rest."""

    def __init__(self, world_pid: int, ours: List[int]) -> None:
        import psutil

        self.psutil = psutil
        self.world = psutil.Process(world_pid)
        self.ours = [psutil.Process(p) for p in ours]

    def _tree(self, roots) -> list:
        seen = {}
        for root in roots:
            for p in [root] + root.children(recursive=True):
                seen[p.pid] = p
        return list(seen.values())

    def sample(self) -> Dict[str, float]:
        psutil = self.psutil
        world_cpu = self.world.cpu_times()
        out = {
            'world_rss_mb': self.world.memory_info().rss / 2**20,
            'world_threads': self.world.num_threads(),
            'world_cpu_s': world_cpu.user + world_cpu.system,
        }
        renders = rss = cpu = 0.0
        for p in self.world.children(recursive=True):
            try:
                rss += p.memory_info().rss / 2**20
                t = p.cpu_times()
                cpu += t.user + t.system
                renders += 1
            except psutil.NoSuchProcess:  # a render process restarting
                pass
        out.update(render_rss_mb=rss, render_cpu_s=cpu, render_processes=renders)
        ours = 0.0
        for p in self._tree(self.ours):
            try:
                t = p.cpu_times()
                ours += t.user + t.system + t.children_user + t.children_system
            except psutil.NoSuchProcess:
                pass
        machine = psutil.cpu_times()
        out['session_cpu_s'] = ours
        out['machine_busy_s'] = (
            machine.user
            + machine.nice
            + machine.system
            + machine.irq
            + machine.softirq
            + getattr(machine, 'steal', 0.0)
        )
        out['load1'] = os.getloadavg()[0]
        return out
