"""Finding ROS packages on the ROS package path: the one lookup every part of arm1 uses."""

from __future__ import annotations

import functools
import os
from typing import List, Optional

import rospkg

from ...description.resource_paths import PackageExports
from ...paths import repo_root


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


def gazebo_exports(rospack: Optional[rospkg.RosPack] = None) -> List[PackageExports]:
    """Every package's ``<export><gazebo_ros gazebo_model_path=... gazebo_media_path=.../>``,
    the paths gazebo_ros adds to Gazebo's (``${prefix}`` = the package's folder)."""
    rospack = rospack or _rospack()
    found = []
    for name in sorted(rospack.list()):
        try:
            manifest = rospack.get_manifest(name)
            exports = PackageExports(
                manifest.get_export('gazebo_ros', 'gazebo_model_path'),
                manifest.get_export('gazebo_ros', 'gazebo_media_path'),
            )
        except Exception:  # noqa: BLE001  rospkg/catkin_pkg raise several kinds
            continue  # a broken manifest of some other package must not stop the world
        if exports.model_paths or exports.media_paths:
            found.append(exports)
    return found
