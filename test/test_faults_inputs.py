#!/usr/bin/env python
"""Bad input to every service and topic the world and arm1's controller manager offer, and floods.

Each case sends one kind of malformed, non-finite, empty, oversized or mismatched input and
checks that it is answered with a clear error naming the culprit (a failed response or a
message on /rosout) and that the world keeps running (/clock advances, the arm is finite,
the controllers still run). The world node (/gazebo) offers the services pause_physics,
unpause_physics, reset_simulation, reset_world (std_srvs/Empty: no input to get wrong),
spawn_urdf_model, delete_model and set_model_configuration, and publishes /clock,
/gazebo/real_time_factor and arm1's camera topics; arm1's controller manager offers
/arm1/controller_manager/{list_controllers, list_controller_types, load_controller,
unload_controller, switch_controller, reload_controller_libraries}, each position
controller subscribes to its ``command`` topic, publishes ``state`` and serves its gains at
``pid/set_parameters`` (dynamic_reconfigure).
"""

import glob
import math
import os
import subprocess
import sys
import tempfile
import threading
import time
import unittest

import rospy
import rostest
from control_msgs.msg import JointControllerState
from controller_manager_msgs.srv import (
    ListControllerTypes,
    LoadController,
    SwitchController,
    UnloadController,
)
from dynamic_reconfigure.client import Client
from gazebo_msgs.srv import DeleteModel, GetWorldProperties, SetModelConfiguration, SpawnModel
from std_msgs.msg import Float64

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from camera_util import ImageRecorder  # noqa: E402
from faults_util import (  # noqa: E402
    ClockPace,
    ClockWindow,
    World,
    finite_arm,
    logged,
    raw_service_call,
    urdf,
)
from rostest_util import (  # noqa: E402
    Recorder,
    clock_recorder,
    joint_recorder,
    rosout_recorder,
    sim_wait,
    wait_for,
    wait_for_controllers,
)

from _arm1sim.bench.big_description import spawn_big_description  # noqa: E402
from _arm1sim.ros.common.publishers import synchronous_publisher  # noqa: E402

CM = '/arm1/controller_manager/'
CTRL = '/arm1/%s_position_controller'
LIMITS = {
    'joint1': (-1.57, 1.57),
    'joint2': (0.01, 1.57),
    'joint3': (-1.0, 1.57),
    'joint4': (-0.8, 1.57),
}
CONTROLLERS = {'joint_state_controller'} | {'joint%d_position_controller' % i for i in range(1, 5)}
BEST_EFFORT, STRICT = 1, 2
# A flood's real-time factor from /clock may not fall below this share of the 3 s before it
# (0.9 and 1.0 on an idle machine; judged against the baseline, as other work may share it)
MIN_PACE_RATIO = 0.8
# Issue 22, case 7 (docs/faults.md, "Third round"): a spawn's /clock gap may exceed the longest
# of the 1.5 sim s before it by this much (wall s; the idle-machine bound is 100 ms: this
# margin is for a busy 2-core machine), its real-time factor fall to this share of that window's
GAP_MARGIN = 0.5
MIN_RTF_RATIO = 0.5
BIG_CLIENT = '--big-description-client'


def big_client_main(kind, name):
    """Spawns ``big_description(kind)`` (_arm1sim.bench.big_description) from a process of its own,
    so that building and sending 50 MB does not delay the test's /clock recorder."""
    rospy.init_node('big_description_client', anonymous=True)
    print(spawn_big_description(kind, name))


def spawn_from_another_process(kind, name):
    """(success, what the client printed) of big_client_main's spawn."""
    out = subprocess.run(
        [sys.executable, os.path.abspath(__file__), BIG_CLIENT, kind, name],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        timeout=120,
    ).stdout.decode(errors='replace')
    answer = [line for line in out.splitlines() if ' answered ' in line]
    assert answer, out[-2000:]
    return ' answered True' in answer[-1], answer[-1]


def model_files(since, robot):
    """{path: bytes} of the URDFs a world on this machine wrote for pybullet since then for a
    ``<robot name=robot>`` (other worlds may run beside this test's and write their own)."""
    out = {}
    head = ('<robot name="%s"' % robot).encode()
    for path in glob.glob(os.path.join(tempfile.gettempdir(), 'arm1-sim-*', 'model-*.urdf')):
        try:
            if os.path.getmtime(path) >= since:
                with open(path, 'rb') as f:
                    if head in f.read(4096):
                        out[path] = os.path.getsize(path)
        except OSError:  # deleted meanwhile
            pass
    return out


class FaultsInputs(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_faults_inputs')
        cls.rosout = rosout_recorder()
        cls.clock = clock_recorder()
        cls.pace = ClockPace(cls.clock)
        cls.states = joint_recorder()
        cls.list = wait_for_controllers(5)
        cls.world = World()
        # Written in this thread (no queue to drop from), so a burst reaches the world whole;
        # joint4's command topic is left free for the wrong-type publisher.
        cls.cmd = {
            j: synchronous_publisher(CTRL % j + '/command', Float64)
            for j in ('joint1', 'joint2', 'joint3')
        }
        cls.ctrl_state = {
            j: Recorder(CTRL % j + '/state', JointControllerState)
            for j in ('joint1', 'joint3', 'joint4')
        }
        assert wait_for(lambda: all(p.get_num_connections() for p in cls.cmd.values()), 30)
        cls.configure = rospy.ServiceProxy('/gazebo/set_model_configuration', SetModelConfiguration)
        cls.spawn = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
        cls.delete = rospy.ServiceProxy('/gazebo/delete_model', DeleteModel)
        cls.world_props = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)
        cls.window = ClockWindow(cls.clock)
        cls.load = rospy.ServiceProxy(CM + 'load_controller', LoadController)
        cls.unload = rospy.ServiceProxy(CM + 'unload_controller', UnloadController)
        cls.switch = rospy.ServiceProxy(CM + 'switch_controller', SwitchController)

    # -- helpers ------------------------------------------------------------------
    def running(self):
        return {c.name for c in self.list().controller if c.state == 'running'}

    def assert_world_runs(self):
        """The world process lives, sim time advances, the arm is finite, all 5 controllers run."""
        self.assertTrue(self.world.alive(), 'the world process is gone')
        self.assertTrue(self.pace.advances(0.2), '/clock stopped')
        self.assertTrue(finite_arm(self.states), 'joint_states not finite: %s' % self.states.last())
        self.assertEqual(self.running(), CONTROLLERS)

    def set_point(self, joint):
        msg = self.ctrl_state[joint].last()
        return None if msg is None else msg.set_point

    def command(self, joint, value):
        """Publish a target and wait until the controller's state shows it as its set point."""
        self.cmd[joint].publish(value)
        lo, hi = LIMITS[joint]
        want = min(max(value, lo), hi)
        self.assertTrue(
            wait_for(lambda: self.set_point(joint) == want, 20),
            '%s set point %s, not %s' % (joint, self.set_point(joint), want),
        )

    def assert_logged(self, since, *words):
        msg = logged(self.rosout, since, *words)
        self.assertIsNotNone(msg, 'no /rosout message with %s' % (words,))
        return msg

    def paced_spawn(self, kind, name):
        """Spawn bench.big_description(kind) from another process: (success, answer, files the
        world wrote for it); asserts /clock kept the pace of the 1.5 sim s before."""
        self.window.start()
        sim_wait(1.5)
        base_gap, base_rtf = self.window.stop()
        mark = time.time() - 1.0  # mtime has a coarse clock on some file systems
        self.window.start()
        ok, answer = spawn_from_another_process(kind, name)
        sim_wait(0.5)
        gap, rtf = self.window.stop()
        print(
            '%s: %s; max /clock gap %.3f s, real-time factor %.3f (before: %.3f s, %.3f)'
            % (kind, answer, gap, rtf, base_gap, base_rtf)
        )
        self.assertLess(gap, base_gap + GAP_MARGIN, '%s: /clock stopped for %.3f s' % (kind, gap))
        self.assertGreater(rtf, MIN_RTF_RATIO * base_rtf, '%s: real-time factor %.3f' % (kind, rtf))
        return ok, answer, model_files(mark, name)

    # -- big descriptions (issue 22, case 7) -------------------------------------------
    def test_a_50_mb_description_spawns_whole_and_pybullet_is_handed_only_what_it_reads(self):
        ok, answer, files = self.paced_spawn('bulk', 'bulk50')
        self.assertTrue(ok, answer)
        self.assertIn('bulk50', self.world_props().model_names)
        self.assertTrue(files, 'no URDF written for the model')
        # what pybullet parsed on the physics thread: the robot, not 50 MB (before: 50 MB)
        self.assertLess(max(files.values()), 1e6, files)
        self.assertTrue(self.delete('bulk50').success)
        self.assertNotIn('bulk50', self.world_props().model_names)
        self.assertFalse([f for f in files if os.path.exists(f)], 'its URDF stayed')
        self.assert_world_runs()

    def test_a_description_past_the_shape_limit_is_refused_at_once_and_leaves_nothing(self):
        before = set(self.world_props().model_names)
        ok, answer, files = self.paced_spawn('shapes', 'shapes40k')
        self.assertFalse(ok, answer)
        for words in ("'shapes40k'", 'shapes per model is 40', '~limits/shapes_per_model'):
            self.assertIn(words, answer)
        self.assertEqual(set(self.world_props().model_names), before, 'something stayed')
        self.assertFalse([f for f in files if os.path.exists(f)], 'its URDF stayed')
        self.assert_world_runs()

    # -- command topics -----------------------------------------------------------
    def test_nan_and_infinite_commands_are_ignored_with_a_warning_naming_the_controller(self):
        self.command('joint1', 0.3)
        mark = time.monotonic()
        for bad in (math.nan, math.inf, -math.inf):
            self.cmd['joint1'].publish(bad)
            time.sleep(0.1)
        self.assert_logged(mark, 'joint1_position_controller', 'non-finite', 'joint1')
        sim_wait(0.3)
        self.assertEqual(self.set_point('joint1'), 0.3, 'the target was not held')
        self.assert_world_runs()

    def test_huge_commands_are_clamped_to_the_joint_limits_with_a_warning(self):
        mark = time.monotonic()
        self.command('joint1', sys.float_info.max)
        self.assertEqual(self.set_point('joint1'), 1.57)
        self.assert_logged(
            mark, 'joint1_position_controller', 'joint1', 'outside its limits', 'clamped to 1.57'
        )
        self.command('joint1', -1e300)
        self.assertEqual(self.set_point('joint1'), -1.57)
        self.command('joint1', 0.0)
        self.assert_world_runs()

    def test_a_command_of_the_wrong_message_type_is_refused_and_the_target_kept(self):
        before = wait_for(lambda: self.set_point('joint4'), 10)
        proc = subprocess.Popen(
            [
                'rostopic',
                'pub',
                '-r',
                '10',
                CTRL % 'joint4' + '/command',
                'std_msgs/String',
                'data: up',
            ],
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
        )
        try:
            time.sleep(3.0)
        finally:
            proc.terminate()
            out = proc.communicate(timeout=20)[0]
        # rospy's publisher refuses the world's Float64 subscription and says which types differ
        self.assertIn('topic types do not match: [std_msgs/Float64] vs. [std_msgs/String]', out)
        self.assertEqual(self.set_point('joint4'), before)
        self.assert_world_runs()

    # -- /gazebo/set_model_configuration --------------------------------------------
    def test_set_model_configuration_with_mismatched_lengths_fails_naming_both_counts(self):
        for names, values in ((['joint1', 'joint2'], [0.1]), (['joint1'], [0.1, 0.2])):
            resp = self.configure('arm1', '', names, values)
            self.assertFalse(resp.success, (names, values))
            self.assertIn('joint_names', resp.status_message)
            self.assertIn('joint_positions', resp.status_message)
            self.assertIn(str(len(names)), resp.status_message)
            self.assertIn(str(len(values)), resp.status_message)
        self.assert_world_runs()

    def test_set_model_configuration_with_an_unknown_joint_fails_naming_it(self):
        resp = self.configure('arm1', '', ['joint1', 'no_such_joint'], [0.0, 0.0])
        self.assertFalse(resp.success)
        self.assertIn('no_such_joint', resp.status_message)
        self.assert_world_runs()

    def test_set_model_configuration_with_non_finite_positions_fails_naming_the_joint(self):
        for bad in (math.nan, math.inf):
            resp = self.configure('arm1', '', ['joint1', 'joint2'], [0.0, bad])
            self.assertFalse(resp.success)
            self.assertIn('joint2', resp.status_message)
            self.assertIn('non-finite', resp.status_message)
        self.assert_world_runs()

    def test_set_model_configuration_of_an_unknown_model_fails_naming_it(self):
        resp = self.configure('ghost_model', '', ['joint1'], [0.0])
        self.assertFalse(resp.success)
        self.assertIn('ghost_model', resp.status_message)
        self.assert_world_runs()

    def test_set_model_configuration_with_100000_joints_fails_with_a_short_message(self):
        names = ['j%d' % i for i in range(100000)]
        resp = self.configure('arm1', '', names, [0.0] * len(names))
        self.assertFalse(resp.success)
        self.assertIn('j0', resp.status_message)
        self.assertLess(len(resp.status_message), 2000)
        self.assert_world_runs()

    # -- /gazebo/spawn_urdf_model and delete_model --------------------------------------
    def assert_spawn_fails(self, name, xml, *words):
        resp = self.spawn(name, xml, '', None, '')
        self.assertFalse(resp.success, '%s spawned' % name)
        for word in (name,) + words:
            self.assertIn(word, resp.status_message)
        self.assertGreater(len(resp.status_message), len(name) + 15, 'no reason given')
        self.assertLess(len(resp.status_message), 2000)
        return resp.status_message

    def test_spawn_of_an_empty_description_fails_naming_the_model(self):
        self.assert_spawn_fails('empty_model', '')
        self.assert_spawn_fails('blank_model', '   \n')
        self.assert_world_runs()

    def test_spawn_of_text_that_is_not_xml_fails_naming_the_model(self):
        self.assert_spawn_fails('text_model', 'this is not <xml')
        self.assert_spawn_fails('binary_model', '\x00\x01\x02' * 100)
        self.assert_world_runs()

    def test_spawn_of_xml_with_a_root_other_than_robot_fails_naming_it(self):
        self.assert_spawn_fails('sdf_model', '<sdf version="1.6"><model name="m"/></sdf>', 'sdf')
        self.assert_spawn_fails('html_model', '<html><body/></html>', 'html')
        self.assert_world_runs()

    def test_spawn_under_a_name_in_use_fails_and_leaves_the_first(self):
        self.assert_spawn_fails('arm1', urdf('arm1'), 'already exists')
        self.assert_world_runs()

    def test_a_model_without_joints_spawns_while_the_camera_keeps_streaming(self):
        images = ImageRecorder()
        try:
            self.assertTrue(wait_for(lambda: images.meta, 60), 'no image before the spawn')
            resp = self.spawn('lone_box', urdf('lone_box', 1), '', None, '')
            self.assertTrue(resp.success, resp.status_message)
            after = rospy.Time.now().to_sec()
            self.assertTrue(
                wait_for(lambda: len([m for m in images.meta if m[0] > after]) >= 10, 60),
                'the camera stopped after spawning a jointless model',
            )
            self.assert_world_runs()
            resp = self.delete('lone_box')
            self.assertTrue(resp.success, resp.status_message)
            after = rospy.Time.now().to_sec()
            self.assertTrue(
                wait_for(lambda: any(m[0] > after for m in images.meta), 60),
                'the camera stopped after deleting it',
            )
        finally:
            images.close()
        self.assert_world_runs()

    def test_a_model_with_only_fixed_joints_spawns_and_is_deleted(self):
        resp = self.spawn('fixed_chain', urdf('fixed_chain', 3, 'fixed'), '', None, '')
        self.assertTrue(resp.success, resp.status_message)
        self.assert_world_runs()
        resp = self.configure('fixed_chain', '', [], [])
        self.assertTrue(resp.success, resp.status_message)
        resp = self.delete('fixed_chain')
        self.assertTrue(resp.success, resp.status_message)
        self.assert_world_runs()

    def test_delete_of_an_unknown_model_fails_naming_it(self):
        for name in ('ghost_model', ''):
            resp = self.delete(name)
            self.assertFalse(resp.success)
            self.assertIn("'%s'" % name, resp.status_message)
        self.assert_world_runs()

    # -- controller manager ---------------------------------------------------------
    def test_load_controller_with_an_empty_or_invalid_name_fails_saying_why(self):
        mark = time.monotonic()
        self.assertFalse(self.load('').ok)
        self.assert_logged(mark, 'Could not load controller', 'empty')
        mark = time.monotonic()
        self.assertFalse(self.load('two words').ok)
        self.assert_logged(mark, 'two words', 'not a valid controller name')
        mark = time.monotonic()
        self.assertFalse(self.load('x' * 100000).ok)
        msg = self.assert_logged(mark, 'xxxx', '100000 characters', 'not a valid controller name')
        self.assertLess(len(msg), 500, 'the whole name went to the log')
        self.assert_world_runs()

    def test_load_controller_of_an_unknown_or_loaded_name_fails_naming_it(self):
        mark = time.monotonic()
        self.assertFalse(self.load('no_such_controller').ok)
        self.assert_logged(mark, 'no_such_controller', 'type was not specified')
        mark = time.monotonic()
        self.assertFalse(self.load('joint1_position_controller').ok)
        self.assert_logged(mark, 'joint1_position_controller', 'already loaded')
        self.assert_world_runs()

    def test_unload_of_an_unknown_or_running_controller_fails_naming_it(self):
        mark = time.monotonic()
        self.assertFalse(self.unload('no_such_controller').ok)
        self.assert_logged(mark, 'no_such_controller', 'no controller with this name')
        mark = time.monotonic()
        self.assertFalse(self.unload('joint1_position_controller').ok)
        self.assert_logged(mark, 'joint1_position_controller', 'still running')
        self.assert_world_runs()

    def test_strict_switch_with_an_unknown_name_fails_naming_it_and_changes_nothing(self):
        mark = time.monotonic()
        self.assertFalse(self.switch(['no_such_controller'], [], STRICT, False, 0.0).ok)
        self.assert_logged(mark, "Could not start controller 'no_such_controller'", 'not loaded')
        mark = time.monotonic()
        self.assertFalse(
            self.switch(
                [], ['joint1_position_controller', 'no_such_controller'], STRICT, False, 0.0
            ).ok
        )
        self.assert_logged(mark, "Could not stop controller 'no_such_controller'")
        self.assert_world_runs()  # joint1_position_controller was not stopped

    def test_best_effort_switch_skips_unknown_names_with_one_warning(self):
        mark = time.monotonic()
        resp = self.switch(
            ['no_such_controller', 'joint1_position_controller'], ['ghost'], BEST_EFFORT, False, 0.0
        )
        self.assertTrue(resp.ok)
        self.assert_logged(mark, "Not starting controller 'no_such_controller'", 'not loaded')
        self.assert_logged(  # BEST_EFFORT starts a running one again, as ros_control
            mark, "Controller 'joint1_position_controller' is already running", 'starting it again'
        )
        self.assert_logged(mark, "Not stopping controller 'ghost'", 'not loaded')
        self.assert_world_runs()

    def test_switch_with_10000_unknown_names_answers_at_once_with_short_messages(self):
        names = ['ghost%d' % i for i in range(10000)]
        for strictness, ok in ((STRICT, False), (BEST_EFFORT, True)):
            mark = time.monotonic()
            self.assertEqual(self.switch(names, names, strictness, False, 0.0).ok, ok)
            self.assertLess(time.monotonic() - mark, 10.0)
            msg = self.assert_logged(mark, 'ghost0')
            self.assertLess(len(msg), 500)
            sim_wait(0.2)
            said = [m for m in self.rosout.since(mark) if 'ghost' in m.msg]
            self.assertLessEqual(len(said), 2, 'one message per name: %d' % len(said))
        self.assertIn('9995 more', self.assert_logged(mark, 'Not starting', 'ghost0'))
        self.assert_world_runs()

    def test_switch_with_an_invalid_strictness_is_best_effort_with_a_warning(self):
        for strictness in (0, 7, -1):
            mark = time.monotonic()
            self.assertTrue(self.switch(['ghost'], [], strictness, False, 0.0).ok)
            self.assert_logged(mark, 'strictness %d' % strictness, 'BEST_EFFORT')
        self.assert_world_runs()

    def test_switch_with_a_non_finite_or_huge_timeout_waits_for_the_update(self):
        for timeout in (math.nan, math.inf, 1e300, -1.0):
            self.assertTrue(
                self.switch([], ['joint_state_controller'], STRICT, False, timeout).ok, timeout
            )
            self.assertTrue(
                self.switch(['joint_state_controller'], [], STRICT, False, timeout).ok, timeout
            )
        self.assert_world_runs()

    # -- pid/set_parameters (dynamic_reconfigure) -------------------------------------
    def pid_client(self):
        return Client(CTRL % 'joint1' + '/pid', timeout=30)

    def gains_in_state(self):
        msg = self.ctrl_state['joint1'].last()
        return msg.p, msg.i, msg.d, msg.i_clamp

    def test_nan_gains_are_refused_naming_the_controller_and_the_old_ones_kept(self):
        client = self.pid_client()
        before = client.get_configuration(10)
        state_before = self.gains_in_state()
        mark = time.monotonic()
        after = client.update_configuration({'p': math.nan, 'd': math.nan})
        self.assertEqual((after['p'], after['d']), (before['p'], before['d']))
        self.assert_logged(mark, 'joint1_position_controller', 'refusing pid gains', 'non-finite')
        sim_wait(0.2)
        self.assertEqual(self.gains_in_state(), state_before)
        client.close()
        self.assert_world_runs()

    def test_huge_gains_are_clamped_to_the_configured_range_and_the_arm_stays_finite(self):
        client = self.pid_client()
        before = client.get_configuration(10)
        try:
            after = client.update_configuration(
                {'p': 1e12, 'd': 1e12, 'i': 1e12, 'i_clamp_max': 1e12}
            )
            self.assertEqual(
                (after['p'], after['i'], after['d'], after['i_clamp_max']),
                (100000.0, 100000.0, 1000.0, 100000.0),
            )
            self.assertTrue(wait_for(lambda: self.gains_in_state()[0] == 100000.0, 10))
            self.cmd['joint1'].publish(0.2)
            sim_wait(1.0)
            self.assertTrue(finite_arm(self.states))
            state = self.ctrl_state['joint1'].last()
            self.assertTrue(math.isfinite(state.command) and math.isfinite(state.error))
        finally:
            client.update_configuration(
                {k: before[k] for k in ('p', 'i', 'd', 'i_clamp_min', 'i_clamp_max')}
            )
            client.close()
        self.command('joint1', 0.0)
        self.assert_world_runs()

    def test_negative_gains_apply_with_a_warning_naming_the_controller(self):
        client = self.pid_client()
        before = client.get_configuration(10)
        mark = time.monotonic()
        try:
            after = client.update_configuration({'p': -2.0})
            self.assertEqual(after['p'], -2.0)  # control_toolbox's range allows it
            self.assert_logged(mark, 'joint1_position_controller', 'negative', 'p=-2')
            sim_wait(1.0)
            self.assertTrue(finite_arm(self.states))
        finally:
            client.update_configuration({'p': before['p']})
            client.close()
        self.command('joint1', 0.0)
        self.assert_world_runs()

    # -- malformed requests on the wire --------------------------------------------------
    def test_garbage_bytes_to_a_service_port_leave_the_service_working(self):
        raw_service_call('/gazebo/delete_model', {'nonsense': 'x'}, b'\xff' * 64)
        raw_service_call('/gazebo/delete_model', {}, b'')
        resp = self.delete('ghost_model')
        self.assertFalse(resp.success)
        self.assertIn('ghost_model', resp.status_message)
        self.assert_world_runs()

    def test_a_request_of_the_wrong_service_type_is_refused_naming_the_mismatch(self):
        reply = raw_service_call(
            '/gazebo/delete_model',
            {
                'service': '/gazebo/delete_model',
                'md5sum': SpawnModel._md5sum,
                'callerid': '/faults_raw',
            },
            b'',
        )
        self.assertIn(b'md5sums do not match', reply)
        self.assertTrue(self.delete('ghost_model').status_message)
        self.assert_world_runs()

    def test_a_truncated_request_body_is_refused_and_the_service_keeps_working(self):
        header = {
            'service': '/gazebo/set_model_configuration',
            'md5sum': SetModelConfiguration._md5sum,
            'callerid': '/faults_raw',
        }
        # a model_name claiming 2 GB, then nothing
        raw_service_call(
            '/gazebo/set_model_configuration',
            header,
            b'\x08\x00\x00\x00' + b'\xff\xff\xff\x7f' + b'abcd',
        )
        resp = self.configure('ghost_model', '', [], [])
        self.assertFalse(resp.success)
        self.assert_world_runs()

    # -- floods ----------------------------------------------------------------------
    def pace_window_end(self, start, least=3.0):
        """The newest /clock once ``least`` wall seconds have passed since ``start``: a window
        long enough that /clock's 10 ms granularity does not count (the pacer hides lags
        below 0.1 s by catching up, so a short window would show only noise)."""
        time.sleep(max(0.0, start[0] + least - time.monotonic()))
        return self.pace.now()

    def test_a_burst_of_10000_commands_is_absorbed_and_the_clock_keeps_pace(self):
        base = self.pace.baseline()
        start = self.pace.now()
        pub = self.cmd['joint3']
        for k in range(10000):
            pub.publish(0.3 if k % 2 else -0.3)
        pub.publish(0.25)
        sent = time.monotonic() - start[0]
        self.assertTrue(
            wait_for(lambda: self.set_point('joint3') == 0.25, 60),
            'the last command of the burst never arrived',
        )
        applied = time.monotonic() - start[0]
        end = self.pace_window_end(start)
        factor = self.pace.factor(start, end)
        print(
            '10000 commands sent in %.2f s, the last applied after %.2f s: real-time factor '
            '%.3f over %.1f s from the first (before: %.3f)'
            % (sent, applied, factor, end[0] - start[0], base)
        )
        self.assertGreaterEqual(factor, MIN_PACE_RATIO * base)
        self.command('joint3', 0.0)
        self.assert_world_runs()

    def test_500_service_calls_from_8_threads_are_all_answered_and_the_clock_keeps_pace(self):
        proxies = [
            (CM + 'list_controller_types', ListControllerTypes, ()),
            (
                '/gazebo/set_model_configuration',
                SetModelConfiguration,
                ('arm1', '', ['no_such_joint'], [0.0]),
            ),
            (CM + 'load_controller', LoadController, ('joint1_position_controller',)),
            ('/gazebo/delete_model', DeleteModel, ('ghost_model',)),
        ]
        answered, errors, lock = [], [], threading.Lock()

        def worker(k):
            for n in range(63):
                name, srv, args = proxies[(k + n) % len(proxies)]
                try:
                    resp = rospy.ServiceProxy(name, srv)(*args)
                    with lock:
                        answered.append(resp)
                except Exception as exc:  # counted, reported below
                    with lock:
                        errors.append('%s: %s' % (name, exc))

        base = self.pace.baseline()
        start = self.pace.now()
        threads = [threading.Thread(target=worker, args=(k,)) for k in range(8)]
        for t in threads:
            t.start()
        for t in threads:
            t.join(120)
        took = time.monotonic() - start[0]
        end = self.pace_window_end(start)
        factor = self.pace.factor(start, end)
        print(
            '504 service calls in %.1f s: real-time factor %.3f over %.1f s from the first '
            '(before: %.3f)' % (took, factor, end[0] - start[0], base)
        )
        self.assertEqual(errors, [])
        self.assertEqual(len(answered), 504)
        self.assertGreaterEqual(factor, MIN_PACE_RATIO * base)
        self.assert_world_runs()


if __name__ == '__main__':
    if sys.argv[1:2] == [BIG_CLIENT]:
        big_client_main(*sys.argv[2:4])
    else:
        rostest.rosrun('arm1', 'test_faults_inputs', FaultsInputs)
