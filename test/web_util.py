"""Helpers of the browser-view rostests: the page in headless Chromium, where the page's camera
draws a world point, its buttons and sliders, and what a screenshot shows."""

import io
import math
import os
import time

import numpy as np
from PIL import Image

from _arm1sim.session.browser import Browser

# where the page's camera is (ros/web/web_view.py: INITIAL_*)
CAMERA = np.array((0.3, -0.3, 0.25))
LOOK_AT = np.array((0.0, 0.0, 0.05))
FOV = math.radians(60.0)
SHOTS = os.environ.get('ROS_LOG_DIR', '/tmp')

# JavaScript: [mean, sd] of the green channel of the page's 640x480 image (the camera's), if
# there is one with anything in it (sd > 5), else null
CAMERA_IMAGE_JS = (
    "(async () => { const i = [...document.querySelectorAll('img')]"
    '.find(i => i.naturalWidth === 640 && i.naturalHeight === 480);'
    " if (!i) return null; const c = document.createElement('canvas');"
    " c.width = 640; c.height = 480; const g = c.getContext('2d'); g.drawImage(i, 0, 0);"
    ' const d = g.getImageData(0, 0, 640, 480).data; let s = 0, s2 = 0;'
    ' for (let k = 0; k < d.length; k += 4) { s += d[k + 1]; s2 += d[k + 1] * d[k + 1]; }'
    ' const n = d.length / 4, m = s / n, sd = Math.sqrt(s2 / n - m * m);'
    ' return sd > 5 ? [m, sd] : null; })()'
)


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


def page_has_js(text):
    return 'document.body.innerText.includes(%r)' % text


def open_page(url, ready_text, timeout=120):
    """A headless Chromium showing ``url`` once the page's text includes ``ready_text``."""
    browser = Browser()
    try:  # a caller's tearDownClass does not run when its setUpClass fails
        browser.open(url)
        assert browser.wait_js(page_has_js(ready_text), timeout), (
            'the page never showed %r' % ready_text
        )
    except BaseException:
        browser.close()
        raise
    return browser


def click_button(browser, text, timeout=60):
    """A mouse click in the middle of the page's button labelled ``text``."""
    rect = browser.wait_js(rect_js(button(text)), timeout)
    assert rect, 'no button %r on the page' % text
    x, y, w, h = rect
    browser.click(x + w / 2, y + h / 2)


def screenshot(browser, name, clip=None):
    """The page (or its rectangle ``clip``) as an RGB array (ints), also written to
    SHOTS/web_view_<name>.png."""
    data = browser.screenshot(os.path.join(SHOTS, 'web_view_%s.png' % name), clip)
    return np.asarray(Image.open(io.BytesIO(data)).convert('RGB')).astype(int)


def viewport(browser):
    """The page's (width, height) in pixels: a screenshot's size."""
    return browser.js('[window.innerWidth, window.innerHeight]')


def wait_drawn(browser, name, timeout=120):
    """The page once its scene is drawn the same twice, half a second apart (software WebGL
    takes seconds to light a new page: a screenshot before then is washed out), as
    ``screenshot`` gives it; None if it never settled."""
    scene = slice(0, scene_right_edge(browser))
    end = time.monotonic() + timeout
    last = screenshot(browser, name)
    while time.monotonic() < end:
        time.sleep(0.5)
        shot = screenshot(browser, name)
        if (np.abs(shot[:, scene] - last[:, scene]).max(axis=2) > 40).sum() < 50:
            return shot
        last = shot
    return None


def scene_right_edge(browser):
    """The page's x left of which the 3D scene is not covered by the control panel."""
    return int(browser.js(rect_js(button('Pause')))[0]) - 30


def assert_arm_drawn(test, a, b, tip_a, tip_b, scene_right):
    """Screenshots ``a`` and ``b`` of the arm at two poses, its tip at ``tip_a``/``tip_b``
    (world, from link states): the pixels that changed lie where the arm is, and some where
    the tip now is."""
    height, width = a.shape[:2]
    moved = np.abs(a - b).max(axis=2) > 40
    moved[:, scene_right:] = False
    ys, xs = np.nonzero(moved)
    test.assertGreater(len(xs), 200, 'nothing on the page moved with the arm')
    # every changed pixel lies near the arm's two poses as the joint states place them
    (ax, ay), (bx, by) = project([tip_a, tip_b], width, height)
    base = project([(0.0, 0.0, 0.0)], width, height)[0]
    margin = height / 4  # the links' own size on the page
    left, right = min(ax, bx, base[0]) - margin, max(ax, bx, base[0]) + margin
    top, bottom = min(ay, by, base[1]) - margin, max(ay, by, base[1]) + margin
    inside = (xs >= left) & (xs <= right) & (ys >= top) & (ys <= bottom)
    test.assertGreater(inside.mean(), 0.95, 'pixels changed away from the arm')
    near_b = np.hypot(xs - bx, ys - by) < height / 10
    test.assertGreater(near_b.sum(), 20, 'no change where the tip now is (%d, %d)' % (bx, by))


def red_pixels(shot, centre, radius):
    """How many clearly red pixels of ``shot`` lie within ``radius`` px of ``centre``."""
    height, width = shot.shape[:2]
    ys, xs = np.mgrid[0:height, 0:width]
    near = np.hypot(xs - centre[0], ys - centre[1]) < radius
    r, g, b = shot[..., 0], shot[..., 1], shot[..., 2]
    red = (r > 120) & (g < 90) & (b < 90)
    return int((red & near).sum())


POSE_A = (0.0, 0.8, 0.0, 0.0)
POSE_B = (1.2, 0.8, 0.0, 0.0)  # joint1 swings the arm round


def link_positions(links):
    """{link: (x, y, z)} of the newest /gazebo/link_states in ``links`` (a Recorder)."""
    msg = links.last()
    return {
        n.split('::')[-1]: (p.position.x, p.position.y, p.position.z)
        for n, p in zip(msg.name, msg.pose)
    }


def check_arm_drawn(test, browser, arm, links, poses=(POSE_A, POSE_B)):
    """Two screenshots with the arm at two poses (``arm``: a camera_util JointCommander,
    ``links``: a /gazebo/link_states Recorder): the pixels that change lie where the arm's link
    states project into the page's camera, and the tip is drawn where its link state puts it."""
    shots, tips = [], []
    for name, pose in zip('ab', poses):
        test.assertTrue(arm.go(pose, timeout=120), 'the arm did not reach pose %s' % name)
        shot = wait_drawn(browser, name)
        test.assertIsNotNone(shot, 'the page never settled at pose %s' % name)
        shots.append(shot)
        tips.append(link_positions(links)['link4'])
    assert_arm_drawn(test, shots[0], shots[1], tips[0], tips[1], scene_right_edge(browser))


ARM_LINKS = ('base_link', 'link1', 'link2', 'link3', 'link4', 'camera_link')
ORANGE_LINKS = ('link1', 'link3')  # arm1.urdf.xacro's material="orange"
# JavaScript: the rectangles of the page's notice that WebGL runs in software (its stripe is
# orange too)
NOTICES_JS = (
    "[...document.querySelectorAll('div')].filter(d => (d.innerText || '')"
    ".startsWith('Software WebGL')).map(d => d.getBoundingClientRect())"
    '.filter(r => r.width < 500).map(r => [r.left, r.top, r.width, r.height])'
)


def orange(shot):
    """Pixels of arm1's orange links (bright, green about half the red, little blue): not
    the grey ground, the white links or a red box's shading."""
    r, g, b = shot[..., 0], shot[..., 1], shot[..., 2]
    return (r > 150) & (r - g > 40) & (g > 0.4 * r) & (b < 0.6 * g)


def check_arm_shown(test, browser, links):
    """One screenshot of the arm at rest (``links``: a /gazebo/link_states Recorder): its
    orange links are drawn, and only where its link states project into the page's camera."""
    shot = wait_drawn(browser, 'arm')
    test.assertIsNotNone(shot, 'the page never settled')
    at = link_positions(links)
    height, width = shot.shape[:2]
    mask = orange(shot)
    mask[:, scene_right_edge(browser) :] = False
    for x, y, w, h in browser.js(NOTICES_JS) or []:
        mask[max(0, int(y) - 4) : int(y + h) + 4, max(0, int(x) - 4) : int(x + w) + 4] = False
    ys, xs = np.nonzero(mask)
    test.assertGreater(len(xs), 200, 'the arm is not drawn (no orange links on the page)')
    shown = [link for link in ARM_LINKS if link in at]
    test.assertIn('link4', shown, 'no link states of the arm')
    drawn = project([at[link] for link in shown], width, height)
    margin = height / 8  # a link's own size on the page
    inside = (
        (xs >= drawn[:, 0].min() - margin)
        & (xs <= drawn[:, 0].max() + margin)
        & (ys >= drawn[:, 1].min() - margin)
        & (ys <= drawn[:, 1].max() + margin)
    )
    test.assertGreater(inside.mean(), 0.95, 'orange drawn away from the arm')
    for link, (x, y) in zip(shown, drawn):
        if link in ORANGE_LINKS:
            near = np.hypot(xs - x, ys - y) < margin
            test.assertGreater(near.sum(), 20, '%s not drawn at (%d, %d)' % (link, x, y))
