"""Starts and stops roslaunch / rosrun processes against a private ROS master (demo, tests, bench)."""
import os
import signal
import socket
import subprocess
import time


def free_port():
    with socket.socket() as s:
        s.bind(('localhost', 0))
        return s.getsockname()[1]


class RosSession:
    """A private master on a free port; children inherit it through ROS_MASTER_URI."""

    def __init__(self, log_dir=None):
        self.env = dict(os.environ)
        self.env['ROS_MASTER_URI'] = 'http://localhost:%d' % free_port()
        if log_dir:
            self.env['ROS_LOG_DIR'] = log_dir
        self.procs = []

    def activate(self):
        """Point this process's own rospy at the session's master."""
        os.environ['ROS_MASTER_URI'] = self.env['ROS_MASTER_URI']

    def wait_for_master(self, timeout=20.0):
        import rosgraph
        master = rosgraph.Master('/arm1_launcher', master_uri=self.env['ROS_MASTER_URI'])
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            try:
                master.getPid()
                return True
            except Exception:  # not up yet: connection refused
                time.sleep(0.1)
        return False

    def start(self, *cmd, quiet=True):
        proc = subprocess.Popen(cmd, env=self.env, start_new_session=True,
                                stdout=subprocess.DEVNULL if quiet else None,
                                stderr=subprocess.STDOUT if quiet else None)
        self.procs.append(proc)
        return proc

    def roslaunch(self, package, launch_file, *args, quiet=True):
        return self.start('roslaunch', package, launch_file, *args, quiet=quiet)

    def stop(self, timeout=10.0):
        for proc in reversed(self.procs):
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGINT)
        deadline = time.monotonic() + timeout
        for proc in reversed(self.procs):
            try:
                proc.wait(max(0.1, deadline - time.monotonic()))
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()
        self.procs = []

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stop()
