"""Finding ROS packages on the ROS package path: the one lookup every part of arm1 uses."""

from __future__ import annotations

import functools
import os

import rospkg

from ..paths import repo_root


@functools.lru_cache(maxsize=1)
def _rospack() -> rospkg.RosPack:
    return rospkg.RosPack()


def find_package(name: str) -> str:
    """The directory of package ``name`` (what ``rospack find`` prints); LookupError if the
    package path has none. arm1 itself is found in this source tree even outside a workspace."""
    try:
        return _rospack().get_path(name)
    except rospkg.ResourceNotFound:
        if name == 'arm1' and os.path.isfile(os.path.join(repo_root(), 'package.xml')):
            return repo_root()
        raise LookupError(name) from None
