"""A 50 MB robot description spawned into the real launch at real time (issue 22, case 7):
the longest /clock gap and the real-time factor while the world receives, parses and loads
it, next to the same window before. The request is sent by another process
(``big_description_client``), so building and sending 50 MB does not delay this probe's
/clock recorder. The model is spawned 2 m from arm1 (inside its links it would cost
contacts, not parsing)."""

from __future__ import annotations

import subprocess
import sys
import time
from typing import Any, Dict

from .launched import WINDOW, clock_pace, launch_and_wait, record_clock

BULK = 50 * 1000 * 1000  # characters of padding: inside the 64 MiB description_bytes
_BOX = '<geometry><box size="0.01 0.01 0.01"/></geometry>'
_LINK = (
    '<link name="{name}"><inertial><mass value="0.1"/>'
    '<inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>'
    '<visual>' + _BOX + '</visual><collision>' + _BOX + '</collision>{extra}</link>'
)


def big_description(kind: str, name: str = 'big') -> str:
    """``bulk``: a 2-link robot padded to 50 MB with comments (5 MB) and a ``<gazebo>``
    plugin's text (45 MB), its base carrying 1 900 box visuals (inside shapes_per_model);
    ``shapes``: 40 000 box collisions on one link (2.9 MB, inside the element budget; 45 s
    of pybullet's loadURDF, past shapes_per_model)."""
    if kind == 'shapes':
        extra = '<collision>%s</collision>' % _BOX * 40000
    else:
        extra = '<visual><origin xyz="0 0 0.1"/>%s</visual>' % _BOX * 1900
    base, child = _LINK.format(name='l0', extra=extra), _LINK.format(name='l1', extra='')
    joint = (
        '<joint name="j1" type="revolute"><parent link="l0"/><child link="l1"/>'
        '<origin xyz="0 0 0.06"/><axis xyz="0 0 1"/>'
        '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
    )
    padding = ''
    if kind == 'bulk':
        comment = '<!-- %s -->\n' % ('c' * 90)
        comments = comment * (BULK // 10 // len(comment))
        plugin = '<gazebo><plugin name="notes" filename="libnotes.so"><notes>%s</notes></plugin>'
        padding = comments + plugin % ('t' * (BULK - len(comments))) + '</gazebo>'
    return '<robot name="%s">%s%s%s%s</robot>' % (name, base, child, joint, padding)


def spawn_big_description(kind: str, name: str) -> str:
    """Spawns ``big_description(kind, name)`` 2 m from the origin; the world's answer as a
    line."""
    import rospy
    from gazebo_msgs.srv import SpawnModel
    from geometry_msgs.msg import Point, Pose, Quaternion

    xml = big_description(kind, name)
    rospy.wait_for_service('/gazebo/spawn_urdf_model', 60)
    clear = Pose(Point(2.0, 0.0, 0.0), Quaternion(0.0, 0.0, 0.0, 1.0))
    answer = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)(name, xml, '', clear, '')
    return '%.1f MB answered %s: %s' % (len(xml) / 1e6, answer.success, answer.status_message)


def big_description_bench() -> Dict[str, Any]:
    import rospy

    from ..session.launcher import RosSession

    session = RosSession()
    session.activate()
    with session:
        launch_and_wait(session)
        clock = record_clock()
        rospy.wait_for_message('/arm1/joint_states', rospy.AnyMsg, timeout=60)
        time.sleep(2.0)
        before = time.perf_counter()
        time.sleep(WINDOW)
        during = time.perf_counter()
        client = subprocess.run(
            [sys.executable, '-m', '_arm1sim.bench.workers', 'big_description_client'],
            stdout=subprocess.PIPE,
            text=True,
            timeout=120,
        )
        answered = time.perf_counter()
        time.sleep(1.0)
        end = time.perf_counter()
        gap_during, rtf_during = clock_pace([m for m in clock if m[0] < end], during)
        gap_before, rtf_before = clock_pace([m for m in clock if m[0] < during], before)
        rospy.signal_shutdown('measured')
    if ' answered True' not in client.stdout:
        raise RuntimeError('the big description was not spawned: %s' % client.stdout[-2000:])
    return {
        'answer_s': answered - during,
        'gap_before_ms': gap_before * 1e3,
        'rtf_before': rtf_before,
        'gap_ms': gap_during * 1e3,
        'rtf': rtf_during,
    }


def big_description_client() -> None:
    import rospy

    rospy.init_node('bench_big_description', anonymous=True)
    print(spawn_big_description('bulk', 'big_description'))
