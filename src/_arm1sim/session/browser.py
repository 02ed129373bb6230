"""Headless Chromium driven over the Chrome DevTools protocol: the browser view's tests and bench.

Debian's ``chromium`` (APT_PACKAGES) with software WebGL (SwiftShader), a private profile
and a DevTools port on loopback only; Debian's ``python3-websocket`` (APT_PACKAGES) speaks the
protocol. Nothing here serves anything: the page is the world's own.
"""

import base64
import json
import os
import shutil
import subprocess
import tempfile
import time
import urllib.request

CHROMIUM = shutil.which('chromium') or '/usr/bin/chromium'


def _die_with_parent() -> None:
    """In the child: SIGTERM when the process that started it ends (a killed test or bench
    leaves no browser behind; Linux's PR_SET_PDEATHSIG)."""
    import ctypes
    import signal

    try:
        ctypes.CDLL('libc.so.6', use_errno=True).prctl(1, signal.SIGTERM)
    except OSError:
        pass


class Browser:
    """One headless Chromium with one page."""

    def __init__(self, width=960, height=640, timeout=120.0):
        import websocket  # Debian's python3-websocket: the tests run under /usr/bin/python3

        self.profile = tempfile.mkdtemp(prefix='arm1-chromium-')
        self.proc = subprocess.Popen(
            [
                CHROMIUM,
                '--headless=new',
                '--use-angle=swiftshader',
                '--enable-unsafe-swiftshader',
                '--no-sandbox',
                '--no-first-run',
                '--no-default-browser-check',
                '--disable-extensions',
                '--disable-background-networking',
                '--remote-debugging-address=127.0.0.1',
                '--remote-debugging-port=0',
                '--user-data-dir=%s' % self.profile,
                '--window-size=%d,%d' % (width, height),
                'about:blank',
            ],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            preexec_fn=_die_with_parent,
        )
        port_file = os.path.join(self.profile, 'DevToolsActivePort')
        end = time.time() + timeout
        while not os.path.exists(port_file) or not open(port_file).read().strip():
            if time.time() > end or self.proc.poll() is not None:
                self.close()
                raise RuntimeError('chromium did not open its DevTools port')
            time.sleep(0.1)
        port = int(open(port_file).read().split()[0])
        pages: list = []
        while not pages:
            with urllib.request.urlopen('http://127.0.0.1:%d/json' % port) as f:
                pages = [t for t in json.load(f) if t.get('type') == 'page']
            time.sleep(0.1)
        self.ws = websocket.create_connection(pages[0]['webSocketDebuggerUrl'], timeout=timeout)
        self._id = 0
        self.send('Page.enable')
        self.send('Runtime.enable')

    def send(self, method, **params):
        """A DevTools command; its result (events in between are dropped)."""
        self._id += 1
        self.ws.send(json.dumps({'id': self._id, 'method': method, 'params': params}))
        while True:
            msg = json.loads(self.ws.recv())
            if msg.get('id') == self._id:
                if 'error' in msg:
                    raise RuntimeError('%s: %s' % (method, msg['error']))
                return msg.get('result', {})

    def open(self, url):
        self.send('Page.navigate', url=url)

    def js(self, expression):
        """The value of a JavaScript expression in the page (awaited if a promise)."""
        result = self.send(
            'Runtime.evaluate', expression=expression, returnByValue=True, awaitPromise=True
        )
        if 'exceptionDetails' in result:
            raise RuntimeError('javascript: %s' % result['exceptionDetails'])
        return result['result'].get('value')

    def wait_js(self, expression, timeout=30.0):
        end = time.time() + timeout
        while time.time() < end:
            try:
                value = self.js(expression)
            except RuntimeError:  # the page is not there yet (e.g. no document.body)
                value = None
            if value:
                return value
            time.sleep(0.2)
        return None

    def screenshot(self, path=None, clip=None):
        """The page, or its rectangle ``clip`` (x, y, width, height), as PNG bytes (also
        written to ``path``)."""
        params: dict = {'format': 'png'}
        if clip is not None:
            x, y, w, h = clip
            params['clip'] = {'x': x, 'y': y, 'width': w, 'height': h, 'scale': 1}
        data = base64.b64decode(self.send('Page.captureScreenshot', **params)['data'])
        if path:
            with open(path, 'wb') as f:
                f.write(data)
        return data

    def click(self, x, y):
        for kind in ('mousePressed', 'mouseReleased'):
            self.send('Input.dispatchMouseEvent', type=kind, x=x, y=y, button='left', clickCount=1)

    def drag(self, points):
        """A left-button drag through page points (x, y): pressed at the first, moved
        through the others, released at the last."""
        mouse = 'Input.dispatchMouseEvent'
        (x, y), rest = points[0], points[1:]
        self.send(mouse, type='mouseMoved', x=x, y=y)
        self.send(mouse, type='mousePressed', x=x, y=y, button='left', buttons=1, clickCount=1)
        for x, y in rest:
            self.send(mouse, type='mouseMoved', x=x, y=y, button='left', buttons=1)
            time.sleep(0.05)  # a few of the page's frames between two moves, as a hand gives
        self.send(mouse, type='mouseReleased', x=x, y=y, button='left', buttons=0, clickCount=1)

    def key(self, key, code, keycode):
        for kind in ('keyDown', 'keyUp'):
            self.send(
                'Input.dispatchKeyEvent',
                type=kind,
                key=key,
                code=code,
                windowsVirtualKeyCode=keycode,
            )

    def close(self):
        try:
            self.ws.close()
        except Exception:
            pass
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        shutil.rmtree(self.profile, ignore_errors=True)
