"""``make demo``: arm1 in the headless stand-in under simple_mover, with a live table.

Starts ``roslaunch arm1 gazebo.launch gui:=false`` and ``rosrun arm1 simple_mover``
on a private master, prints sim time, real-time factor and each joint's command
and position once a wall second, then a summary; exits non-zero if the arm did
not follow.
"""

import argparse
import math
import sys
import threading
import time
from typing import Dict

JOINTS = ['joint1', 'joint2', 'joint3', 'joint4']


class Monitor:
    def __init__(self):
        import rospy
        from sensor_msgs.msg import JointState
        from std_msgs.msg import Float64

        self.lock = threading.Lock()
        self.position: Dict[str, float] = {}
        self.command: Dict[str, float] = {}
        self.rtf = float('nan')
        self.stamp = 0.0
        self.samples = []  # (sim time, {joint: (command, position)})
        rospy.Subscriber('/arm1/joint_states', JointState, self._on_state, queue_size=10)
        rospy.Subscriber(
            '/gazebo/real_time_factor',
            Float64,
            lambda m: setattr(self, 'rtf', m.data),
            queue_size=1,
        )
        for j in JOINTS:
            rospy.Subscriber(
                '/arm1/%s_position_controller/command' % j,
                Float64,
                lambda m, j=j: self.command.__setitem__(j, m.data),
                queue_size=1,
            )

    def _on_state(self, msg):
        with self.lock:
            self.stamp = msg.header.stamp.to_sec()
            self.position = dict(zip(msg.name, msg.position))
            if all(j in self.command for j in JOINTS):
                self.samples.append(
                    (self.stamp, {j: (self.command[j], self.position.get(j)) for j in JOINTS})
                )


def table_header():
    cols = ''.join('%-17s' % ('%s cmd/pos' % j) for j in JOINTS)
    return '%8s %6s  %s' % ('sim t', 'RTF', cols)


def table_row(mon):
    with mon.lock:
        cells = ''.join(
            '%7s %7s  ' % (_f(mon.command.get(j)), _f(mon.position.get(j))) for j in JOINTS
        )
        return '%8.2f %6s  %s' % (mon.stamp, _f(mon.rtf, 2), cells)


def _f(value, digits=3):
    return (
        '-'
        if value is None or (isinstance(value, float) and math.isnan(value))
        else '%.*f' % (digits, value)
    )


def summary(samples, limits):
    """Per joint: range reached, whether it stayed within limits, tracking error once moving."""
    lines, ok = [], bool(samples)
    for j in JOINTS:
        pos = [s[1][j][1] for s in samples if s[1][j][1] is not None]
        if not pos:
            return ['no joint_states for %s' % j], False
        lo, hi = limits[j]
        # The controller tracks the command clamped to the limits.
        err = [abs(min(max(c, lo), hi) - p) for _, d in samples for c, p in [d[j]] if p is not None]
        within = lo - 0.05 <= min(pos) and max(pos) <= hi + 0.05
        moved = max(pos) - min(pos) > 0.5 * (hi - lo)
        ok = ok and within and moved
        lines.append(
            '%s: reached [%+.3f, %+.3f] of limits [%+.2f, %+.2f]  median |error| %.3f rad'
            '  %s'
            % (
                j,
                min(pos),
                max(pos),
                lo,
                hi,
                sorted(err)[len(err) // 2],
                'ok' if within and moved else 'FAILED',
            )
        )
    return lines, ok


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--duration', type=float, default=25.0, help='wall seconds to run')
    args = parser.parse_args(argv)

    from .launcher import RosSession

    session = RosSession()
    session.activate()
    import rospy

    from ..description.urdf_model import parse_urdf

    with session:
        print('starting: roslaunch arm1 gazebo.launch gui:=false; rosrun arm1 simple_mover')
        session.roslaunch('arm1', 'gazebo.launch', 'gui:=false')
        if not session.wait_for_master():
            print('FAILED: the ROS master did not start', file=sys.stderr)
            return 1
        rospy.init_node('arm1_demo', anonymous=True, disable_signals=True)
        mon = Monitor()
        try:
            rospy.wait_for_message('/arm1/joint_states', rospy.AnyMsg, timeout=30)
        except rospy.ROSException:
            print('FAILED: no /arm1/joint_states within 30 s', file=sys.stderr)
            return 1
        description = parse_urdf(rospy.get_param('/robot_description'))
        limits = {
            j: (description.joints[j].limits.lower, description.joints[j].limits.upper)
            for j in JOINTS
        }
        session.start('rosrun', 'arm1', 'simple_mover')
        print(table_header())
        end = time.monotonic() + args.duration
        while time.monotonic() < end:
            time.sleep(1.0)
            print(table_row(mon), flush=True)
        rospy.signal_shutdown('demo over')
    lines, ok = summary(mon.samples, limits)
    print('\n'.join(lines))
    print(
        'demo: %s'
        % ('all four joints followed simple_mover within their limits' if ok else 'FAILED')
    )
    return 0 if ok else 1


if __name__ == '__main__':
    sys.exit(main())
