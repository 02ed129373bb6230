"""A throw-away catkin workspace beside arm1 holding a robot repository's packages, unchanged.

ROS-free: finds the catkin packages of one or more checkouts, picks the ones a launch needs
(the launch file's package, then every package of the checkouts it depends on or names with
``$(find ...)``), links them into ``WS/src`` and runs catkin_make with arm1's own workspace
(.ws/devel: arm1 and its gazebo_ros, controller_manager, xacro, ... compat packages) as the
underlay.
"""

import os
import re
import shutil
import subprocess
import time
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Set, Tuple

from _arm1sim.description import safe_xml

ARM1 = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
UNDERLAY = os.path.join(ARM1, '.ws', 'devel', 'setup.bash')
VENV_PYTHON = os.path.join(ARM1, '.ws', 'venv', 'bin', 'python3')

DEPEND_TAGS = ('depend', 'build_depend', 'exec_depend', 'run_depend', 'buildtool_depend')
# $(find pkg), and package://pkg/ (a mesh's package, resolved on the package path by
# Gazebo: stretch_gazebo's URDF takes its meshes from stretch_description, not a dependency)
FIND_RE = re.compile(r'\$\(find\s+([A-Za-z0-9_]+)\)|package://([A-Za-z0-9_]+)/')
# Files whose $(find pkg) a bringup follows: launch files, xacro and URDF, yaml configs.
SCANNED = ('.launch', '.xml', '.xacro', '.urdf', '.yaml', '.world')
SKIP_DIRS = {'.git', 'build', 'devel', 'install', 'node_modules'}
MAX_SCANNED_BYTES = 2_000_000


@dataclass
class Package:
    name: str
    path: str
    depends: List[str] = field(default_factory=list)


@dataclass
class BuildResult:
    ok: bool
    packages: List[str]
    seconds: float
    log: str
    log_tail: str = ''


def find_packages(checkout: str, unignore: Sequence[str] = ()) -> Dict[str, Package]:
    """Every catkin package (a dir with package.xml) under checkout, by name.

    Like catkin: a package's own subdirectories are not searched, nor dirs holding
    CATKIN_IGNORE, except the dirs in unignore (whose CATKIN_IGNORE a vendor's install
    script removes, as Interbotix's does; the ones below them still count).
    """
    found: Dict[str, Package] = {}
    keep = {os.path.realpath(u) for u in unignore}
    for root, dirs, files in os.walk(checkout, followlinks=False):
        if 'CATKIN_IGNORE' in files and os.path.realpath(root) not in keep:
            dirs[:] = []
            continue
        dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS and not d.startswith('.'))
        if 'package.xml' in files:
            dirs[:] = []
            pkg = read_package(root)
            if pkg.name in found:
                raise ValueError(
                    'package %s is twice in %s: %s and %s'
                    % (pkg.name, checkout, found[pkg.name].path, root)
                )
            found[pkg.name] = pkg
    return found


def read_package(path: str) -> Package:
    manifest = os.path.join(path, 'package.xml')
    with open(manifest, 'rb') as f:
        root = safe_xml.parse(f.read(), manifest)
    name = (root.findtext('name') or '').strip()
    if not name:
        raise ValueError('%s has no <name>' % manifest)
    depends = sorted({(e.text or '').strip() for t in DEPEND_TAGS for e in root.iter(t)} - {''})
    return Package(name, path, depends)


def named_packages(pkg: Package) -> List[str]:
    """Packages the package's launch, xacro, URDF and yaml files name with $(find ...) or
    package://."""
    names: Set[str] = set()
    for root, dirs, files in os.walk(pkg.path):
        dirs[:] = [d for d in dirs if d not in SKIP_DIRS and not d.startswith('.')]
        for fname in files:
            if not fname.endswith(SCANNED):
                continue
            path = os.path.join(root, fname)
            try:
                if os.path.getsize(path) > MAX_SCANNED_BYTES:
                    continue
                with open(path, encoding='utf-8', errors='replace') as f:
                    names.update(a or b for a, b in FIND_RE.findall(f.read()))
            except OSError:
                continue
    return sorted(names)


def needed_packages(available: Dict[str, Package], start: str) -> List[Package]:
    """start and, transitively, every package of available it depends on or $(find)s."""
    if start not in available:
        raise ValueError(
            'package %s is not in the checkout(s); they hold: %s'
            % (start, ', '.join(sorted(available)) or 'no catkin package')
        )
    chosen: Dict[str, Package] = {}
    todo = [start]
    while todo:
        name = todo.pop()
        if name in chosen or name not in available:
            continue
        pkg = available[name]
        chosen[name] = pkg
        todo.extend(pkg.depends)
        todo.extend(named_packages(pkg))
    return [chosen[n] for n in sorted(chosen)]


def make_workspace(ws: str, packages: List[Package]) -> None:
    """WS/src with one symlink per package (the checkout itself stays untouched)."""
    src = os.path.join(ws, 'src')
    os.makedirs(src, exist_ok=True)
    for pkg in packages:
        link = os.path.join(src, pkg.name)
        if os.path.lexists(link):
            os.remove(link)
        os.symlink(os.path.abspath(pkg.path), link)


def build(
    ws: str, packages: List[Package], timeout: float = 1200.0, blacklist: Sequence[str] = ()
) -> BuildResult:
    """catkin_make in ws, overlaying arm1's workspace, leaving out the ``blacklist``ed
    packages (CATKIN_BLACKLIST_PACKAGES, always given: CMake caches it); the log goes to
    ws/build.log."""
    make_workspace(ws, packages)
    log = os.path.join(ws, 'build.log')
    script = (
        'set -e; source "$1"; cd "$2"; '
        'catkin_make -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE="$3" '
        '-DCATKIN_ENABLE_TESTING=OFF -DCATKIN_BLACKLIST_PACKAGES="$4" -j2'
    )
    start = time.monotonic()
    with open(log, 'w') as out:
        try:
            rc = subprocess.run(
                ['bash', '-c', script, 'build', UNDERLAY, ws, VENV_PYTHON, ';'.join(blacklist)],
                stdout=out,
                stderr=subprocess.STDOUT,
                timeout=timeout,
            ).returncode
        except subprocess.TimeoutExpired:
            rc = -1
            out.write('\ntry_robot: catkin_make timed out after %.0f s\n' % timeout)
    with open(log, encoding='utf-8', errors='replace') as f:
        tail = ''.join(f.readlines()[-40:])
    ok = rc == 0 and os.path.exists(os.path.join(ws, 'devel', 'setup.bash'))
    return BuildResult(ok, [p.name for p in packages], time.monotonic() - start, log, tail)


# catkin_make's log: the package being configured, and make's failed targets
# (`make[2]: *** [PKG/CMakeFiles/...]`, `make[1]: *** [CMakeFiles/Makefile2:N: PKG/CMakeFiles/...]`)
ADD_SUBDIRECTORY_RE = re.compile(r'^-- ==> add_subdirectory\((.+?)\)\s*$', re.M)
MAKE_FAILED_RE = re.compile(r'\*\*\* \[(?:CMakeFiles/Makefile2:\d+: )?([^/\s\]:]+)/CMakeFiles/')


def blamed_packages(log: str, names: Sequence[str]) -> Dict[str, Dict[str, str]]:
    """The packages a failed catkin_make log blames: {name: {stage, error}}, stage 'cmake'
    (the package configured when CMake first failed) or 'compile' (make's failed targets)."""
    blamed: Dict[str, Dict[str, str]] = {}
    cmake_error = log.find('CMake Error')
    if cmake_error >= 0:
        configured = ADD_SUBDIRECTORY_RE.findall(log[:cmake_error])
        name = os.path.basename(configured[-1]) if configured else ''
        if name in names:
            blamed[name] = {'stage': 'cmake', 'error': _first_line(log, cmake_error)}
        return blamed
    for name in MAKE_FAILED_RE.findall(log):
        if name in names and name not in blamed:
            blamed[name] = {'stage': 'compile', 'error': _first_error(log, name)}
    return blamed


def _first_line(log: str, at: int) -> str:
    """The message of the error starting at ``at``: its line and the next non-empty one."""
    lines = [t.strip() for t in log[at:].splitlines()[:4] if t.strip()]
    return ' '.join(lines[:2])[:300]


def _first_error(log: str, name: str) -> str:
    for line in log.splitlines():
        if ('error:' in line or 'Error' in line) and '/%s/' % name in line:
            return line.strip()[:300]
    return 'make failed on %s' % name


def build_each(
    ws: str, packages: List[Package], timeout: float = 1200.0
) -> Tuple[BuildResult, BuildResult, Dict[str, Dict[str, Any]]]:
    """Build as a user's plain catkin_make would, then, while it fails, again without the
    packages the log blames (CATKIN_BLACKLIST_PACKAGES, as arm1's stand-ins advise), to
    learn package by package what builds unchanged. Returns the first build, the last and
    {package: {built, stage, error}}; the first build's log is kept as ws/build-first.log."""
    names = [p.name for p in packages]
    first = last = build(ws, packages, timeout)
    if not first.ok:
        shutil.copy(first.log, os.path.join(ws, 'build-first.log'))
        first.log = os.path.join(ws, 'build-first.log')
    verdicts: Dict[str, Dict[str, Any]] = {}
    blacklist: List[str] = []
    while not last.ok and len(blacklist) < len(names):
        with open(last.log, encoding='utf-8', errors='replace') as f:
            blamed = blamed_packages(f.read(), [n for n in names if n not in blacklist])
        if not blamed:
            break
        for name, why in blamed.items():
            verdicts[name] = {'built': False, **why}
        blacklist += sorted(blamed)
        if len(blacklist) < len(names):
            last = build(ws, packages, timeout, blacklist)
    for name in names:
        if name not in verdicts:
            verdicts[name] = (
                {'built': last.ok} if last.ok else {'built': False, 'stage': 'not reached'}
            )
    return first, last, verdicts


def workspace_env(ws: Optional[str], packages: List[Package]) -> Dict[str, str]:
    """The environment of the built workspace (its devel/setup.bash sourced over arm1's).

    ws None (the build failed): arm1's workspace with the packages' source dirs put first
    on ROS_PACKAGE_PATH, so launch files and descriptions are still found.
    """
    setup = os.path.join(ws, 'devel', 'setup.bash') if ws else UNDERLAY
    out = subprocess.run(
        ['bash', '-c', 'source "$1" && env -0', 'env', setup],
        check=True,
        stdout=subprocess.PIPE,
    ).stdout.decode('utf-8', 'replace')
    env = dict(item.split('=', 1) for item in out.split('\0') if '=' in item)
    if ws is None:
        dirs = [os.path.abspath(p.path) for p in packages]
        env['ROS_PACKAGE_PATH'] = os.pathsep.join(dirs + [env.get('ROS_PACKAGE_PATH', '')])
    return env


def checkout_info(path: str) -> Dict[str, Any]:
    """Where the packages came from: the checkout's commit, its date, branch, local changes."""

    def git(*args: str) -> str:
        try:
            return (
                subprocess.run(
                    ['git', '-C', path, *args],
                    stdout=subprocess.PIPE,
                    stderr=subprocess.DEVNULL,
                    check=True,
                    timeout=30,
                )
                .stdout.decode('utf-8', 'replace')
                .strip()
            )
        except (subprocess.SubprocessError, OSError):
            return ''

    remote = git('config', '--get', 'remote.origin.url')
    return {
        'path': os.path.abspath(path),
        'commit': git('rev-parse', 'HEAD') or None,
        'commit_date': git('log', '-1', '--format=%cI') or None,
        'branch': git('rev-parse', '--abbrev-ref', 'HEAD') or None,
        'remote': remote or None,
        'local_changes': bool(git('status', '--porcelain', '--untracked-files=no')),
    }
