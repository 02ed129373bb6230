#!/usr/bin/env python
"""The browser view of ``robot_spawn.launch gui:=false web:=true`` in headless Chromium: the
page issue 23 asks for (the arm, its camera image), and the everyday controls driven as a
person would, with the mouse: Step, Reset world, Reset simulation, a click on a model that
shows its name, pose and links, a drag of its handle that moves it, a model that
arrives, leaves and comes back while the page is open, and joint1's slider.

The drag is a real one: DevTools mouse events pressed on the handle's y arrow where the
page's camera draws it, moved along it and released; the world is then asked where the
model is (/gazebo/get_model_state)."""

import os
import re
import sys
import time

import numpy as np
import rospy
import rostest
from gazebo_msgs.msg import LinkStates
from gazebo_msgs.srv import (
    DeleteModel,
    GetModelState,
    GetPhysicsProperties,
    GetWorldProperties,
    SpawnModel,
)
from geometry_msgs.msg import Point, Pose, Quaternion

from _arm1sim.session.web_picture import SOFTWARE_WEBGL, dismiss_notice, notice_js

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from camera_util import LOOK, JointCommander  # noqa: E402
from rostest_util import Recorder, WorldTestCase, positions, wait_for  # noqa: E402
from web_util import (  # noqa: E402
    CAMERA_IMAGE_JS,
    check_arm_shown,
    click_button,
    open_page,
    page_has_js,
    project,
    red_pixels,
    screenshot,
    viewport,
)

BOX = 'web_box'
SIDE = 0.05  # m
BOX_AT = (-0.2, -0.25, SIDE / 2)  # on the ground, left of the arm on the page
RESPAWN_AT = (-0.2, -0.05, SIDE / 2)
HANDLE = 0.3  # m: the drag handle's size (web_view.select)
GRAB = 0.55  # of HANDLE: where on the y arrow the mouse presses (clear of the planes, arcs)
DRAG = 0.1  # m along y
BOX_SDF = (
    '<sdf version="1.6"><model name="%s"><link name="link"><inertial><mass>0.2</mass>'
    '<inertia><ixx>1e-4</ixx><iyy>1e-4</iyy><izz>1e-4</izz></inertia></inertial>'
    '<collision name="c"><geometry><box><size>{s} {s} {s}</size></box></geometry></collision>'
    '<visual name="v"><geometry><box><size>{s} {s} {s}</size></box></geometry><material>'
    '<ambient>1 0 0 1</ambient><diffuse>1 0 0 1</diffuse></material></visual></link></model>'
    '</sdf>'
).format(s=SIDE)
# s of wall time: the longest the page or the world may take to answer on a loaded machine
PAGE = 60
INFO = re.compile(r'position (\S+) (\S+) (\S+) m')


def spawn_box(at):
    spawn = rospy.ServiceProxy('/gazebo/spawn_sdf_model', SpawnModel)
    res = spawn(BOX, BOX_SDF % BOX, '', Pose(Point(*at), Quaternion(0, 0, 0, 1)), 'world')
    assert res.success, res.status_message


class WebViewControls(WorldTestCase):
    NODE = 'test_web_view_controls'
    RECORD = ('states', 'clock')
    FIRST = ('states', 'clock')
    CONTROLLERS = 5
    SERVICES = ('/gazebo/spawn_sdf_model', '/gazebo/delete_model', '/gazebo/get_model_state')

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        assert wait_for(lambda: rospy.has_param('/gazebo/web_url'), 30), 'no ~web_url'
        cls.links = Recorder('/gazebo/link_states', LinkStates)
        cls.arm = JointCommander(cls.states)
        cls.model_state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        cls.world = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)
        cls.physics = rospy.ServiceProxy('/gazebo/get_physics_properties', GetPhysicsProperties)
        cls.browser = open_page(rospy.get_param('/gazebo/web_url'), 'joint4_position_controller')

    @classmethod
    def tearDownClass(cls):
        cls.browser.close()

    # -- helpers -----------------------------------------------------------------------
    def box_at(self):
        p = self.model_state(BOX, 'world').pose.position
        return np.array((p.x, p.y, p.z))

    def shown_at(self, where):
        """Whether the page's model info gives ``where`` (within 2 mm)."""
        found = INFO.search(self.browser.js('document.body.innerText'))
        shown = [float(v) for v in found.groups()] if found else None
        return shown is not None and np.abs(np.array(shown) - where).max() < 0.002

    def pixel(self, point):
        return project([point], *viewport(self.browser))[0]

    def red_near(self, point, name, radius=30):
        """Red pixels within ``radius`` px of where the page draws ``point`` (a screenshot of
        just that square: on a busy machine a whole page's takes seconds)."""
        x, y = self.pixel(point)
        clip = (int(x) - radius, int(y) - radius, 2 * radius, 2 * radius)
        shot = screenshot(self.browser, name, clip)
        return red_pixels(shot, (x - clip[0], y - clip[1]), radius)

    def pause(self):
        click_button(self.browser, 'Pause')
        self.assertTrue(wait_for(lambda: self.physics().pause, PAGE), 'the world is not paused')

    def play(self):
        click_button(self.browser, 'Play')
        self.assertTrue(wait_for(lambda: not self.physics().pause, PAGE), 'Play did not resume')

    # -- the page robot_spawn.launch serves (issue 23's done-when) ----------------------
    def test_01_the_arm_and_its_camera_image(self):
        self.assertTrue(self.arm.go(LOOK, timeout=120), 'the arm did not reach the look pose')
        check_arm_shown(self, self.browser, self.links)
        stats = self.browser.wait_js(CAMERA_IMAGE_JS, 60)
        self.assertTrue(stats, 'no 640x480 camera image with anything in it on the page')

    # -- World buttons -----------------------------------------------------------------
    def test_02_step_advances_one_physics_step(self):
        step = self.physics().time_step
        self.pause()
        before = self.world().sim_time
        time.sleep(0.5)
        self.assertEqual(self.world().sim_time, before, 'the world stepped while paused')
        t = before
        for k in range(3):  # each click one step: no more, no fewer
            click_button(self.browser, 'Step')
            moved = wait_for(lambda: self.world().sim_time != t, PAGE)
            self.assertTrue(moved, 'Step %d did not step the world' % (k + 1))
            time.sleep(0.3)  # a second step would show by now
            now = self.world().sim_time
            self.assertAlmostEqual(now - t, step, delta=1e-9, msg='Step %d' % (k + 1))
            t = now
        self.assertTrue(
            wait_for(lambda: abs(self.clock.last().clock.to_sec() - t) < 1e-6, PAGE),
            '/clock does not say the stepped time',
        )
        shown = self.browser.wait_js(page_has_js('sim time %.3f s' % t), PAGE)
        self.assertTrue(shown, 'the page does not show sim time %.3f s' % t)
        self.assertTrue(self.physics().pause, 'Step unpaused the world')
        self.play()

    # -- selecting and dragging a model ------------------------------------------------
    def test_03_a_click_on_a_model_shows_its_name_pose_and_links(self):
        spawn_box(BOX_AT)  # while the page is open: it arrives
        drawn = wait_for(lambda: self.red_near(BOX_AT, 'box') > 100, PAGE, poll=0.5)
        self.assertTrue(drawn, 'the spawned box is not drawn')
        x, y = self.pixel(BOX_AT)
        self.browser.click(x, y)
        self.assertTrue(
            self.browser.wait_js(page_has_js('links: link'), PAGE), 'no model info on the page'
        )
        self.assertIn(BOX, self.browser.js('document.body.innerText'))
        self.assertTrue(self.shown_at(self.box_at()), 'the page shows another position')

    def test_04_dragging_the_handle_moves_the_model(self):
        start = self.box_at()
        grab, release = (start + (0.0, d, 0.0) for d in (GRAB * HANDLE, GRAB * HANDLE + DRAG))
        a, b = self.pixel(grab), self.pixel(release)
        self.browser.drag([a + (b - a) * k / 3 for k in range(4)])  # pressed, moved, released
        moved = wait_for(lambda: self.box_at()[1] - start[1] > DRAG / 2, PAGE)
        self.assertTrue(moved, 'the box did not move: %s' % self.box_at())
        time.sleep(0.5)
        end = self.box_at()
        self.assertAlmostEqual(end[1] - start[1], DRAG, delta=0.03, msg='dragged %s' % end)
        self.assertAlmostEqual(end[0], start[0], delta=0.01, msg='moved off the y axis')
        self.assertAlmostEqual(end[2], start[2], delta=0.01, msg='moved off the y axis')
        # the page's readout follows the model
        self.assertTrue(wait_for(lambda: self.shown_at(end), PAGE), 'the page shows an old pose')

    def test_05_reset_world_puts_models_back_and_time_goes_on(self):
        self.assertGreater(abs(self.box_at()[1] - BOX_AT[1]), 0.02, 'the box was not moved')
        before = self.world().sim_time
        click_button(self.browser, 'Reset world')
        back = wait_for(lambda: np.abs(self.box_at() - BOX_AT).max() < 0.005, PAGE)
        self.assertTrue(back, 'the box is not back: %s' % self.box_at())
        self.assertGreaterEqual(self.world().sim_time, before, 'Reset world reset time')

    def test_06_reset_simulation_takes_time_back_to_zero(self):
        self.assertTrue(wait_for(lambda: self.world().sim_time > 1.0, 30), 'time stands still')
        self.pause()  # time stays at the reset's, so the page can be read at leisure
        click_button(self.browser, 'Reset simulation')
        self.assertTrue(wait_for(lambda: self.world().sim_time == 0.0, PAGE), 'time is not 0')
        shown = self.browser.wait_js(page_has_js('sim time 0.000 s'), PAGE)
        self.assertTrue(shown, 'the page does not show the reset time')
        np.testing.assert_allclose(self.box_at(), BOX_AT, atol=0.005)
        mark = time.monotonic()
        self.play()
        zeroed = wait_for(lambda: any(c.clock.to_sec() < 0.5 for c in self.clock.since(mark)), PAGE)
        self.assertTrue(zeroed, '/clock does not go on from 0')

    # -- models arriving and leaving -----------------------------------------------------
    def test_07_a_model_leaves_and_comes_back(self):
        self.assertGreater(self.red_near(BOX_AT, 'box_there'), 100, 'the box is not drawn')
        res = rospy.ServiceProxy('/gazebo/delete_model', DeleteModel)(BOX)
        self.assertTrue(res.success, res.status_message)
        gone = wait_for(lambda: self.red_near(BOX_AT, 'box_gone') < 5, PAGE, poll=0.5)
        self.assertTrue(gone, 'the deleted box is still drawn')
        self.assertTrue(
            self.browser.wait_js('!' + page_has_js('links: link'), PAGE),
            'the page still shows the deleted model',
        )
        spawn_box(RESPAWN_AT)

        def drawn_again():  # one screenshot for both places
            shot = screenshot(self.browser, 'box_back')
            old, new = project([BOX_AT, RESPAWN_AT], shot.shape[1], shot.shape[0])
            return red_pixels(shot, new, 30) > 100 and red_pixels(shot, old, 30) < 5

        self.assertTrue(wait_for(drawn_again, PAGE, poll=0.5), 'not drawn where it was spawned')

    # -- a controller's slider (issue 23's done-when, robot_spawn's position controllers) --
    def test_08_a_slider_moves_its_joint(self):
        slider = "document.querySelectorAll('[role=slider]')[0]"  # joint1's
        start = float(self.browser.js(slider + ".getAttribute('aria-valuenow')"))
        self.browser.js(slider + '.focus()')
        for _ in range(10):  # ten steps of 0.01 rad down, as a person's arrow key gives
            self.browser.key('ArrowLeft', 'ArrowLeft', 37)
        target = round(start - 0.1, 2)
        shown = float(self.browser.js(slider + ".getAttribute('aria-valuenow')"))
        self.assertAlmostEqual(shown, target, places=6, msg='the slider did not move')

        def there():
            return abs(positions(self.states.last())['joint1'] - target) < 0.02

        self.assertTrue(wait_for(there, 60), 'joint1 did not follow its slider to %.2f' % target)
        text = self.browser.wait_js(page_has_js('command %.3f' % target), PAGE)
        self.assertTrue(text, 'the page does not show the new command')

    # -- viser's notice over the scene (issue 32; session/web_picture.py closes it) ----------
    def test_09_the_software_webgl_notice_closes_with_a_click(self):
        # Chromium draws WebGL with SwiftShader here: viser names it over the scene
        self.assertIsNotNone(self.browser.js(notice_js(SOFTWARE_WEBGL)), 'no notice shown')
        self.assertTrue(dismiss_notice(self.browser, SOFTWARE_WEBGL), 'the notice stays')
        time.sleep(2.0)
        self.assertFalse(self.browser.js(page_has_js(SOFTWARE_WEBGL)), 'the notice came back')


if __name__ == '__main__':
    rostest.rosrun('arm1', 'web_view_controls', WebViewControls)
