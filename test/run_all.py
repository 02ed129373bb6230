"""Every test of the package: ruff and mypy, test/unit and test/integration (pytest), then each
test/*.test (rostest).

Run inside the sourced workspace (``make test`` does). Prints each suite's
outcome as it goes and ends with one line ``N passed, N failed``; exits
non-zero if anything failed, or if a suite ran no test at all.
"""

import glob
import os
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))


def count_junit(path):
    """(passed, failed, names of failed) of one JUnit XML file."""
    passed, failed, names = 0, 0, []
    for case in ET.parse(path).getroot().iter('testcase'):
        if case.find('failure') is not None or case.find('error') is not None:
            failed += 1
            names.append('%s.%s' % (case.get('classname', ''), case.get('name')))
        elif case.find('skipped') is None:
            passed += 1
    return passed, failed, names


def run_pytest(out, suite):
    """test/unit (ROS-free) or test/integration (starts its own ROS processes)."""
    xml = os.path.join(out, suite + '.xml')
    cmd = [
        sys.executable,
        '-m',
        'pytest',
        '-q',
        '-p',
        'no:cacheprovider',
        '--junitxml',
        xml,
        os.path.join(HERE, suite),
    ]
    rc = subprocess.call(cmd)
    if not os.path.exists(xml):
        return 0, 1, ['%s tests: pytest exited %d without results' % (suite, rc)]
    return count_junit(xml)


def run_rostest(path, out):
    name = os.path.splitext(os.path.basename(path))[0]
    home = os.path.join(out, name)
    env = dict(os.environ, ROS_HOME=home)
    start = time.monotonic()
    proc = subprocess.run(
        ['rostest', 'arm1', os.path.basename(path)],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )
    log = os.path.join(out, name + '.log')
    with open(log, 'w') as f:
        f.write(proc.stdout)
    # rostest writes one rosunit XML per <test> node (the per-method results).
    results = [
        p
        for p in glob.glob(os.path.join(home, 'test_results', 'arm1', '*.xml'))
        if not os.path.basename(p).startswith('rostest-')
    ]
    passed = failed = 0
    names = []
    for r in results:
        p, f, n = count_junit(r)
        passed, failed, names = passed + p, failed + f, names + n
    if proc.returncode != 0 and not failed:
        failed, names = failed + 1, names + ['%s: rostest exited %d' % (name, proc.returncode)]
    if passed + failed == 0:
        failed, names = 1, ['%s: ran no test' % name]
    status = 'ok' if not failed else 'FAILED (log: %s)' % log
    print(
        'rostest %-28s %3d passed, %d failed  %5.1f s  %s'
        % (name, passed, failed, time.monotonic() - start, status),
        flush=True,
    )
    if failed:
        print(proc.stdout[-4000:])
    return passed, failed, names


LINTERS = [  # (name, command): ruff.toml and mypy.ini at the repository root configure them
    ('ruff check', ['-m', 'ruff', 'check', '.']),
    ('ruff format', ['-m', 'ruff', 'format', '--check', '.']),
    ('mypy', ['-m', 'mypy']),
]


def run_lint():
    """Each linter counts as one test: it passes when it finds nothing."""
    root = os.path.dirname(HERE)
    passed, failed, names = 0, 0, []
    for name, args in LINTERS:
        proc = subprocess.run(
            [sys.executable] + args,
            cwd=root,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
        )
        ok = proc.returncode == 0
        print('lint %-12s %s' % (name, 'ok' if ok else 'FAILED'), flush=True)
        if ok:
            passed += 1
        else:
            print(proc.stdout[-6000:])
            failed, names = failed + 1, names + ['lint: %s' % name]
    return passed, failed, names


def main():
    out = tempfile.mkdtemp(prefix='arm1-test-')
    passed, failed, names = run_lint()
    for suite in ('unit', 'integration'):
        p, f, n = run_pytest(out, suite)
        print('%s tests: %d passed, %d failed' % (suite, p, f), flush=True)
        passed, failed, names = passed + p, failed + f, names + n
    for path in sorted(glob.glob(os.path.join(HERE, '*.test'))):
        p, f, n = run_rostest(path, out)
        passed, failed, names = passed + p, failed + f, names + n
    for n in names:
        print('FAILED: %s' % n)
    print('%d passed, %d failed' % (passed, failed))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
