"""Helpers of the fault rostests: the world's process, its pace, small models and log checks."""

import math
import socket
import struct
import time
from typing import Dict, Optional, Tuple

import psutil
import rosgraph
import rospy
from camera_util import node_pid
from gazebo_msgs.srv import DeleteModel, SpawnModel
from rostest_util import Recorder, wait_for

LINK = '''<link name="{name}">
    <inertial><mass value="0.1"/>
      <inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><box size="0.05 0.05 0.05"/></geometry></visual>
    <collision><geometry><box size="0.05 0.05 0.05"/></geometry></collision>
  </link>'''


def urdf(name: str, links: int = 1, joint_type: str = 'revolute') -> str:
    """A chain of ``links`` boxes joined by ``joint_type`` joints (no plugin, no camera)."""
    parts = [LINK.format(name='l0')]
    for i in range(1, links):
        limit = (
            '<limit lower="-1" upper="1" effort="1" velocity="1"/>'
            if joint_type in ('revolute', 'prismatic')
            else ''
        )
        parts.append(LINK.format(name='l%d' % i))
        parts.append(
            '<joint name="j%d" type="%s"><parent link="l%d"/><child link="l%d"/>'
            '<origin xyz="0 0 0.06"/><axis xyz="0 0 1"/>%s</joint>'
            % (i, joint_type, i - 1, i, limit)
        )
    return '<robot name="%s">%s</robot>' % (name, ''.join(parts))


class World:
    """The world node seen from outside: its process and its spawn/delete services."""

    def __init__(self) -> None:
        rospy.wait_for_service('/gazebo/spawn_urdf_model', 60)
        self.process = psutil.Process(node_pid('/gazebo'))
        self.spawn_srv = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
        self.delete_srv = rospy.ServiceProxy('/gazebo/delete_model', DeleteModel)

    def spawn(self, name: str, xml: str, namespace: str = ''):
        return self.spawn_srv(name, xml, namespace, None, '')

    def delete(self, name: str):
        return self.delete_srv(name)

    def threads(self) -> int:
        return self.process.num_threads()

    def rss_mb(self) -> float:
        return self.process.memory_info().rss / 1e6

    def alive(self) -> bool:
        return self.process.is_running() and self.process.status() != psutil.STATUS_ZOMBIE

    def render_processes(self):
        """The world's camera render processes (psutil.Process)."""
        out = []
        for child in self.process.children():
            try:
                if any('render_process_main' in part for part in child.cmdline()):
                    out.append(child)
            except psutil.NoSuchProcess:
                pass
        return out


class ClockPace:
    """Sim time against wall time from /clock as the test receives it."""

    def __init__(self, clock: Recorder) -> None:
        self.clock = clock

    def now(self) -> Tuple[float, float]:
        """(wall, sim) of the newest /clock message."""
        wait_for(lambda: self.clock.msgs, 30)
        with self.clock.lock:
            wall, msg = self.clock.msgs[-1]
        return wall, msg.clock.to_sec()

    @staticmethod
    def factor(start: Tuple[float, float], end: Tuple[float, float]) -> float:
        return (end[1] - start[1]) / max(1e-9, end[0] - start[0])

    def baseline(self, seconds: float = 3.0) -> float:
        """The real-time factor over the next ``seconds`` of wall time: what this machine gives
        the world now, that a flood's window is judged against (other work may share it)."""
        start = self.now()
        time.sleep(seconds)
        return self.factor(start, self.now())

    def advances(self, seconds: float = 0.2, timeout: float = 20) -> bool:
        """True once sim time has gone ``seconds`` past the newest message now."""
        _, before = self.now()
        return bool(wait_for(lambda: self.now()[1] - before >= seconds, timeout))


class ClockWindow:
    """/clock gaps and real-time factor between start() and stop(), in wall time of arrival."""

    def __init__(self, clock: Recorder) -> None:
        self.clock = clock

    def start(self) -> None:
        self.t0 = time.monotonic()

    def stop(self) -> Tuple[float, float]:
        msgs = [(t, m.clock.to_sec()) for t, m in list(self.clock.msgs) if t >= self.t0]
        assert len(msgs) > 10, 'no /clock during the case'
        gaps = [b[0] - a[0] for a, b in zip(msgs, msgs[1:])]
        wall = msgs[-1][0] - msgs[0][0]
        rtf = (msgs[-1][1] - msgs[0][1]) / max(wall, 1e-9)
        return max(gaps), rtf


def logged(rosout: Recorder, since: float, *words: str, timeout: float = 10) -> Optional[str]:
    """The first /rosout message since ``since`` (wall) that contains every word, or None."""

    def find():
        return next((m.msg for m in rosout.since(since) if all(w in m.msg for w in words)), None)

    return wait_for(find, timeout)


def finite_arm(states: Recorder) -> bool:
    """The newest joint_states has only finite positions and velocities."""
    msg = states.last()
    return msg is not None and all(
        math.isfinite(v) for v in list(msg.position) + list(msg.velocity)
    )


def raw_service_call(
    service: str, header: Dict[str, str], body: bytes, timeout: float = 10.0
) -> bytes:
    """Talk TCPROS to a service by hand: send ``header`` and ``body`` as they are, return what
    comes back before the server closes (or ``timeout``)."""
    uri = rosgraph.Master('/faults_raw').lookupService(service)
    host, port = uri[len('rosrpc://') :].rsplit(':', 1)
    encoded = [('%s=%s' % kv).encode() for kv in header.items()]
    fields = b''.join(struct.pack('<I', len(e)) + e for e in encoded)
    data = struct.pack('<I', len(fields)) + fields + body
    out = b''
    with socket.create_connection((host, int(port)), timeout) as sock:
        sock.sendall(data)
        sock.shutdown(socket.SHUT_WR)
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            try:
                chunk = sock.recv(65536)
            except (socket.timeout, ConnectionError):
                break
            if not chunk:
                break
            out += chunk
    return out
