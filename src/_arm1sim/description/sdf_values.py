"""Values of SDF and plugin elements: numbers, flags and poses, with messages naming where."""

from __future__ import annotations

import math
from typing import Any, Callable, Optional, Tuple

from .urdf_model import UrdfError

Pose = Tuple[float, float, float, float, float, float]  # x y z roll pitch yaw, SDF's order
ZERO_POSE: Pose = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


def number(
    element: Any, path: str, default: float, where: str, kind: Callable[[str], float] = float
) -> float:
    """``element.findtext(path)`` as a finite number, ``default`` when absent or empty."""
    text = element.findtext(path)
    if text is None or not text.strip():
        return default
    try:
        value = kind(text.strip())
    except ValueError:
        raise UrdfError('%s <%s>: %r is not a number' % (where, path, text))
    if not math.isfinite(value):
        raise UrdfError('%s <%s>: %r is not a finite number' % (where, path, text))
    return value


def vector3(text: Optional[str]) -> Optional[Tuple[float, float, float]]:
    """Three finite numbers ``x y z``: zero when the text is absent or empty, None when it is
    not three finite numbers (the caller names the culprit)."""
    if not text:
        return (0.0, 0.0, 0.0)
    try:
        values = [float(v) for v in text.split()]
    except ValueError:
        return None
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        return None
    return (values[0], values[1], values[2])


def flag(element: Any, path: str, default: bool, where: str) -> bool:
    text = element.findtext(path)
    if text is None or not text.strip():
        return default
    value = text.strip().lower()
    if value in ('1', 'true'):
        return True
    if value in ('0', 'false'):
        return False
    raise UrdfError('%s <%s>: %r is not true or false' % (where, path, text))


def pose(element: Any, path: str, where: str) -> Pose:
    """An SDF ``<pose>`` (6 numbers), zero when absent."""
    text = element.findtext(path)
    if text is None or not text.strip():
        return ZERO_POSE
    try:
        values = tuple(float(v) for v in text.split())
    except ValueError:
        values = ()
    if len(values) != 6 or not all(math.isfinite(v) for v in values):
        raise UrdfError('%s <%s>: %r is not 6 numbers' % (where, path, text))
    return values
