"""Starts and stops roslaunch / rosrun processes against a private ROS master (demo, tests,
bench)."""

import os
import signal
import socket
import subprocess
import time
from typing import Dict, List, Mapping, Optional, Tuple
from urllib.parse import urlparse

# ROS 1 has no authentication: whoever reaches a node's or the master's port can move the
# arm. rosgraph.network.get_bind_address binds 127.0.0.1 when ROS_HOSTNAME is 'localhost'.
LOOPBACK_HOST = 'localhost'
DEFAULT_MASTER_PORT = 11311


def loopback_env(env: Mapping[str, str], port: Optional[int] = None) -> Dict[str, str]:
    """A copy of env in which the master and every node listen on loopback only.

    ROS_HOSTNAME=localhost, ROS_IP dropped (an outside ROS_IP would be advertised to
    peers), ROS_MASTER_URI on localhost at port (default: the port env already names,
    else 11311). tools/ws-run does the same in shell for every make target.
    """
    out = dict(env)
    out.pop('ROS_IP', None)
    out['ROS_HOSTNAME'] = LOOPBACK_HOST
    if port is None:
        try:
            port = urlparse(out.get('ROS_MASTER_URI', '')).port
        except ValueError:  # a malformed port in the URI
            port = None
    out['ROS_MASTER_URI'] = 'http://%s:%d' % (LOOPBACK_HOST, port or DEFAULT_MASTER_PORT)
    return out


def free_port():
    with socket.socket() as s:
        s.bind(('localhost', 0))
        return s.getsockname()[1]


def node_pid(name: str, master_uri: Optional[str] = None, caller: str = '/arm1_launcher') -> int:
    """The pid of a running node (its slave API's getPid), looked up at the master."""
    import xmlrpc.client

    import rosgraph

    master = rosgraph.Master(caller, master_uri=master_uri)
    reply: Tuple[int, str, int] = xmlrpc.client.ServerProxy(  # type: ignore[assignment]
        master.lookupNode(name)
    ).getPid(caller)
    code, msg, pid = reply
    if code != 1:
        raise RuntimeError('getPid of %s failed: %s' % (name, msg))
    return pid


def listening_addresses(pid: int) -> List[Tuple[str, int]]:
    """(ip, port) of every TCP socket the process listens on."""
    import psutil

    return sorted(
        (c.laddr.ip, c.laddr.port)
        for c in psutil.Process(pid).connections('tcp')
        if c.status == psutil.CONN_LISTEN
    )


class RosSession:
    """A private master on a free port, on loopback; children inherit it through the env."""

    def __init__(self, log_dir=None):
        self.env = loopback_env(os.environ, free_port())
        if log_dir:
            self.env['ROS_LOG_DIR'] = log_dir
        self.procs = []

    def activate(self):
        """Point this process's own rospy at the session's master, on loopback too."""
        os.environ.pop('ROS_IP', None)
        for key in ('ROS_MASTER_URI', 'ROS_HOSTNAME'):
            os.environ[key] = self.env[key]

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
        proc = subprocess.Popen(
            cmd,
            env=self.env,
            start_new_session=True,
            stdout=subprocess.DEVNULL if quiet else None,
            stderr=subprocess.STDOUT if quiet else None,
        )
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
