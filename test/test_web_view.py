#!/usr/bin/env python
"""The browser view (gazebo.launch web:=true) in Debian's headless Chromium, checked as a person
would: the arm drawn where its joint states put it, pause that pauses, a slider that moves a
joint, the camera's image on the page."""

import io
import math
import os
import sys
import time

import numpy as np
import rospy
import rostest
from gazebo_msgs.msg import LinkStates
from gazebo_msgs.srv import GetPhysicsProperties
from PIL import Image

from arm1.session.browser import Browser

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from camera_util import LOOK, JointCommander  # noqa: E402
from rostest_util import Recorder, WorldTestCase, positions, sim_wait, wait_for  # noqa: E402

# where the page's camera is (ros/world/web_view.py: INITIAL_*)
CAMERA = np.array((0.3, -0.3, 0.25))
LOOK_AT = np.array((0.0, 0.0, 0.05))
FOV = math.radians(60.0)
POSE_A = (0.0, 0.8, 0.0, 0.0)
POSE_B = (1.2, 0.8, 0.0, 0.0)  # joint1 swings the arm round
SHOTS = os.environ.get('ROS_LOG_DIR', '/tmp')


def project(points, width, height):
    """Pixel (x, y) of world points seen by the page's camera (three.js' perspective)."""
    forward = (LOOK_AT - CAMERA) / np.linalg.norm(LOOK_AT - CAMERA)
    right = np.cross(forward, (0.0, 0.0, 1.0))
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    t = math.tan(FOV / 2)
    out = []
    for p in points:
        d = np.asarray(p) - CAMERA
        z = d @ forward
        x, y = (d @ right) / (z * t * width / height), (d @ up) / (z * t)
        out.append(((x + 1) / 2 * width, (1 - y) / 2 * height))
    return np.array(out)


def rect_js(selector_js):
    """JavaScript giving the client rectangle of the element ``selector_js`` finds."""
    return (
        '(() => { const e = %s; if (!e) return null; const r = e.getBoundingClientRect();'
        ' return [r.left, r.top, r.width, r.height]; })()' % selector_js
    )


def button(text):
    return "[...document.querySelectorAll('button')].find(b => b.innerText.trim() === '%s')" % text


class WebView(WorldTestCase):
    NODE = 'test_web_view'
    RECORD = ('states', 'clock')
    FIRST = ('states', 'clock')
    CONTROLLERS = 5

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        assert wait_for(lambda: rospy.has_param('/gazebo/web_url'), 30), 'no ~web_url'
        cls.url = rospy.get_param('/gazebo/web_url')
        cls.links = Recorder('/gazebo/link_states', LinkStates)
        cls.arm = JointCommander(cls.states)
        cls.browser = Browser()
        try:  # tearDownClass does not run when setUpClass fails: the browser must not outlive it
            cls.browser.open(cls.url)
            page = cls.browser.wait_js(
                "document.body.innerText.includes('joint4_position_controller')", 120
            )
            assert page, 'the page never showed the controllers'
        except BaseException:
            cls.browser.close()
            raise

    @classmethod
    def tearDownClass(cls):
        cls.browser.close()

    def shot(self, name):
        time.sleep(2.0)  # a few frames of the view at the new pose
        data = self.browser.screenshot(os.path.join(SHOTS, 'web_view_%s.png' % name))
        return np.asarray(Image.open(io.BytesIO(data)).convert('RGB')).astype(int)

    def link_positions(self):
        msg = self.links.last()
        return {
            n.split('::')[-1]: (p.position.x, p.position.y, p.position.z)
            for n, p in zip(msg.name, msg.pose)
        }

    def test_01_the_arm_is_drawn_where_its_joint_states_put_it(self):
        self.assertTrue(self.arm.go(POSE_A, timeout=120), 'the arm did not reach pose A')
        a = self.shot('a')
        tip_a = self.link_positions()['link4']
        self.assertTrue(self.arm.go(POSE_B, timeout=120), 'the arm did not reach pose B')
        b = self.shot('b')
        tip_b = self.link_positions()['link4']
        panel = self.browser.js(rect_js(button('Pause')))
        height, width = a.shape[:2]
        scene = slice(0, height), slice(0, int(panel[0]) - 30)  # left of the control panel
        moved = np.abs(a - b).max(axis=2) > 40
        moved[:, scene[1].stop :] = False
        ys, xs = np.nonzero(moved)
        self.assertGreater(len(xs), 200, 'nothing on the page moved with the arm')
        # every changed pixel lies near the arm's two poses as the joint states place them
        (ax, ay), (bx, by) = project([tip_a, tip_b], width, height)
        base = project([(0.0, 0.0, 0.0)], width, height)[0]
        margin = height / 4  # the links' own size on the page
        left, right = min(ax, bx, base[0]) - margin, max(ax, bx, base[0]) + margin
        top, bottom = min(ay, by, base[1]) - margin, max(ay, by, base[1]) + margin
        inside = (xs >= left) & (xs <= right) & (ys >= top) & (ys <= bottom)
        self.assertGreater(inside.mean(), 0.95, 'pixels changed away from the arm')
        # and the tip is drawn at pose B: changed pixels close to where it projects
        near_b = np.hypot(xs - bx, ys - by) < height / 10
        self.assertGreater(near_b.sum(), 20, 'no change where the tip now is (%d, %d)' % (bx, by))

    def test_02_pause_button_pauses_the_world(self):
        physics = rospy.ServiceProxy('/gazebo/get_physics_properties', GetPhysicsProperties)
        x, y, w, h = self.browser.js(rect_js(button('Pause')))
        self.browser.click(x + w / 2, y + h / 2)
        self.assertTrue(wait_for(lambda: physics().pause, 20), 'the world is not paused')
        time.sleep(0.5)
        before = self.clock.last().clock
        time.sleep(1.5)
        self.assertEqual(self.clock.last().clock, before, '/clock went on while paused')
        shown = self.browser.wait_js("document.body.innerText.includes('paused')", 10)
        self.assertTrue(shown, 'the page does not say paused')
        x, y, w, h = self.browser.wait_js(rect_js(button('Play')), 10)
        self.browser.click(x + w / 2, y + h / 2)
        self.assertTrue(wait_for(lambda: not physics().pause, 20), 'Play did not resume')
        self.assertTrue(wait_for(lambda: self.clock.last().clock > before, 10))

    def test_03_a_slider_moves_its_joint(self):
        # joint1's slider (the first): Home puts it at its minimum, the joint's lower limit
        self.browser.js("document.querySelectorAll('[role=slider]')[0].focus()")
        self.browser.key('Home', 'Home', 36)

        def at_minimum():
            msg = self.states.last()
            return abs(positions(msg)['joint1'] + 1.57) < 0.05

        self.assertTrue(wait_for(at_minimum, 60), 'joint1 did not follow its slider')
        sim_wait(0.5)
        text = self.browser.wait_js("document.body.innerText.includes('command -1.570')", 10)
        self.assertTrue(text, 'the page does not show the new command')

    def test_04_the_camera_image_is_shown(self):
        # look_away's pose: the camera sees the horizon (straight up it sees a white sky)
        self.assertTrue(self.arm.go(LOOK, timeout=120), 'the arm did not reach the look pose')
        stats = self.browser.wait_js(
            "(async () => { const i = [...document.querySelectorAll('img')]"
            ".find(i => i.naturalWidth === 640 && i.naturalHeight === 480);"
            " if (!i) return null; const c = document.createElement('canvas');"
            " c.width = 640; c.height = 480; const g = c.getContext('2d'); g.drawImage(i, 0, 0);"
            " const d = g.getImageData(0, 0, 640, 480).data; let s = 0, s2 = 0;"
            " for (let k = 0; k < d.length; k += 4) { s += d[k + 1]; s2 += d[k + 1] * d[k + 1]; }"
            " const n = d.length / 4, m = s / n, sd = Math.sqrt(s2 / n - m * m);"
            " return sd > 5 ? [m, sd] : null; })()",
            60,
        )
        self.assertTrue(stats, 'no 640x480 camera image with anything in it on the page')


if __name__ == '__main__':
    rostest.rosrun('arm1', 'web_view', WebView)
