"""Where this source tree lies: the repository root (package.xml, urdf/, config/, worlds/ ...).

The package is used from its source tree (the devel space imports src/_arm1sim), so the
root is two levels above the package. Looking a package up on the ROS package path is
another matter: see ros/packages.py.
"""

from __future__ import annotations

import os

_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def repo_root() -> str:
    """The repository root: the directory holding src/_arm1sim and package.xml."""
    return _ROOT


def repo_path(*parts: str) -> str:
    """A path under the repository root, e.g. ``repo_path('config', 'controllers.yaml')``."""
    return os.path.join(_ROOT, *parts)
