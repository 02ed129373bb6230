"""A collision's contact surface as Gazebo/ODE reads and combines it: SDF ``<surface>`` and the
URDF ``<gazebo reference>`` tags that sdformat's URDF reader turns into one.

ROS-free and pybullet-free. Defaults are SDFormat's (surface.sdf): ``mu`` and ``mu2`` 1,
``kp`` 1e12, ``kd`` 1, ``max_vel`` 0.01, ``min_depth`` 0, bounce 0. sdformat's URDF reader
writes a ``<surface>`` value only for a tag the ``<gazebo reference>`` gives, so an untagged
URDF link has the same defaults. Two surfaces in contact are combined per contact as Gazebo's
ODEPhysics::Collide does (``combine``): the smaller ``mu`` and ``mu2``, the smaller bounce,
``kp`` as two springs in series, ``kd`` summed.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass, replace
from typing import Dict, List, Optional, Tuple

MU_DEFAULT = 1.0  # <friction><ode><mu> and <mu2>
KP_DEFAULT = 1e12  # <contact><ode><kp>
KD_DEFAULT = 1.0  # <contact><ode><kd>
RESTITUTION_DEFAULT = 0.0  # <bounce><restitution_coefficient>

# SDF <surface> paths -> the <gazebo reference> tag sdformat's URDF reader maps onto them.
# (Bounce has no URDF tag in sdformat; the SDF->URDF path of this package writes it under
# SDF's own element name, which gazebo_tags reads.)
SDF_TO_TAG = {
    'friction/ode/mu': 'mu1',
    'friction/ode/mu2': 'mu2',
    'friction/ode/fdir1': 'fdir1',
    'contact/ode/kp': 'kp',
    'contact/ode/kd': 'kd',
    'contact/ode/min_depth': 'minDepth',
    'contact/ode/max_vel': 'maxVel',
    'bounce/restitution_coefficient': 'restitution_coefficient',
    'bounce/threshold': 'bounce_threshold',
}
# What pybullet has no per-link setting for: said, warned once, not applied.
NOT_APPLIED = {
    'fdir1': 'friction direction (pybullet friction is isotropic)',
    'minDepth': 'ODE contact min depth',
    'maxVel': 'ODE max correcting velocity',
    'bounce_threshold': 'bounce velocity threshold',
}


class SurfaceError(ValueError):
    """A surface value is not a finite number; the message names where."""


@dataclass(frozen=True)
class Surface:
    """What pybullet can apply of one link's surface: friction (isotropic), bounce, and the
    contact spring when one was said (None: pybullet's own contact ERP, see docs)."""

    mu: float = MU_DEFAULT
    mu2: float = MU_DEFAULT
    restitution: float = RESTITUTION_DEFAULT
    kp: Optional[float] = None
    kd: Optional[float] = None

    @property
    def friction(self) -> float:
        """The one coefficient pybullet's isotropic friction takes: ODE's first direction's."""
        return self.mu


def combine(a: Surface, b: Surface) -> Surface:
    """The surface of a contact between ``a`` and ``b``, as Gazebo's ODE contact gets it."""
    kp_a = a.kp if a.kp is not None else KP_DEFAULT
    kp_b = b.kp if b.kp is not None else KP_DEFAULT
    said = a.kp is not None or b.kp is not None or a.kd is not None or b.kd is not None
    return Surface(
        mu=min(a.mu, b.mu),
        mu2=min(a.mu2, b.mu2),
        restitution=min(a.restitution, b.restitution),
        kp=1.0 / (1.0 / kp_a + 1.0 / kp_b) if said else None,
        kd=(a.kd if a.kd is not None else KD_DEFAULT) + (b.kd if b.kd is not None else KD_DEFAULT)
        if said
        else None,
    )


def _number(text: str, where: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value):
        raise SurfaceError('%s: %r is not a finite number' % (where, text))
    return value


def sdf_surface_tags(surface: Optional[ET.Element], where: str) -> Dict[str, str]:
    """The ``<gazebo reference>`` tags (SDF_TO_TAG) an SDF ``<surface>`` says, each checked."""
    tags: Dict[str, str] = {}
    if surface is None:
        return tags
    for path, tag in SDF_TO_TAG.items():
        text = surface.findtext(path)
        if text is None or not text.strip():
            continue
        text = ' '.join(text.split())
        if tag == 'fdir1':
            for v in text.split():
                _number(v, '%s <%s>' % (where, path))
        else:
            _number(text, '%s <%s>' % (where, path))
        tags[tag] = text
    return tags


def surface_from_tags(tags: Dict[str, str], where: str) -> Tuple[Surface, List[str]]:
    """The Surface a link's ``<gazebo reference>`` tags give, over SDF's defaults, and the
    tags said that pybullet cannot apply (NOT_APPLIED, and a mu2 other than mu)."""
    surface = Surface()
    skipped: List[str] = []
    values: Dict[str, float] = {}
    for tag in ('mu1', 'mu2', 'kp', 'kd', 'restitution_coefficient'):
        if tag in tags:
            values[tag] = _number(tags[tag], '%s <%s>' % (where, tag))
            if values[tag] < 0 or (tag == 'kp' and values[tag] == 0):
                raise SurfaceError(
                    '%s <%s>: %s must be %s'
                    % (where, tag, tags[tag], 'positive' if tag == 'kp' else 'at least 0')
                )
    mu1 = values.get('mu1', MU_DEFAULT)
    mu2 = values.get('mu2', MU_DEFAULT)
    surface = replace(surface, mu=mu1, mu2=mu2)
    if 'restitution_coefficient' in values:
        surface = replace(surface, restitution=values['restitution_coefficient'])
    if 'kp' in values or 'kd' in values:
        surface = replace(surface, kp=values.get('kp', KP_DEFAULT), kd=values.get('kd', KD_DEFAULT))
    if mu1 != mu2 and ('mu1' in tags or 'mu2' in tags):
        skipped.append('mu2 (different from mu1: pybullet friction is isotropic, mu1 is used)')
    for tag, why in NOT_APPLIED.items():
        if tag in tags:
            skipped.append('%s (%s)' % (tag, why))
    return surface, skipped
