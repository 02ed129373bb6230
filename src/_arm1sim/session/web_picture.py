"""Retake docs/images/web-view.png: the browser view of ``robot_spawn.launch gui:=false
web:=true`` in headless Chromium, at real time and as a user sees it.

The picture is taken only once the page's own real-time-factor readout has stayed at 1.00
(within ``--tolerance``) for ``--steady`` seconds, and once viser's "Software WebGL rendering
detected" notice (Chromium draws WebGL with SwiftShader here) is closed with a mouse click on
its close button, as a user would: viser 1.1.1 has no setting or URL parameter that turns the
notice off (client/src/BrowserWarning.tsx shows it whenever the renderer is a software one).
Run ``make web-picture``.
"""

from __future__ import annotations

import argparse
import io
import os
import sys
import time
from typing import List, Optional, Sequence, Tuple

from .browser import Browser

SOFTWARE_WEBGL = 'Software WebGL rendering detected'
PICTURE = os.path.join('docs', 'images', 'web-view.png')

# JavaScript: the page's real-time factor readout (web_view.py: "real-time factor **0.98**")
RTF_JS = (
    "(() => { const m = document.body && document.body.innerText"
    '.match(/real-time factor\\s+([0-9.]+)/); return m ? parseFloat(m[1]) : null; })()'
)


def notice_js(title: str) -> str:
    """JavaScript: the client rectangle of the close button of the Mantine notification
    titled ``title`` (viser's notices); null once ``title`` is nowhere in the page's text,
    [] while it is but no close button is found (a viser whose notices look otherwise)."""
    return (
        '(() => { if (!document.body.innerText.includes(%r)) return null;'
        " const n = [...document.querySelectorAll('[class*=\"Notification-root\"]')]"
        ".find(e => e.innerText.includes(%r)); const b = n && n.querySelector('button');"
        ' if (!b) return []; const r = b.getBoundingClientRect();'
        ' return [r.left, r.top, r.width, r.height]; })()' % (title, title)
    )


def steady_since(readings: Sequence[Tuple[float, Optional[float]]], tolerance: float) -> float:
    """The wall time since which every (time, rtf) reading, up to the last, was within
    ``tolerance`` of 1 (inf if the last one was not)."""
    since = float('inf')
    for t, rtf in reversed(readings):
        if rtf is None or abs(rtf - 1.0) > tolerance:
            break
        since = t
    return since


def dismiss_notice(browser: Browser, title: str, timeout: float = 60.0) -> bool:
    """Close the notice ``title`` with a click on its close button, if it is (or appears
    within a few seconds) on the page; True once it is gone, False if it stays."""
    if not browser.wait_js('%s !== null' % notice_js(title), 10.0):
        return True  # never shown (a GPU renderer) or already gone
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        rect = browser.js(notice_js(title))
        if rect is None:
            return True
        if rect:
            x, y, w, h = rect
            browser.click(x + w / 2, y + h / 2)
        time.sleep(1.0)  # Mantine animates the notice away
    return browser.js(notice_js(title)) is None


def wait_real_time(
    browser: Browser, tolerance: float, steady: float, timeout: float
) -> Tuple[bool, List[Tuple[float, Optional[float]]]]:
    """Read the page's real-time factor twice a second until it has stayed within
    ``tolerance`` of 1 for ``steady`` seconds (True) or ``timeout`` passed (False)."""
    readings: List[Tuple[float, Optional[float]]] = []
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        now = time.monotonic()
        readings.append((now, browser.js(RTF_JS)))
        if now - steady_since(readings, tolerance) >= steady:
            return True, readings
        time.sleep(0.5)
    return False, readings


def optimised_png(data: bytes) -> bytes:
    """The screenshot as a smaller PNG: a 256-colour palette (the page is flat colours and
    grey anti-aliasing; no visible change) with zlib's best compression."""
    from PIL import Image

    image = Image.open(io.BytesIO(data)).convert('RGB')
    out = io.BytesIO()
    image.quantize(256, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE).save(
        out, 'PNG', optimize=True
    )
    return out.getvalue()


def _get_param(session, name: str, timeout: float):
    import rosgraph

    master = rosgraph.Master('/arm1_web_picture', master_uri=session.env['ROS_MASTER_URI'])
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        try:
            return master.getParam(name)
        except Exception:  # no master yet, or no parameter yet
            time.sleep(0.5)
    return None


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--out', default=PICTURE, help='the PNG to write (%(default)s)')
    parser.add_argument('--tolerance', type=float, default=0.02, help='|RTF - 1| allowed')
    parser.add_argument('--steady', type=float, default=10.0, help='s at real time first')
    parser.add_argument('--timeout', type=float, default=300.0, help='s to wait for real time')
    args = parser.parse_args(argv)

    from .launcher import RosSession

    with RosSession() as session:
        print('starting: roslaunch arm1 robot_spawn.launch gui:=false web:=true web_port:=0')
        session.roslaunch('arm1', 'robot_spawn.launch', 'gui:=false', 'web:=true', 'web_port:=0')
        url = _get_param(session, '/gazebo/web_url', 120.0)
        if not url:
            print('FAILED: the world published no /gazebo/web_url within 120 s', file=sys.stderr)
            return 1
        browser = Browser()
        try:
            browser.open(url)
            if browser.wait_js(RTF_JS, 120.0) is None:
                print('FAILED: %s never showed its real-time factor' % url, file=sys.stderr)
                return 1
            if not dismiss_notice(browser, SOFTWARE_WEBGL):
                print('FAILED: the notice %r did not close' % SOFTWARE_WEBGL, file=sys.stderr)
                return 1
            print(
                'waiting for the page to read real time (%.0f s within %.2f of 1)'
                % (args.steady, args.tolerance)
            )
            ok, readings = wait_real_time(browser, args.tolerance, args.steady, args.timeout)
            if ok:
                data = browser.screenshot()
                after = browser.js(RTF_JS)  # the picture lies between this and the last reading
                ok = after is not None and abs(after - 1.0) <= args.tolerance
                readings.append((time.monotonic(), after))
            if not ok:
                seen = [r for _, r in readings[-20:] if r is not None]
                print(
                    'FAILED: the world did not run at real time (the page read %s in the last'
                    ' %d readings, wanted 1.00 +- %.2f for %.0f s within %.0f s); the machine'
                    ' is busy (load average %.1f): retake it when it is quieter'
                    % (
                        ', '.join('%.2f' % r for r in seen[-8:]) or 'nothing',
                        len(seen),
                        args.tolerance,
                        args.steady,
                        args.timeout,
                        os.getloadavg()[0],
                    ),
                    file=sys.stderr,
                )
                return 1
            if browser.js(notice_js(SOFTWARE_WEBGL)) is not None:
                print('FAILED: the notice %r came back' % SOFTWARE_WEBGL, file=sys.stderr)
                return 1
        finally:
            browser.close()
    png = optimised_png(data)
    with open(args.out, 'wb') as f:
        f.write(png)
    print('wrote %s (%d bytes; real-time factor %.2f)' % (args.out, len(png), after))
    return 0


if __name__ == '__main__':
    sys.exit(main())
