#!/usr/bin/env python
"""Processes dying around the world, and models coming and going, leave it running and lean.

- a client killed with SIGKILL in the middle of service calls (spawn/delete/configure, and a
  switch that waits on paused physics): the world keeps serving;
- a camera render process killed: images resume or an error naming the camera is logged,
  and /clock goes on;
- 50 spawn/delete cycles of a small model, and arm1 itself deleted and spawned again with
  its controllers (spawner) three times: the world's threads and memory stay bounded and
  the respawned arm works (commands, live gains);
- the ROS master killed and started again (a private master, so the rostest one stays):
  the world keeps stepping, serves the connections it had, and registers again.
"""

import os
import signal
import socket
import subprocess
import sys
import threading
import time
import unittest

import rosgraph
import rospy
import rostest
from control_msgs.msg import JointControllerState
from controller_manager_msgs.srv import ListControllers, SwitchController
from dynamic_reconfigure.client import Client
from gazebo_msgs.srv import SetModelConfiguration
from std_msgs.msg import Float64
from std_srvs.srv import Empty

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from camera_util import ImageRecorder  # noqa: E402
from faults_util import ClockPace, World, finite_arm, logged, urdf  # noqa: E402
from rostest_util import (  # noqa: E402
    Recorder,
    clock_recorder,
    joint_recorder,
    rosout_recorder,
    wait_for,
    wait_for_controllers,
)

CM = '/arm1/controller_manager/'
CONTROLLERS = ['joint_state_controller'] + ['joint%d_position_controller' % i for i in range(1, 5)]
THREAD_SLACK = 2  # threads the world may hold beyond its count before the cycles
RSS_SLACK_MB = 10.0  # resident memory it may grow by over the cycles, after a warm-up

# A client that spawns, configures and deletes a model in a loop, until killed.
LOOPING_CLIENT = '''
import rospy
from gazebo_msgs.srv import DeleteModel, SetModelConfiguration, SpawnModel
rospy.init_node('looping_client', anonymous=True)
spawn = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
delete = rospy.ServiceProxy('/gazebo/delete_model', DeleteModel)
configure = rospy.ServiceProxy('/gazebo/set_model_configuration', SetModelConfiguration)
print('looping', flush=True)
while True:
    spawn('victim', %r, '', None, '')
    configure('victim', '', ['j1'], [0.5])
    delete('victim')
'''

# A client whose switch waits for the next update (physics is paused), until killed.
WAITING_SWITCH = '''
import rospy
from controller_manager_msgs.srv import SwitchController
rospy.init_node('waiting_switch', anonymous=True)
switch = rospy.ServiceProxy('/arm1/controller_manager/switch_controller', SwitchController)
print('calling', flush=True)
switch([], ['joint_state_controller'], 2, False, 0.0)
print('answered', flush=True)
'''

# A /clock subscriber that prints the sim time it gets, five times a wall second.
CLOCK_PRINTER = '''
import time, rospy
from rosgraph_msgs.msg import Clock
rospy.init_node('clock_printer', anonymous=True)
last = [0.0]
def cb(msg):
    if time.monotonic() - last[0] >= 0.2:
        last[0] = time.monotonic()
        print('clock %.3f' % msg.clock.to_sec(), flush=True)
rospy.Subscriber('/clock', Clock, cb)
rospy.spin()
'''


def free_port():
    with socket.socket() as s:
        s.bind(('localhost', 0))
        return s.getsockname()[1]


class LineReader:
    """The lines a child process printed so far, read without blocking (a thread per pipe)."""

    def __init__(self, proc):
        self.lines = []
        self.proc = proc
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        for line in self.proc.stdout:
            self.lines.append(line.rstrip('\n'))

    def clocks(self):
        return [float(line.split()[1]) for line in list(self.lines) if line.startswith('clock ')]


class FaultsLifecycle(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_faults_lifecycle')
        cls.rosout = rosout_recorder()
        cls.clock = clock_recorder()
        cls.pace = ClockPace(cls.clock)
        cls.states = joint_recorder()
        cls.list = wait_for_controllers(5)
        cls.world = World()
        cls.configure = rospy.ServiceProxy('/gazebo/set_model_configuration', SetModelConfiguration)
        cls.spawners = []  # spawner processes this test started

    @classmethod
    def tearDownClass(cls):
        for proc in cls.spawners:
            if proc.poll() is None:
                proc.send_signal(signal.SIGINT)
                proc.wait(30)

    def assert_world_serves(self):
        """The world lives, sim time advances, and spawn/delete are answered."""
        self.assertTrue(self.world.alive(), 'the world process is gone')
        self.assertTrue(self.pace.advances(0.2), '/clock stopped')
        resp = self.world.spawn('probe', urdf('probe', 2))
        self.assertTrue(resp.success, resp.status_message)
        self.assertTrue(self.world.delete('probe').success)

    def python(self, code):
        return subprocess.Popen(
            [sys.executable, '-c', code],
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
        )

    # -- clients killed mid-call ---------------------------------------------------------
    def test_a_client_killed_mid_call_leaves_the_world_serving(self):
        for round_ in range(3):
            proc = self.python(LOOPING_CLIENT % urdf('victim', 2))
            reader = LineReader(proc)
            self.assertTrue(wait_for(lambda: 'looping' in reader.lines, 30), reader.lines)
            time.sleep(1.0 + 0.37 * round_)  # somewhere inside a call of the loop
            proc.kill()
            proc.wait(10)
            self.assertEqual(proc.returncode, -signal.SIGKILL)
            # it may have died with 'victim' spawned: then it is an ordinary model
            self.world.delete('victim')
            self.assert_world_serves()
        self.assertEqual(self.world.spawn('victim', urdf('victim', 2)).success, True)
        self.assertTrue(self.world.delete('victim').success)

    def test_a_client_killed_while_its_switch_waits_on_paused_physics_leaves_no_stuck_call(self):
        pause = rospy.ServiceProxy('/gazebo/pause_physics', Empty)
        unpause = rospy.ServiceProxy('/gazebo/unpause_physics', Empty)
        threads = self.world.threads()
        pause()
        try:
            proc = self.python(WAITING_SWITCH)
            reader = LineReader(proc)
            self.assertTrue(wait_for(lambda: 'calling' in reader.lines, 30), reader.lines)
            time.sleep(1.0)
            self.assertIsNone(proc.poll(), 'the switch returned while physics was paused')
            proc.kill()
            proc.wait(10)
        finally:
            unpause()

        # The switch asked for is carried out at the next update (as in ros_control), and the
        # thread that served it ends although its client is gone.
        def states():
            return {c.name: c.state for c in self.list().controller}

        self.assertTrue(
            wait_for(lambda: states()['joint_state_controller'] == 'stopped', 10), states()
        )
        switch = rospy.ServiceProxy(CM + 'switch_controller', SwitchController)
        self.assertTrue(switch(['joint_state_controller'], [], 2, False, 5.0).ok)
        self.assertTrue(
            wait_for(lambda: self.world.threads() <= threads + THREAD_SLACK, 10),
            '%d threads, %d before' % (self.world.threads(), threads),
        )
        self.assert_world_serves()

    # -- the camera's render process killed -------------------------------------------------
    def test_a_killed_render_process_leaves_images_resumed_or_an_error_naming_the_camera(self):
        images = ImageRecorder()
        try:
            self.assertTrue(wait_for(lambda: len(images.meta) >= 5, 60), 'no images')
            renderers = self.world.render_processes()
            self.assertTrue(renderers, 'no render process while images stream')
            mark, killed_at = time.monotonic(), rospy.Time.now().to_sec()
            renderers[0].kill()
            renderers[0].wait(10)
            resumed = wait_for(
                lambda: len([m for m in images.meta if m[0] > killed_at + 0.5]) >= 10, 30
            )
            error = logged(self.rosout, mark, 'rgb_camera', timeout=0 if resumed else 5)
            print(
                'render process %d killed: %s'
                % (renderers[0].pid, 'images resumed' if resumed else 'error: %s' % error)
            )
            self.assertTrue(resumed or error, 'images stopped and nothing names the camera')
            self.assertTrue(self.pace.advances(2.0), '/clock stopped')
        finally:
            images.close()
        self.assertTrue(finite_arm(self.states))
        self.assert_world_serves()

    # -- spawn/delete cycles -------------------------------------------------------------
    def cycle_small_model(self, n):
        xml = urdf('cycler', 3)
        for _ in range(n):
            resp = self.world.spawn('cycler', xml)
            self.assertTrue(resp.success, resp.status_message)
            resp = self.configure('cycler', '', ['j1', 'j2'], [0.3, -0.3])
            self.assertTrue(resp.success, resp.status_message)
            self.assertTrue(self.world.delete('cycler').success)

    def test_50_spawn_delete_cycles_of_a_small_model_leave_threads_and_memory_bounded(self):
        self.cycle_small_model(5)  # warm-up: first-use allocations
        time.sleep(1.0)
        threads, rss = self.world.threads(), self.world.rss_mb()
        children = len(self.world.process.children())
        start = time.monotonic()
        self.cycle_small_model(50)
        took = time.monotonic() - start
        after_threads = (
            wait_for(
                lambda: self.world.threads() <= threads + THREAD_SLACK and self.world.threads(), 10
            )
            or self.world.threads()
        )
        growth = self.world.rss_mb() - rss
        print(
            '50 spawn/delete cycles in %.1f s: threads %d -> %d, RSS %.1f MB %+.1f MB'
            % (took, threads, after_threads, rss, growth)
        )
        self.assertLessEqual(after_threads, threads + THREAD_SLACK)
        self.assertLess(growth, RSS_SLACK_MB)
        self.assertEqual(len(self.world.process.children()), children)
        self.assert_world_serves()

    def respawn_arm1(self):
        """Delete arm1, spawn it again from robot_description and start its controllers."""
        resp = self.world.delete('arm1')
        self.assertTrue(resp.success, resp.status_message)
        self.assertTrue(
            wait_for(lambda: not self.service_up(CM + 'list_controllers'), 10),
            'the deleted arm1 still offers its controller manager',
        )
        resp = self.world.spawn('arm1', rospy.get_param('/robot_description'))
        self.assertTrue(resp.success, resp.status_message)
        for proc in self.spawners:
            if proc.poll() is None:  # its controllers went with the old arm1
                proc.send_signal(signal.SIGINT)
                proc.wait(30)
        proc = subprocess.Popen(
            ['rosrun', 'arm1', 'spawner', '__ns:=/arm1'] + CONTROLLERS,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
        )
        self.spawners.append(proc)
        reader = LineReader(proc)
        rospy.wait_for_service(CM + 'list_controllers', 30)
        list_controllers = rospy.ServiceProxy(CM + 'list_controllers', ListControllers)

        def running():
            return sorted(c.name for c in list_controllers().controller if c.state == 'running')

        self.assertTrue(
            wait_for(lambda: running() == sorted(CONTROLLERS), 60),
            'running: %s; spawner said:\n%s' % (running(), '\n'.join(reader.lines)),
        )
        self.assertNotIn('already registered', '\n'.join(reader.lines))

    @staticmethod
    def service_up(name):
        try:
            rosgraph.Master('/t').lookupService(name)
            return True
        except rosgraph.MasterError:
            return False

    def test_arm1_deleted_and_respawned_with_its_controllers_works_and_stays_bounded(self):
        mark = time.monotonic()
        self.respawn_arm1()  # warm-up
        time.sleep(1.0)
        threads, rss = self.world.threads(), self.world.rss_mb()
        for _ in range(3):
            self.respawn_arm1()
        time.sleep(1.0)
        after_threads = (
            wait_for(
                lambda: self.world.threads() <= threads + THREAD_SLACK and self.world.threads(), 10
            )
            or self.world.threads()
        )
        growth = self.world.rss_mb() - rss
        print(
            'arm1 respawned 3 times with its controllers: threads %d -> %d, RSS %.1f MB '
            '%+.1f MB' % (threads, after_threads, rss, growth)
        )
        self.assertLessEqual(after_threads, threads + THREAD_SLACK)
        self.assertLess(growth, RSS_SLACK_MB)
        self.assertIsNone(logged(self.rosout, mark, 'already registered', timeout=0))
        # The new arm takes commands and live gains (checked after counting threads: rospy
        # keeps a thread per subscriber of a queued publisher until its next message).
        state = Recorder('/arm1/joint1_position_controller/state', JointControllerState)
        cmd = rospy.Publisher(
            '/arm1/joint1_position_controller/command', Float64, queue_size=1, latch=True
        )
        cmd.publish(0.4)
        self.assertTrue(
            wait_for(
                lambda: state.last() is not None and abs(state.last().process_value - 0.4) < 0.05,
                30,
            ),
            'joint1 did not follow its command after the respawn',
        )
        client = Client('/arm1/joint1_position_controller/pid', timeout=30)
        p = client.get_configuration(10)['p']
        self.assertEqual(client.update_configuration({'p': p * 2})['p'], p * 2)
        self.assertTrue(wait_for(lambda: state.last().p == p * 2, 10))
        client.update_configuration({'p': p})
        client.close()
        state.sub.unregister()
        cmd.unregister()
        self.assertTrue(finite_arm(self.states))
        self.assert_world_serves()

    # -- the master restarted --------------------------------------------------------------
    def test_the_world_outlives_its_master_and_registers_again_with_a_new_one(self):
        port = free_port()
        env = dict(os.environ, ROS_MASTER_URI='http://localhost:%d' % port)
        env.pop('ROS_NAMESPACE', None)

        def start(*cmd):
            return subprocess.Popen(
                cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True
            )

        procs = []
        try:
            master = start('rosmaster', '--core', '-p', str(port))
            procs.append(master)
            remote = rosgraph.Master('/faults_master', master_uri=env['ROS_MASTER_URI'])
            self.assertTrue(wait_for(remote.is_online, 20), 'the private master did not start')
            remote.setParam('/use_sim_time', True)
            world = start('rosrun', 'arm1', 'gzserver')
            procs.append(world)
            world_log = LineReader(world)
            printer = start(sys.executable, '-c', CLOCK_PRINTER)
            procs.append(printer)
            before = LineReader(printer)
            self.assertTrue(
                wait_for(lambda: len(before.clocks()) >= 3, 60), 'no /clock from the private world'
            )

            master.kill()
            master.wait(10)
            seen = len(before.clocks())
            time.sleep(3.0)
            clocks = before.clocks()[seen:]
            self.assertTrue(
                clocks and clocks[-1] - clocks[0] >= 1.5,
                'the world stopped with its master: %s' % clocks,
            )
            self.assertIsNone(world.poll(), 'the world died with its master')

            master = start('rosmaster', '--core', '-p', str(port))
            procs.append(master)
            self.assertTrue(wait_for(remote.is_online, 20))
            # The world's own watch registers it again within a few seconds: new nodes find
            # /clock and the /gazebo services.
            self.assertTrue(
                wait_for(lambda: self.published(remote, '/clock'), 15),
                'the world did not register again:\n%s' % '\n'.join(world_log.lines),
            )
            # Topics and services register one by one: /clock may come back first.
            self.assertTrue(
                wait_for(lambda: self.provides(remote, '/gazebo/spawn_urdf_model'), 15),
                'the /gazebo services did not register again:\n%s' % '\n'.join(world_log.lines),
            )
            printer = start(sys.executable, '-c', CLOCK_PRINTER)
            procs.append(printer)
            after = LineReader(printer)
            self.assertTrue(
                wait_for(lambda: len(after.clocks()) >= 3, 30),
                'a new subscriber gets no /clock after the master restarted',
            )

            world.send_signal(signal.SIGINT)
            world.wait(30)
            self.assertEqual(world.returncode, 0, '\n'.join(world_log.lines[-20:]))
        finally:
            for proc in procs:
                if proc.poll() is None:
                    proc.kill()
                    proc.wait(10)

    @staticmethod
    def provides(master, service):
        try:
            return bool(master.lookupService(service))
        except (OSError, rosgraph.MasterException):
            return False

    @staticmethod
    def published(master, topic):
        try:
            pubs, _, _ = master.getSystemState()
        except (OSError, rosgraph.MasterException):
            return False
        return any(name == topic and nodes for name, nodes in pubs)


if __name__ == '__main__':
    rostest.rosrun('arm1', 'test_faults_lifecycle', FaultsLifecycle)
