"""The soak's run: robot_spawn.launch, simple_mover and a camera viewer on a private master,
sampled every SAMPLE_S wall seconds until the time is up, a line printed each minute."""

import os
import time
from typing import List, Optional, Tuple

from .judge import minute_rows
from .probes import SAMPLE_S, Probe, ProcessWatch
from .report import HEADER, format_row


def run(minutes: float, warmup_s: float) -> Tuple[List[dict], Optional[str]]:
    """Start everything, sample until the time is up; (samples, why it stopped early or None)."""
    import rospy

    from ...session.launcher import RosSession, node_pid

    session = RosSession()
    session.activate()
    samples: List[dict] = []
    with session:
        print(
            'soak: roslaunch arm1 robot_spawn.launch gui:=false; '
            'rosrun arm1 simple_mover __name:=simple_mover; a viewer of the camera; '
            '%g min (warm-up %.0f s), a line a minute' % (minutes, warmup_s),
            flush=True,
        )
        launch = session.roslaunch('arm1', 'robot_spawn.launch', 'gui:=false')
        if not session.wait_for_master():
            return samples, 'the ROS master did not start'
        rospy.init_node('arm1_soak', anonymous=True, disable_signals=True)
        probe = Probe()
        try:
            rospy.wait_for_message('/arm1/joint_states', rospy.AnyMsg, timeout=60)
        except rospy.ROSException:
            return samples, 'no /arm1/joint_states within 60 s'
        # The seed's simple_mover calls itself arm_mover (rospy.init_node('arm_mover')):
        # beside robot_spawn.launch's arm_mover the master would shut the service node
        # down ("new node registered with same name"), so it runs under its own name.
        mover = session.start('rosrun', 'arm1', 'simple_mover', '__name:=simple_mover')
        world = ProcessWatch(
            node_pid('/gazebo', caller=rospy.get_name()), [launch.pid, mover.pid, os.getpid()]
        )
        print(HEADER, flush=True)
        t0 = time.monotonic()
        end, printed, why = t0 + 60.0 * minutes, 0, None
        while True:
            try:
                s = dict(probe.snapshot(), **world.sample())
            except Exception as e:  # psutil.NoSuchProcess: the world is gone
                why = 'the world process stopped: %s' % e
                break
            s['t'] = time.monotonic() - t0
            samples.append(s)
            rows = minute_rows(samples)
            for r in rows[printed:]:
                print(format_row(r), flush=True)
            printed = len(rows)
            if launch.poll() is not None:
                why = 'roslaunch exited (%s)' % launch.returncode
                break
            if time.monotonic() >= end:
                break
            time.sleep(min(SAMPLE_S, max(0.0, end - time.monotonic())))
        rospy.signal_shutdown('soak over')
    if why is None and len(samples) < 3:
        why = 'too few samples'
    return samples, why
