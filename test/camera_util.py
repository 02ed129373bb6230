"""Helpers of the camera, arm_mover and look_away rostests: images, poses and the render process."""

import os
import threading
import time
import xmlrpc.client

import rosgraph
import rospy
from gazebo_msgs.srv import DeleteModel, SpawnModel
from geometry_msgs.msg import Pose
from rostest_util import JOINTS, positions, wait_for
from sensor_msgs.msg import Image
from std_msgs.msg import Float64

from _arm1sim.goal.image import is_uniform

UP = (0.0, 1.5, 0.0, 0.0)  # arm upright: the camera at its tip sees only the sky
LOOK = (0.0, 0.6, -0.4, -0.4)  # look_away's default pose: the horizon


class ImageRecorder:
    """Keeps every frame's header and size, and the latest frame (frames are 0.9 MB each)."""

    def __init__(self, topic='/rgb_camera/image_raw', buff_size=1 << 26):
        self.lock = threading.Lock()
        self.meta = []  # (stamp s, width, height, encoding, step, len(data), frame_id)
        self.arrived = []  # wall time (monotonic) of each frame
        self.latest = None
        self.sub = rospy.Subscriber(topic, Image, self._cb, queue_size=100, buff_size=buff_size)

    def _cb(self, msg):
        with self.lock:
            self.meta.append(
                (
                    msg.header.stamp.to_sec(),
                    msg.width,
                    msg.height,
                    msg.encoding,
                    msg.step,
                    len(msg.data),
                    msg.header.frame_id,
                )
            )
            self.arrived.append(time.monotonic())
            self.latest = msg

    def frame_after(self, stamp, timeout=20):
        """The first frame stamped after ``stamp`` (sim seconds), or None."""
        return wait_for(
            lambda: (
                self.latest
                if self.latest is not None and self.latest.header.stamp.to_sec() > stamp
                else None
            ),
            timeout,
        )

    def close(self):
        self.sub.unregister()


def uniform(msg):
    return is_uniform(msg.data, msg.width, msg.height, msg.step)


class JointCommander:
    """Publishes to the four position controllers and waits for the arm to get there."""

    def __init__(self, states, ns='/arm1'):
        self.states = states  # a rostest_util joint_recorder
        self.pubs = [
            rospy.Publisher(
                '%s/%s_position_controller/command' % (ns, j), Float64, queue_size=1, latch=True
            )
            for j in JOINTS
        ]

    def go(self, pose, tol=0.05, timeout=30):
        for pub, value in zip(self.pubs, pose):
            pub.publish(value)
        return self.wait_at(pose, tol, timeout)

    def wait_at(self, pose, tol=0.05, timeout=30):
        """The stamp (s) of the first joint state within ``tol`` of ``pose``, or None."""

        def there():
            msg = self.states.last()
            if msg is None:
                return None
            pos = positions(msg)
            ok = all(abs(pos[j] - v) <= tol for j, v in zip(JOINTS, pose))
            return msg.header.stamp.to_sec() if ok else None

        return wait_for(there, timeout)


def node_pid(name):
    uri = rosgraph.Master('/camera_util').lookupNode(name)
    return xmlrpc.client.ServerProxy(uri).getPid('/camera_util')[2]


def render_processes(world_pid):
    """pids of the world's camera render processes."""
    out = []
    for entry in os.listdir('/proc'):
        if not entry.isdigit():
            continue
        try:
            with open('/proc/%s/stat' % entry) as f:
                ppid = int(f.read().rsplit(')', 1)[1].split()[1])
            with open('/proc/%s/cmdline' % entry, 'rb') as f:
                cmdline = f.read()
        except (OSError, ValueError, IndexError):
            continue
        if ppid == world_pid and b'render_process_main' in cmdline:
            out.append(int(entry))
    return out


def cpu_seconds(pid):
    """User + system CPU time a process has used."""
    with open('/proc/%d/stat' % pid) as f:
        fields = f.read().rsplit(')', 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')


def camera_box_urdf(width, height, rate, camera_name='eye'):
    """A one-link model (no joints) carrying a gazebo_ros_camera that looks down at the ground."""
    return (
        '<robot name="box"><link name="body"><inertial><mass value="0.5"/><inertia ixx="1e-3" '
        'ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial><visual><geometry><box '
        'size="0.1 0.1 0.1"/></geometry></visual><collision><geometry><box size="0.1 0.1 0.1"/>'
        '</geometry></collision></link><gazebo reference="body"><sensor type="camera" '
        'name="%s"><update_rate>%g</update_rate><pose>0 0 0.5 0 1.2 0</pose><camera><image>'
        '<width>%d</width><height>%d</height></image></camera><plugin name="cam" '
        'filename="libgazebo_ros_camera.so"><cameraName>%s</cameraName></plugin></sensor>'
        '</gazebo></robot>' % (camera_name, rate, width, height, camera_name)
    )


def spawn_urdf(name, xml, z=0.05, x=0.0):
    """/gazebo/spawn_urdf_model: (success, status_message)."""
    rospy.wait_for_service('/gazebo/spawn_urdf_model', 60)
    pose = Pose()
    pose.position.x = x
    pose.position.z = z
    pose.orientation.w = 1.0
    resp = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)(name, xml, '', pose, 'world')
    return resp.success, resp.status_message


def delete_model(name):
    resp = rospy.ServiceProxy('/gazebo/delete_model', DeleteModel)(name)
    return resp.success, resp.status_message


def clock_rate(clock, since):
    """Sim seconds per wall second of the /clock messages (a rostest_util Recorder) since a
    wall time (monotonic), from the first to the last of them."""
    with clock.lock:
        msgs = [(t, m.clock.to_sec()) for t, m in clock.msgs if t >= since]
    (w0, s0), (w1, s1) = msgs[0], msgs[-1]
    return (s1 - s0) / (w1 - w0)
