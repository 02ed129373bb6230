"""Finding ROS packages on the ROS package path: the one lookup every part of arm1 uses."""
from __future__ import annotations

import functools

import rospkg


@functools.lru_cache(maxsize=1)
def _rospack() -> rospkg.RosPack:
    return rospkg.RosPack()


def find_package(name: str) -> str:
    """The directory of package ``name``; LookupError if the package path has none."""
    try:
        return _rospack().get_path(name)
    except rospkg.ResourceNotFound:
        raise LookupError(name) from None
