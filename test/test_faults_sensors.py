#!/usr/bin/env python
"""Bad input to the surface of SDF spawns, sensors and fixed-joint lumping (issue 10).

Against an empty headless world (arm1_faults_sensors.test, the world's output in its log
file): spawn_sdf_model with non-finite poses and numbers, a DTD, 100000 links, a 99000-frame
relative_to chain, mesh URIs that climb out or are missing, duplicate names, nothing, a URDF,
an unknown reference_frame; spawn_urdf_model with SDF; robots with malformed sensor
parameters; fixed-joint trees with loops, duplicates, NaN inertias and 5000 links; a robot
with a laser, an IMU and a depth camera deleted and respawned 20 times while its topics have
subscribers, and subscribers that come and go; a client killed while the world parses its
costly spawn. Each refusal names the culprit, the world lives, /clock keeps real time, and
no traceback through arm1's code reaches the world's log (rospy logs its own connection
races with one).
"""

import glob
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import threading
import time
import unittest

import numpy as np
import rospkg
import rospy
import rostest
from gazebo_msgs.srv import DeleteModel, GetModelState, SpawnModel
from geometry_msgs.msg import Point, Pose, Quaternion
from sensor_msgs.msg import Image, Imu, LaserScan

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(1, os.path.join(os.path.dirname(os.path.abspath(__file__)), 'unit'))
from faults_util import ClockPace, World, logged  # noqa: E402
from rostest_util import clock_recorder, rosout_recorder, wait_for  # noqa: E402
from urdf_snippets import joint, link, sdf_tower  # noqa: E402

from _arm1sim.bench import dense_meshes  # noqa: E402

# Real-time factors from /clock, as a share of the 3 s before (what the machine gives the
# world now: other work may share it). Over subscriber churn (0.9-1.0 on an idle machine):
MIN_PACE_RATIO = 0.8
# over a 3 s window holding a costly request (~1.5 s of parsing on a loaded 2-core machine):
# parsed on the physics thread it would fall to ~0.5; on the caller's, 0.97-1.0 was seen
# here (0.82 once, under other helpers' load)
MIN_PARSE_PACE_RATIO = 0.75
ERROR = 8  # rosgraph_msgs/Log level


def robot(name, *parts):
    return '<robot name="%s">%s</robot>' % (name, ''.join(parts))


def sdf_box(pose='0 0 0.5 0 0 0', mass='1', size='0.1 0.1 0.1', uri=None, extra=''):
    geometry = '<mesh><uri>%s</uri></mesh>' % uri if uri else '<box><size>%s</size></box>' % size
    return (
        '<sdf version="1.6"><model name="box"><pose>%s</pose><link name="body">'
        '<inertial><mass>%s</mass></inertial><collision name="c"><geometry>%s</geometry>'
        '</collision></link>%s</model></sdf>' % (pose, mass, geometry, extra)
    )


def cube_triangles(size):
    """A closed cube, wound outward."""
    c = [(x, y, z) for x in (0, size) for y in (0, size) for z in (0, size)]
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    return [t for a, b, d, e in quads for t in ((c[a], c[b], c[d]), (c[a], c[d], c[e]))]


def write_mesh(path, tris):
    """Triangles as a binary STL (written here: this Python may lack numpy-stl), an OBJ or a
    COLLADA file (bench/dense_meshes.py), by the extension."""
    if not path.endswith('.stl'):
        dense_meshes.write_mesh(path, np.asarray(tris, dtype=float))
        return
    flat = [float(v) for t in tris for corner in t for v in corner]
    with open(path, 'wb') as f:
        f.write(b'broken mesh by test_faults_sensors'.ljust(80) + struct.pack('<I', len(tris)))
        for i in range(len(tris)):
            f.write(struct.pack('<12fH', 0, 0, 0, *flat[9 * i : 9 * i + 9], 0))


def mesh_part(path, visual=False):
    """A free part whose one collision is the mesh at ``path`` (its visual too: ``visual``,
    as a CAD export has them)."""
    mesh = '<geometry><mesh filename="file://%s"/></geometry>' % path
    return (
        '<robot name="part"><link name="part"><inertial><mass value="0.1"/><inertia ixx="1e-4" '
        'iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>%s<collision>%s</collision>'
        '</link></robot>' % ('<visual>%s</visual>' % mesh if visual else '', mesh)
    )


def laser(rate='10', samples='60', vertical='1', on='base'):
    return (
        '<gazebo reference="%s"><sensor type="ray" name="laser"><update_rate>%s</update_rate>'
        '<ray><scan><horizontal><samples>%s</samples><min_angle>-1</min_angle>'
        '<max_angle>1</max_angle></horizontal><vertical><samples>%s</samples></vertical></scan>'
        '<range><min>0.1</min><max>10</max></range></ray>'
        '<plugin name="laser" filename="libgazebo_ros_laser.so"><topicName>/faults/scan'
        '</topicName><frameName>base</frameName></plugin></sensor></gazebo>'
        % (on, rate, samples, vertical)
    )


IMU = (
    '<gazebo reference="base"><sensor type="imu" name="imu"><update_rate>50</update_rate>'
    '<always_on>true</always_on><plugin name="imu" filename="libgazebo_ros_imu_sensor.so">'
    '<topicName>/faults/imu</topicName><frameName>base</frameName>'
    '<updateRateHZ>50</updateRateHZ></plugin></sensor></gazebo>'
)
DEPTH = (
    '<gazebo reference="base"><sensor type="depth" name="depth"><update_rate>5</update_rate>'
    '<camera><horizontal_fov>1</horizontal_fov><image><width>32</width><height>24</height>'
    '</image><clip><near>0.05</near><far>10</far></clip></camera>'
    '<plugin name="kinect" filename="libgazebo_ros_openni_kinect.so">'
    '<robotNamespace>faults</robotNamespace><cameraName>depth</cameraName>'
    '<depthImageTopicName>depth/image_raw</depthImageTopicName></plugin></sensor></gazebo>'
)
DEPTH_TOPIC = '/faults/depth/depth/image_raw'
# A client sending a 99000-frame SDF model (about 1.5 s for the world to parse), to be killed
ORPHAN_CLIENT = '''
import rospy
from gazebo_msgs.srv import SpawnModel
rospy.init_node('orphan_client', anonymous=True)
frames = ''.join('<frame name="f%d"><pose relative_to="%s">0 0 1e-5 0 0 0</pose></frame>'
                 % (i, 'f%d' % (i - 1) if i else '__model__') for i in range(99000))
xml = ('<sdf version="1.6"><model name="m"><link name="l"><pose relative_to="f98999">'
       '0 0 0 0 0 0</pose></link>%s</model></sdf>' % frames)
rospy.wait_for_service('/gazebo/spawn_sdf_model', 30)
rospy.loginfo('orphan_client sending')
rospy.ServiceProxy('/gazebo/spawn_sdf_model', SpawnModel)('orphan', xml, '', None, '')
'''


def world_log_text():
    """What the world wrote to its log files (roslaunch output="log") in this run."""
    run = os.path.join(rospkg.get_log_dir(), rospy.get_param('/run_id'))
    text = ''
    for path in glob.glob(os.path.join(run, 'gazebo-*.log')):
        with open(path, errors='replace') as f:
            text += f.read()
    return text


def pose(x=0.0, y=0.0, z=0.0, q=(0.0, 0.0, 0.0, 1.0)):
    return Pose(Point(x, y, z), Quaternion(*q))


class FaultsSensors(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_faults_sensors')
        cls.rosout = rosout_recorder()
        cls.clock = clock_recorder()
        cls.pace = ClockPace(cls.clock)
        cls.world = World()
        rospy.wait_for_service('/gazebo/spawn_sdf_model', 60)
        cls.sdf_srv = rospy.ServiceProxy('/gazebo/spawn_sdf_model', SpawnModel)
        cls.urdf_srv = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
        cls.delete = rospy.ServiceProxy('/gazebo/delete_model', DeleteModel)
        cls.model_state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        assert cls.pace.advances(0.2), 'no /clock'

    # -- helpers ------------------------------------------------------------------
    def assert_world_runs(self):
        self.assertTrue(self.world.alive(), 'the world process is gone')
        self.assertTrue(self.pace.advances(0.2), '/clock stopped')

    def refused(self, srv, name, xml, *words, initial=None, reference=''):
        resp = srv(name, xml, '', initial or pose(), reference)
        self.assertFalse(resp.success, '%s spawned: %s' % (name, resp.status_message))
        for word in words:
            self.assertIn(word, resp.status_message)
        self.assertLess(len(resp.status_message), 2000)
        return resp.status_message

    def spawned(self, srv, name, xml, initial=None, reference=''):
        resp = srv(name, xml, '', initial or pose(), reference)
        self.assertTrue(resp.success, resp.status_message)
        return resp.status_message

    def gone(self, name):
        resp = self.delete(name)
        self.assertTrue(resp.success, resp.status_message)

    def paced(self, action, least=3.0):
        """Run ``action``; return its result, its wall time and /clock's real-time factor over
        at least ``least`` s from its start (shorter windows show only /clock's granularity)
        as a share of the factor over the ``least`` s before it."""
        base = self.pace.baseline(least)
        start = self.pace.now()
        out = action()
        took = time.monotonic() - start[0]
        time.sleep(max(0.0, start[0] + least - time.monotonic()))
        return out, took, self.pace.factor(start, self.pace.now()) / max(base, 1e-9)

    # -- spawn_sdf_model ----------------------------------------------------------
    def test_sdf_non_finite_numbers_are_refused_naming_the_element(self):
        nan = float('nan')
        for initial in (pose(x=nan), pose(q=(0.0, 0.0, math.inf, 1.0))):
            self.refused(
                self.sdf_srv, 'nan_pose', sdf_box(), "'nan_pose'", 'initial pose', initial=initial
            )
        self.refused(self.sdf_srv, 'nan_sdf', sdf_box(pose='nan 0 0 0 0 0'), '<pose>', 'nan')
        self.refused(self.sdf_srv, 'inf_mass', sdf_box(mass='inf'), "link 'body'", '<mass>')
        self.refused(self.sdf_srv, 'nan_size', sdf_box(size='0.1 nan 0.1'), "'c'", 'box size')
        self.assert_world_runs()

    def test_negative_or_nan_shape_sizes_are_refused_naming_link_and_shape(self):
        # pybullet took them from a URDF: a NaN cylinder flew off, a NaN box fell through
        self.refused(self.sdf_srv, 'neg_size', sdf_box(size='-1 0.1 0.1'), "'body'", 'box size')
        cylinder = (
            '<link name="can"><collision><geometry><cylinder radius="0.1" length="nan"/>'
            '</geometry></collision></link>'
        )
        self.refused(self.urdf_srv, 'nan_can', robot('r', cylinder), "'can'", 'cylinder length')
        self.assert_world_runs()

    def test_sdf_with_a_dtd_or_nothing_is_refused_naming_the_model(self):
        laughs = '<!DOCTYPE sdf [<!ENTITY a "aaaaaaaaaa">]>' + sdf_box()
        self.refused(self.sdf_srv, 'dtd_box', laughs, "'dtd_box'", '<!DOCTYPE>')
        self.refused(self.sdf_srv, 'empty_box', '', "'empty_box'")
        self.refused(self.sdf_srv, 'html_box', '<html/>', "'html_box'", 'html')
        self.assert_world_runs()

    def test_broken_meshes_are_repaired_or_left_out_naming_the_file_and_the_world_runs(self):
        """NaN and infinite vertices, out-of-range OBJ indices, no triangle at all, a
        COLLADA index past its source: pybullet crashed on the first two or let the part
        fall through the ground. Each spawns with a warning naming its file, and goes."""
        folder = tempfile.mkdtemp(prefix='arm1-broken-meshes-')
        self.addCleanup(shutil.rmtree, folder, True)
        cube = np.array(cube_triangles(0.05))
        bad = cube.copy()
        bad[3, 1, 0] = float('nan')
        worse = cube.copy()
        worse[5, 2, 2] = float('inf')
        files = {
            'nan.stl': ('left out', bad),
            'inf.stl': ('left out', worse),
            'empty.stl': ('no triangle', cube[:0]),
            'range.obj': ('not in the file', cube),
            'range.dae': ('beyond the limits', cube),
        }
        for name, (_, tris) in files.items():
            write_mesh(os.path.join(folder, name), tris)
        with open(os.path.join(folder, 'range.obj'), 'a') as f:
            f.write('f 1 2 100000\n')
        with open(os.path.join(folder, 'range.dae')) as f:
            text = f.read()
        with open(os.path.join(folder, 'range.dae'), 'w') as f:
            f.write(text.replace('<p>0 1 2 ', '<p>0 1 9999 '))
        for i, (name, (words, _)) in enumerate(files.items()):
            path = os.path.join(folder, name)
            model = 'broken_%d' % i
            mark = time.monotonic()
            self.spawned(self.urdf_srv, model, mesh_part(path), pose(x=2.0 + i, z=0.2))
            self.assertTrue(logged(self.rosout, mark, path, words), '%s: not said' % name)
        for i in range(len(files)):  # (test_broken_meshes.py: repaired parts rest on a ground)
            self.gone('broken_%d' % i)
        self.assert_world_runs()

    def test_a_2m_triangle_mesh_keeps_the_clock_going(self):
        """pybullet built such a collision mesh's hull on the physics thread: /clock stood
        still for 6-11 s. Its hull's points are made on the caller's thread now
        (physics/mesh_hulls.py; test_mesh_hulls.py measures the physics share: 1 ms). As its
        visual (a CAD export's), pybullet parsed it there too (2 s of CPU for 95 MB): a
        stand-in now (physics/visual_stand_ins.py)."""
        folder = tempfile.mkdtemp(prefix='arm1-dense-mesh-')
        self.addCleanup(shutil.rmtree, folder, True)
        path = os.path.join(folder, 'dense.stl')
        dense_meshes.cube_grid_stl(path, 2_000_000 // 12 + 1)
        _, took, factor = self.paced(
            lambda: self.spawned(
                self.urdf_srv, 'dense_2m', mesh_part(path, visual=True), pose(x=-2, z=0.5)
            )
        )
        print('2 M triangles: spawned in %.2f s, %.2f of the pace before' % (took, factor))
        self.gone('dense_2m')
        self.assertLess(took, 60.0)
        # a stall of seconds in the >= 3 s window would bring it near 0; the caller's reading
        # (~2 s of CPU) shares the two cores with the physics thread
        self.assertGreaterEqual(factor, 0.5)
        self.assert_world_runs()

    def test_sdf_mesh_uris_that_climb_out_are_refused_and_missing_ones_left_out(self):
        for uri in ('model://../../../etc/passwd', '../../../../etc/passwd', 'file:///etc/passwd'):
            msg = self.refused(self.sdf_srv, 'climber', sdf_box(uri=uri), "'climber'", uri)
            self.assertNotIn('root:x:0:0', msg)
        self.refused(self.sdf_srv, 'no_mesh', sdf_box(uri='model://ghost/m.stl'), 'model://ghost')
        # within a model on GAZEBO_MODEL_PATH (test/worlds/models): a missing file is left
        # out with a warning (as Gazebo's server), a way out is refused
        missing = 'model://sdf_crate/meshes/nope.stl'
        mark = time.monotonic()
        self.spawned(self.sdf_srv, 'no_file', sdf_box(uri=missing))
        self.assertTrue(logged(self.rosout, mark, "'body'", 'nope.stl', 'not found'))
        self.gone('no_file')
        out = 'model://sdf_crate/../../../../../../etc/passwd'
        msg = self.refused(self.sdf_srv, 'leaver', sdf_box(uri=out), "leaves model 'sdf_crate'")
        self.assertNotIn('root:x:0:0', msg)
        self.assert_world_runs()

    def test_sdf_duplicate_names_and_unknown_reference_frame_are_refused_naming_them(self):
        twice = sdf_box(extra='<link name="body"/>')
        self.refused(self.sdf_srv, 'twice', twice, "'body'", 'used twice')
        self.refused(self.sdf_srv, 'anchored', sdf_box(), 'ghost_frame', reference='ghost_frame')
        self.refused(
            self.urdf_srv,
            'anchored',
            robot('r', link('base')),
            'ghost_frame',
            reference='ghost_frame',
        )
        self.spawned(self.sdf_srv, 'anchor', sdf_box(pose='0 0 0 0 0 0'), pose(x=3.0))
        try:
            self.spawned(self.sdf_srv, 'anchored', sdf_box(), pose(y=1.0), reference='anchor')
            where = self.model_state('anchored', '').pose.position
            self.assertAlmostEqual(where.x, 3.0, delta=0.05)  # the anchor's x, then y=1 in it
            self.assertAlmostEqual(where.y, 1.0, delta=0.05)
            self.gone('anchored')
        finally:
            self.gone('anchor')
        self.assert_world_runs()

    def test_a_urdf_to_spawn_sdf_model_spawns_and_sdf_to_spawn_urdf_model_is_refused(self):
        self.spawned(self.sdf_srv, 'urdf_by_sdf', robot('r', link('base')))
        self.gone('urdf_by_sdf')
        self.refused(self.urdf_srv, 'sdf_by_urdf', sdf_box(), "'sdf_by_urdf'", 'sdf')
        self.assert_world_runs()

    def test_an_sdf_model_of_120_links_spawns(self):
        # its URDF came out on one line that pybullet could not read (74f158d)
        self.spawned(self.sdf_srv, 'tower', sdf_tower(120), pose(x=-3.0))
        self.gone('tower')
        self.assert_world_runs()

    def test_100000_links_or_a_99000_frame_chain_are_answered_in_bounded_time_at_pace(self):
        links = ''.join('<link name="l%d"/>' % i for i in range(100000))
        xml = '<sdf version="1.6"><model name="m">%s</model></sdf>' % links
        msg, took, factor = self.paced(
            lambda: self.refused(self.sdf_srv, 'huge', xml, 'links per model', '100000')
        )
        print('100000 links: refused in %.2f s, %.2f of the pace before' % (took, factor))
        self.assertLess(took, 30.0)
        self.assertGreaterEqual(factor, MIN_PARSE_PACE_RATIO)
        frames = '<frame name="f0"><pose relative_to="__model__">0 0 0 0 0 0</pose></frame>'
        frames += ''.join(
            '<frame name="f%d"><pose relative_to="f%d">0 0 1e-5 0 0 0</pose></frame>' % (i, i - 1)
            for i in range(1, 99000)
        )
        xml = (
            '<sdf version="1.6"><model name="m"><link name="l"><pose relative_to="f98999">'
            '0 0 0 0 0 0</pose></link>%s</model></sdf>' % frames
        )
        _, took, factor = self.paced(lambda: self.spawned(self.sdf_srv, 'deep', xml))
        print('99000-frame chain: spawned in %.2f s, %.2f of the pace before' % (took, factor))
        self.gone('deep')
        self.assertLess(took, 60.0)
        self.assertGreaterEqual(factor, MIN_PARSE_PACE_RATIO)
        self.assert_world_runs()

    def test_a_client_killed_during_a_costly_sdf_spawn_leaves_the_world_serving(self):
        child = subprocess.Popen([sys.executable, '-c', ORPHAN_CLIENT])
        try:
            # killed once its request is out and being parsed (~1.5 s for the world)
            self.assertTrue(
                wait_for(lambda: logged(self.rosout, 0, 'orphan_client', timeout=0), 30),
                'the client never started',
            )
            time.sleep(0.7)
        finally:
            child.kill()
            child.wait(10)
        start = time.monotonic()
        self.refused(self.sdf_srv, 'after_orphan', '', "'after_orphan'")
        self.assertLess(time.monotonic() - start, 10.0)
        # the spawn may have finished for nobody, as upstream's would: then it is a model
        if wait_for(lambda: self.model_state('orphan', '').success, 10):
            self.gone('orphan')
        self.assert_world_runs()

    # -- sensors ------------------------------------------------------------------
    def test_malformed_sensor_parameters_are_refused_naming_sensor_and_parameter(self):
        base = link('base')
        cases = [
            (laser(rate='nan'), ("sensor 'laser'", '<update_rate>', 'nan')),
            (laser(samples='-5'), ("sensor 'laser'", 'samples', '-5')),
            (laser(samples='2000', vertical='1000'), ("sensor 'laser'", 'rays per laser')),
            (laser(rate='1e9'), ("sensor 'laser'", 'sensor update rate')),
            # within rays_per_laser, but ~2 s of ray casting on the physics thread per scan
            (laser(rate='10', samples='1000', vertical='1000'), ('ray casts per second',)),
            (IMU.replace('<update_rate>50', '<update_rate>inf'), ("sensor 'imu'", 'inf')),
            (DEPTH.replace('<width>32', '<width>-32'), ("sensor 'depth'", '-32')),
            # rospy took these, logged FATAL and advertised nothing; the spawn said success
            (laser().replace('/faults/scan', 'bad topic!'), ("'/bad topic!'", 'legal ROS name')),
            (
                DEPTH.replace('>depth</cameraName', '>de pth</cameraName'),
                ("'depth'", "'/faults/de pth/"),
            ),
        ]
        for sensor, words in cases:
            self.refused(self.urdf_srv, 'bad_sensor', robot('r', base, sensor), *words)
        self.assert_world_runs()

    def test_sensors_and_plugins_naming_unknown_links_or_joints_are_warned_about_by_name(self):
        ft = (
            '<gazebo><plugin name="ft" filename="libgazebo_ros_ft_sensor.so"><jointName>ghost_j'
            '</jointName><topicName>ft</topicName></plugin></gazebo>'
        )
        p3d = (
            '<gazebo><plugin name="odom" filename="libgazebo_ros_p3d.so"><bodyName>ghost_b'
            '</bodyName><topicName>odom</topicName></plugin></gazebo>'
        )
        mark = time.monotonic()
        self.spawned(self.urdf_srv, 'lost', robot('r', link('base'), laser(on='ghost_l'), ft, p3d))
        try:
            for word in ('ghost_l', 'ghost_j', 'ghost_b'):
                self.assertIsNotNone(logged(self.rosout, mark, "'lost'", word), word)
        finally:
            self.gone('lost')
        self.assert_world_runs()

    def test_a_sensed_robot_deleted_and_respawned_20_times_under_subscribers_stays_bounded(self):
        xml = robot('r', link('base'), laser(), IMU, DEPTH)
        topics = {'/faults/scan': LaserScan, '/faults/imu': Imu, DEPTH_TOPIC: Image}
        got = {topic: [] for topic in topics}

        def subscribe():
            return [
                rospy.Subscriber(t, k, lambda m, t=t: got[t].append(time.monotonic()), queue_size=1)
                for t, k in topics.items()
            ]

        subs = subscribe()
        mark = time.monotonic()
        try:
            samples = []
            for cycle in range(20):
                self.spawned(self.urdf_srv, 'sensed', xml, pose(z=0.5))
                if cycle in (0, 9, 19):  # re-advertised: every topic delivers to a new subscriber
                    # (a subscriber kept across quick respawns may miss the new publisher for
                    # good: the master's publisherUpdates to it can arrive out of order)
                    for sub in subs:
                        sub.unregister()
                    subs = subscribe()
                    since = time.monotonic()
                    for topic, arrived in got.items():
                        self.assertTrue(
                            wait_for(lambda: any(t > since for t in arrived), 30),
                            'nothing on %s after respawn %d' % (topic, cycle + 1),
                        )
                    samples.append((self.world.threads(), self.world.rss_mb()))
                self.gone('sensed')
        finally:
            for sub in subs:
                sub.unregister()
        print('threads, RSS MB after respawns 1, 10, 20: %s' % samples)
        self.assertLessEqual(samples[-1][0], samples[0][0] + 4, 'threads grow')
        self.assertLess(samples[-1][1], samples[0][1] + 150, 'memory grows')
        errors = [m.msg for m in self.rosout.since(mark) if m.level >= ERROR]
        self.assertEqual(errors, [])
        self.assert_world_runs()

    def test_subscribers_that_connect_and_vanish_rapidly_leave_the_sensor_publishing(self):
        self.spawned(self.urdf_srv, 'flicker', robot('r', link('base'), laser(rate='50'), IMU))
        try:
            base = self.pace.baseline()
            stop = time.monotonic() + 8.0

            def churn(topic, kind):
                while time.monotonic() < stop:
                    sub = rospy.Subscriber(topic, kind, lambda msg: None, queue_size=1)
                    time.sleep(0.02)
                    sub.unregister()

            start = self.pace.now()
            threads = [
                threading.Thread(target=churn, args=(t, k))
                for t, k in (('/faults/scan', LaserScan), ('/faults/imu', Imu)) * 2
            ]
            for t in threads:
                t.start()
            for t in threads:
                t.join(30)
            factor = self.pace.factor(start, self.pace.now())
            print('subscriber churn for 8 s: real-time factor %.3f (before: %.3f)' % (factor, base))
            self.assertGreaterEqual(factor, MIN_PACE_RATIO * base)
            msg = rospy.wait_for_message('/faults/scan', LaserScan, 30)
            self.assertEqual(len(msg.ranges), 60)
        finally:
            self.gone('flicker')
        self.assert_world_runs()

    # -- fixed-joint lumping and gazebo tags --------------------------------------
    def test_bad_fixed_joint_trees_are_refused_naming_the_culprit(self):
        l0, l1, l2 = link('l0'), link('l1'), link('l2')
        loop = robot(
            'r', l0, l1, l2, joint('a', 'l0', 'l1'), joint('b', 'l1', 'l2'), joint('c', 'l2', 'l1')
        )
        self.refused(self.urdf_srv, 'loop', loop, "'loop'", 'l1')
        twice = robot('r', l0, l1, joint('j1', 'l0', 'l1'), joint('j1', 'l0', 'l1'))
        self.refused(self.urdf_srv, 'twice', twice, "joint 'j1' is not unique")
        for mass, ixx in (('nan', '1e-4'), ('0.1', 'nan')):
            nan = robot('r', l0, link('l1', mass, ixx), joint('j1', 'l0', 'l1'))
            self.refused(self.urdf_srv, 'nan_lump', nan, "link 'l1' <inertial>", 'finite')
        tags = '<gazebo reference="l1"><mu1>nan</mu1></gazebo>'
        self.refused(
            self.urdf_srv,
            'nan_mu',
            robot('r', l0, l1, joint('j', 'l0', 'l1'), tags),
            "reference='l1'",
            'nan',
        )
        self.assert_world_runs()

    def test_fixed_chains_of_900_links_spawn_and_of_5000_are_refused_at_pace(self):
        def chain(n):
            return robot(
                'r',
                *[link('l%d' % i) for i in range(n)],
                *[joint('j%d' % i, 'l%d' % (i - 1), 'l%d' % i) for i in range(1, n)],
            )

        _, took, factor = self.paced(
            lambda: self.refused(self.urdf_srv, 'chain5000', chain(5000), 'links per model')
        )
        print('5000-link fixed chain: refused in %.2f s, %.2f of the pace before' % (took, factor))
        self.assertLess(took, 30.0)
        self.assertGreaterEqual(factor, MIN_PARSE_PACE_RATIO)
        # lumped into one link, its URDF had a line pybullet could not read (74f158d)
        _, took, factor = self.paced(
            lambda: self.spawned(self.urdf_srv, 'chain900', chain(900), pose(x=5.0))
        )
        print('900-link fixed chain: spawned in %.2f s, %.2f of the pace before' % (took, factor))
        self.gone('chain900')
        self.assertGreaterEqual(factor, MIN_PARSE_PACE_RATIO)
        self.assert_world_runs()

    def test_zz_the_world_log_has_no_traceback_through_arm1(self):
        text = world_log_text()
        self.assertTrue(text, 'no world log found')
        blocks = [b[:3000] for b in text.split('Traceback (most recent call last):')[1:]]
        # rospy logs its own connection races with a traceback and goes on: a subscriber that
        # vanishes mid-handshake, or connects while a deleted model's publisher closes
        # (ros_comm#544); a traceback through arm1's code is ours
        ours = [
            b
            for b in blocks
            if any('/arm1/' in line for line in b.splitlines()[:40] if line.startswith('  File '))
        ]
        print('world log: %d traceback(s), all within rospy' % (len(blocks) - len(ours)))
        self.assertEqual(ours, [])


if __name__ == '__main__':
    rostest.rosrun('arm1', 'test_faults_sensors', FaultsSensors)
