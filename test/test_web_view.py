#!/usr/bin/env python
"""The browser view (gazebo.launch web:=true) in Debian's headless Chromium, checked as a person
would: the arm drawn where its joint states put it, pause that pauses, a slider that moves a
joint, the camera's image on the page."""

import os
import sys
import time

import rospy
import rostest
from gazebo_msgs.msg import LinkStates
from gazebo_msgs.srv import GetPhysicsProperties, GetWorldProperties

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from camera_util import LOOK, JointCommander  # noqa: E402
from rostest_util import Recorder, WorldTestCase, positions, sim_wait, wait_for  # noqa: E402
from web_util import CAMERA_IMAGE_JS, button, check_arm_drawn, open_page, rect_js  # noqa: E402


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
        cls.browser = open_page(cls.url, 'joint4_position_controller')

    @classmethod
    def tearDownClass(cls):
        cls.browser.close()

    def test_01_the_arm_is_drawn_where_its_joint_states_put_it(self):
        check_arm_drawn(self, self.browser, self.arm, self.links)

    def test_02_pause_button_pauses_the_world(self):
        physics = rospy.ServiceProxy('/gazebo/get_physics_properties', GetPhysicsProperties)
        x, y, w, h = self.browser.js(rect_js(button('Pause')))
        self.browser.click(x + w / 2, y + h / 2)
        self.assertTrue(wait_for(lambda: physics().pause, 20), 'the world is not paused')
        mark = time.monotonic()
        # the world's own time (answered from its physics thread): a /clock sent before the
        # pause may still arrive late on a busy machine, so stamps are judged, not arrivals
        before = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)().sim_time
        time.sleep(2.0)
        late = [c.clock for c in self.clock.since(mark) if c.clock.to_sec() > before + 1e-6]
        self.assertEqual(late, [], '/clock went on while paused')
        shown = self.browser.wait_js("document.body.innerText.includes('paused')", 10)
        self.assertTrue(shown, 'the page does not say paused')
        x, y, w, h = self.browser.wait_js(rect_js(button('Play')), 10)
        self.browser.click(x + w / 2, y + h / 2)
        self.assertTrue(wait_for(lambda: not physics().pause, 20), 'Play did not resume')
        self.assertTrue(wait_for(lambda: self.clock.last().clock.to_sec() > before, 10))

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
        stats = self.browser.wait_js(CAMERA_IMAGE_JS, 60)
        self.assertTrue(stats, 'no 640x480 camera image with anything in it on the page')


if __name__ == '__main__':
    rostest.rosrun('arm1', 'web_view', WebView)
