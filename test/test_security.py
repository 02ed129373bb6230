#!/usr/bin/env python
"""Nothing a ROS client sends reaches beyond the simulation, or stops it for everyone.

Against a real world (arm1_security.test: an empty world whose file sets the models limit
to 40), each case sends one kind of hostile spawn request and checks for a clear refusal:
path-like and oversized model names (and that no file appears where the name points), a
billion-laughs and an external-entity URDF, mesh URIs that climb out of their package or
name a file that is no mesh (and that the file's contents appear neither in the reply nor
on /rosout), a 6000x6000 camera at 30 Hz, and a flood of 200 spawns from 8 threads. The
last case checks that /clock kept the pace the machine gives the world over the whole test.
"""

import os
import shutil
import sys
import tempfile
import threading
import time
import uuid

import rospy
import rostest
from gazebo_msgs.srv import DeleteModel, SpawnModel

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from camera_util import node_pid  # noqa: E402
from faults_util import ClockPace  # noqa: E402
from rostest_util import WorldTestCase, wait_for  # noqa: E402

MODELS_LIMIT = 40  # test/config/security.world
# Through the cases, the real-time factor at least this share of the world's own pace right
# after them: what the machine gives the world is judged, not the cases (0.95 of 1.0 alone
# failed at 0.90 with both cores kept busy by stress-ng and the suite).
MIN_RTF_RATIO = 0.9
PASSWD_WORDS = ('root:x:0:0', '/bin/bash', '/usr/sbin/nologin')

BOX = (
    '<robot name="{name}"><link name="body">'
    '<inertial><mass value="0.1"/>'
    '<inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>'
    '<visual><geometry>{geometry}</geometry></visual>'
    '<collision><geometry><box size="0.05 0.05 0.05"/></geometry></collision>'
    '</link>{extra}</robot>'
)


def box(name='box', geometry='<box size="0.05 0.05 0.05"/>', extra=''):
    return BOX.format(name=name, geometry=geometry, extra=extra)


LAUGHS = (
    '<?xml version="1.0"?><!DOCTYPE robot [<!ENTITY lol "lol">'
    + ''.join(
        '<!ENTITY lol%d "%s">' % (i, ('&lol%s;' % (i - 1 if i > 1 else '')) * 10)
        for i in range(1, 10)
    )
    + ']>'
    + box('&lol9;')
)

CAMERA = '''<gazebo reference="body"><sensor type="camera" name="huge_camera">
  <update_rate>30.0</update_rate>
  <camera name="head"><horizontal_fov>1.4</horizontal_fov>
    <image><width>6000</width><height>6000</height><format>R8G8B8</format></image>
    <clip><near>0.02</near><far>300</far></clip></camera>
  <plugin name="camera_controller" filename="libgazebo_ros_camera.so">
    <cameraName>huge_camera</cameraName><imageTopicName>image_raw</imageTopicName>
    <cameraInfoTopicName>camera_info</cameraInfoTopicName><frameName>body</frameName>
  </plugin></sensor></gazebo>'''


class Security(WorldTestCase):
    NODE = 'test_security'
    RECORD = ('clock', 'rosout')
    SERVICES = ('/gazebo/spawn_urdf_model',)
    FIRST = ('clock',)

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.spawn_srv = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
        cls.delete_srv = rospy.ServiceProxy('/gazebo/delete_model', DeleteModel)
        cls.world_cwd = os.readlink('/proc/%d/cwd' % node_pid('/gazebo'))

    def spawn(self, name, xml):
        return self.spawn_srv(name, xml, '', None, '')

    def refused(self, name, xml, *words, within=None):
        """Spawn; assert it fails with every one of ``words`` in the reply; return the reply."""
        start = time.monotonic()
        resp = self.spawn(name, xml)
        took = time.monotonic() - start
        self.assertFalse(resp.success, 'spawned %r: %s' % (name[:80], resp.status_message))
        for w in words:
            self.assertIn(w, resp.status_message)
        if within is not None:
            self.assertLess(took, within, 'refusal took %.1f s' % took)
        self.assertNotIn('Traceback', resp.status_message)
        return resp.status_message

    def logged_since(self, mark):
        return ' '.join(m.msg for m in self.rosout.since(mark))

    def written(self, marker, *places):
        """Files named with ``marker`` wherever the world might have joined a name onto a folder."""
        cwd = self.world_cwd
        places = set(places) | {
            '/',
            '/tmp',
            tempfile.gettempdir(),
            cwd,
            os.path.dirname(cwd),
            os.path.dirname(os.path.dirname(cwd)),
        }
        return [
            os.path.join(p, f)
            for p in places
            if os.path.isdir(p)
            for f in os.listdir(p)
            if marker in f
        ]

    # -- names ---------------------------------------------------------------------
    def test_01_path_like_model_names_are_refused_and_write_nothing(self):
        marker = 'sec_' + uuid.uuid4().hex[:12]
        outside = tempfile.mkdtemp(prefix='arm1-security-')
        try:
            for name in (
                os.path.join(outside, marker),
                '../../' + marker,
                '..',
                marker + '/x',
                'a\\..\\' + marker,
            ):
                rule = 'is not a name' if name == '..' else 'a name is not a path'
                self.refused(name, box(), 'model name', rule)
            self.assertEqual(self.written(marker, outside), [])
            self.assertEqual(os.listdir(outside), [])
        finally:
            shutil.rmtree(outside, ignore_errors=True)

    def test_02_oversized_model_name_is_refused_by_its_length(self):
        msg = self.refused('n' * 5000, box(), '5000', 'name_length')
        self.assertNotIn('Errno', msg)
        self.assertNotIn('File name too long', msg)
        self.assertLess(len(msg), 1000)  # the name is quoted shortened, not whole

    # -- hostile XML ---------------------------------------------------------------
    def test_03_billion_laughs_is_refused_within_two_seconds(self):
        self.refused('laughs', LAUGHS, 'document type declaration', within=2.0)

    def test_04_external_entity_is_refused_without_reading_it(self):
        mark = time.monotonic()
        xml = '<!DOCTYPE robot [<!ENTITY passwd SYSTEM "file:///etc/passwd">]>' + box(
            'r', extra='<gazebo><comment>&passwd;</comment></gazebo>'
        )
        msg = self.refused('external', xml, 'document type declaration', within=2.0)
        for w in PASSWD_WORDS:
            self.assertNotIn(w, msg + self.logged_since(mark))

    # -- meshes --------------------------------------------------------------------
    def test_05_package_uri_that_climbs_out_is_refused_without_the_files_contents(self):
        mark = time.monotonic()
        for uri, words in (
            ('package://arm1/../../../../etc/passwd', ["leaves package 'arm1'"]),
            ('package://arm1/../../../../etc/passwd.stl', ["leaves package 'arm1'"]),
            ('package://arm1//etc/passwd', ["leaves package 'arm1'"]),
            ('file:///etc/passwd', ['only .stl, .obj, .dae meshes']),
            ('/etc/passwd', ['only .stl, .obj, .dae meshes']),
        ):
            geometry = '<mesh filename="%s"/>' % uri
            msg = self.refused('climber', box(geometry=geometry), "link 'body'", uri, *words)
        time.sleep(0.5)  # let /rosout catch up
        for w in PASSWD_WORDS:
            self.assertNotIn(w, msg + self.logged_since(mark))

    # -- sensors -------------------------------------------------------------------
    def test_06_oversized_camera_is_refused_naming_camera_pixels(self):
        name = 'big_eye_' + uuid.uuid4().hex[:12]
        self.refused(name, box(name, extra=CAMERA), '36000000', '~limits/camera_pixels', within=5.0)
        self.assertFalse(self.delete_srv(name).success)  # nothing was left behind
        self.assertEqual(self.written(name), [])

    # -- floods --------------------------------------------------------------------
    def test_07_flood_of_spawns_is_answered_and_the_world_keeps_stepping(self):
        requests = []
        for i in range(200):
            kind = ('valid', 'valid', 'path', 'laughs')[i % 4]
            if kind == 'valid':
                requests.append((kind, 'flood_%d' % i, box('flood_%d' % i)))
            elif kind == 'path':
                requests.append((kind, 'flood/%d' % i, box()))
            else:
                requests.append((kind, 'laughs_%d' % i, LAUGHS))
        replies, errors = {}, []

        def worker(part):
            proxy = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
            for kind, name, xml in part:
                try:
                    resp = proxy(name, xml, '', None, '')
                    replies[name] = (kind, resp.success, resp.status_message)
                except Exception as exc:  # an unanswered call is the failure looked for
                    errors.append('%s: %r' % (name, exc))

        start = time.monotonic()
        threads = [threading.Thread(target=worker, args=(requests[t::8],)) for t in range(8)]
        for t in threads:
            t.start()
        for t in threads:
            t.join(180)
        self.assertEqual(errors, [])
        self.assertEqual(len(replies), 200, 'only %d of 200 calls answered' % len(replies))
        spawned = [n for n, (kind, ok, _) in replies.items() if ok]
        self.assertTrue(all(replies[n][0] == 'valid' for n in spawned), spawned)
        self.assertEqual(len(spawned), MODELS_LIMIT)  # the world file's limit, exactly
        over = [m for kind, ok, m in replies.values() if kind == 'valid' and not ok]
        self.assertEqual(len(over), 100 - MODELS_LIMIT)
        self.assertTrue(
            all(
                'models is %d, over the limit of %d' % (MODELS_LIMIT + 1, MODELS_LIMIT) in m
                and '~limits/models' in m
                for m in over
            ),
            over[:3],
        )
        for kind, ok, m in replies.values():
            if kind == 'path':
                self.assertIn('not a path', m)
            elif kind == 'laughs':  # the models limit is checked first, once reached
                self.assertTrue('document type declaration' in m or '~limits/models' in m, m)
        rospy.loginfo('flood: 200 spawn calls answered in %.1f s', time.monotonic() - start)
        # the world still steps, and frees what it held
        before = self.clock.last().clock
        self.assertTrue(wait_for(lambda: (self.clock.last().clock - before).to_sec() > 0.5, 10))
        self.assertTrue(all(self.delete_srv(n).success for n in spawned))
        self.assertTrue(self.spawn('after_flood', box('after_flood')).success)
        self.assertTrue(self.delete_srv('after_flood').success)

    # -- the pace, over all of the above ---------------------------------------------
    def test_99_clock_kept_real_time_throughout(self):
        # the cases above take a few seconds: measure over at least 10 s of wall time
        first = self.clock.msgs[0][0]
        time.sleep(max(0.0, first + 10.0 - time.monotonic()))
        with self.clock.lock:
            msgs = list(self.clock.msgs)
        (w0, c0), (w1, c1) = msgs[0], msgs[-1]
        wall = w1 - w0
        self.assertGreater(wall, 5.0)
        rtf = (c1.clock - c0.clock).to_sec() / wall
        gaps = max(b[0] - a[0] for a, b in zip(msgs, msgs[1:]))
        base = ClockPace(self.clock).baseline(5.0)
        rospy.loginfo(
            'security: RTF %.3f over %.1f s of wall time (%.3f after), longest /clock gap %.2f s',
            rtf,
            wall,
            base,
            gaps,
        )
        self.assertGreaterEqual(
            rtf, MIN_RTF_RATIO * base, 'RTF %.3f over %.1f s, %.3f after' % (rtf, wall, base)
        )
        self.assertLess(gaps, 1.0, 'the world stopped for %.2f s' % gaps)


if __name__ == '__main__':
    rostest.rosrun('arm1', 'test_security', Security)
