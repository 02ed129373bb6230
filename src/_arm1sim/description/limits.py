"""Bounds on what spawned content may cost the world: the stand-in's own guard, not Gazebo's.

ROS 1 lets any client spawn anything. These limits keep one client's model from
stopping everyone's world (a 6000 x 6000 camera, a million links, a huge mesh).
The defaults sit far above what real robots bring; a world file
(``<plugin name="arm1_limits" filename="libarm1_limits.so">``) or the world
node's private parameters (``~limits/<name>``) raise or lower them. A refusal
names the limit, the value that broke it and how to raise it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from typing import Any, Mapping, Optional


class LimitError(ValueError):
    """Spawned content exceeds a limit; the message names limit, value and parameter."""


@dataclass
class Limits:
    camera_pixels: int = 4096 * 4096  # per frame of one camera (16.8 Mpx)
    render_pixels_per_second: float = 250e6  # all cameras together, at their sim-time rates
    sensor_update_rate: float = 1000.0  # Hz of sim time, per sensor
    links_per_model: int = 1000
    joints_per_model: int = 1000
    # visuals and collisions, a sphere, cylinder or capsule counting 20 (urdf_model.shape_units):
    # pybullet builds them in one call on the physics thread, ~50 ms for 2000 boxes or 100
    # cylinders on a busy 2-core machine (10 000 boxes in one link: 2 s, 40 000: 45 s)
    shapes_per_model: int = 2000
    models: int = 1000  # per world
    mesh_bytes: int = 256 * 1024 * 1024  # one mesh file
    mesh_triangles: int = 5_000_000  # one mesh
    # one concave collision mesh made into convex pieces (physics/concave_meshes);
    # a larger one collides as its convex hull
    concave_mesh_triangles: int = 200_000
    rays_per_laser: int = 1_000_000  # samples x vertical samples of one ray sensor
    # rays x update rate of the world's ray sensors, each and all together (rate 0 counted
    # as sensor_update_rate): lasers are cast on the physics thread, ~2 us a ray here
    ray_casts_per_second: float = 2e6
    description_bytes: int = 64 * 1024 * 1024  # one URDF/SDF document from a request
    name_length: int = 255  # characters of a model, link, joint or namespace name

    @classmethod
    def from_mapping(
        cls, values: Mapping[str, Any], source: str, base: Optional[Limits] = None
    ) -> Limits:
        """Limits with ``values`` over ``base`` (or the defaults); unknown names and bad values
        raise, naming ``source``."""
        if not isinstance(values, Mapping):
            raise LimitError(
                '%s: limits must be a mapping of name: value, not %r' % (source, values)
            )
        known = {f.name: f for f in fields(cls)}
        out = replace(base) if base is not None else cls()
        for name, raw in values.items():
            if name not in known:
                raise LimitError(
                    '%s: unknown limit %r; known: %s' % (source, name, ', '.join(sorted(known)))
                )
            kind = int if known[name].type == 'int' else float
            try:
                value = float(raw)
                if kind is int and math.isfinite(value):  # int(inf) would raise OverflowError
                    value = int(value)
            except (TypeError, ValueError):
                raise LimitError('%s: limit %s = %r is not a number' % (source, name, raw))
            if not math.isfinite(value) or value <= 0:
                raise LimitError(
                    '%s: limit %s = %r must be a positive number' % (source, name, raw)
                )
            setattr(out, name, value)
        return out

    def check(self, name: str, value: float, what: str) -> None:
        """Raise LimitError if ``value`` exceeds limit ``name``; ``what`` names the culprit."""
        limit = getattr(self, name)
        if value > limit:
            raise LimitError(
                '%s: %s is %s, over the limit of %s (raise it with the world node parameter '
                '~limits/%s or the world file plugin arm1_limits)'
                % (what, name.replace('_', ' '), _fmt(value), _fmt(limit), name)
            )


def _fmt(value: float) -> str:
    return '%d' % value if float(value).is_integer() else '%g' % value
