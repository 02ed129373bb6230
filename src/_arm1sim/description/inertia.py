"""CAD inertias that pybullet would zero, corrected by the least change it accepts.

pybullet's URDF importer (BulletUrdfImporter::getMassAndInertia2) takes a link's principal
moments (the tensor's diagonal, or its eigenvalues by Jacobi rotations when it has products)
and, when one is negative or larger than the sum of the other two (the triangle inequality
every rigid body's moments obey), prints "Bad inertia tensor properties, setting inertia to
zero" and gives the link no inertia at all: it then flails. CAD exports break the
inequality by rounding (a thin SolidWorks finger: izz 5.58e-6 > ixx + iyy 2.59e-6). Gazebo
takes such a tensor as it is: sdformat's URDF conversion copies it, Gazebo's ODELink hands it
to dMassSetParameters, and ODE's dBodySetMass only inverts it (positive definite is all it
needs).

Here such a tensor keeps its principal axes; its moments move by the least (Euclidean) change
onto pybullet's accepted set: negative ones to zero, then, if the largest is still more than
the sum of the others, the orthogonal projection onto "largest = sum of the others", pulled
2 x MARGIN inside so that pybullet's own approximate eigenvalues see it accepted. One warning per
link names both tensors. No ROS, no pybullet.
"""

from __future__ import annotations

import logging
import xml.etree.ElementTree as ET
from typing import List, Optional, Sequence, Tuple

import numpy as np

log = logging.getLogger('_arm1sim.description')

KEYS = ('ixx', 'iyy', 'izz', 'ixy', 'ixz', 'iyz')
# Relative to the moments' sum: pybullet's Jacobi stops at off-diagonals of 1e-6 of the
# trace, so its eigenvalues may differ from the exact ones by about that much.
MARGIN = 1e-6

Tensor = Tuple[float, float, float, float, float, float]  # ixx, iyy, izz, ixy, ixz, iyz


def _matrix(t: Tensor) -> np.ndarray:
    ixx, iyy, izz, ixy, ixz, iyz = t
    return np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]], dtype=float)


def principal_moments(t: Tensor) -> Sequence[float]:
    """As pybullet takes them: the diagonal when there are no products, else eigenvalues."""
    if t[3] == 0 and t[4] == 0 and t[5] == 0:
        return t[:3]
    return [float(v) for v in np.linalg.eigvalsh(_matrix(t))]


def accepted(moments: Sequence[float], slack: float = 0.0) -> bool:
    """pybullet's test: every moment >= 0 and none more than the other two together (less
    ``slack``)."""
    a, b, c = moments  # pybullet's comparisons, in its order of operations
    return min(a, b, c) >= 0 and a <= b + c - slack and b <= a + c - slack and c <= a + b - slack


def least_change(moments: Sequence[float]) -> List[float]:
    """The accepted moments nearest to ``moments`` (Euclidean), 2 x MARGIN inside the boundary."""
    m = [max(0.0, float(v)) for v in moments]
    big = max(range(3), key=lambda k: m[k])
    others = [k for k in range(3) if k != big]
    excess = m[big] - m[others[0]] - m[others[1]]
    if excess > 0:
        # Onto the plane m_big = m_o1 + m_o2 along its normal (1, -1, -1): d = excess / 3.
        d = excess / 3.0
        m[big] -= d
        for k in others:
            m[k] += d
        m[big] -= 2 * MARGIN * sum(m)  # inside the slack corrected() allows
    return m


def corrected(t: Tensor) -> Optional[Tensor]:
    """The tensor with the least change pybullet accepts; None when it accepts ``t``."""
    if t[3] == 0 and t[4] == 0 and t[5] == 0:  # pybullet reads the diagonal as it is
        if accepted(t[:3]):
            return None
        a, b, c = least_change(t[:3])
        return (a, b, c, 0.0, 0.0, 0.0)
    moments = principal_moments(t)
    if accepted(moments, MARGIN * sum(abs(v) for v in moments)):  # its eigenvalues approximate
        return None
    values, axes = np.linalg.eigh(_matrix(t))
    fixed = axes @ np.diag(np.array(least_change(values.tolist()))) @ axes.T
    return (
        float(fixed[0, 0]),
        float(fixed[1, 1]),
        float(fixed[2, 2]),
        float(fixed[0, 1]),
        float(fixed[0, 2]),
        float(fixed[1, 2]),
    )


def _shown(t: Tensor) -> str:
    return ' '.join('%s=%.6g' % (k, v) for k, v in zip(KEYS, t))


def correct_inertias(root: ET.Element, model: str) -> List[str]:
    """Rewrite, in place, each link's ``<inertia>`` that pybullet would zero (in its
    ``<inertial>`` frame: a rotation keeps the moments); warn once per link. Returns the
    links corrected. Links whose inertia does not read as numbers are left to parse_urdf."""
    fixed = []
    for link in root.findall('link'):
        inertia = link.find('inertial/inertia')
        if inertia is None:
            continue
        try:
            t: Tensor = tuple(float(inertia.get(k, '0')) for k in KEYS)  # type: ignore[assignment]
        except ValueError:
            continue
        if not all(np.isfinite(t)):
            continue
        new = corrected(t)
        if new is None:
            continue
        name = link.get('name', '')
        for k, v in zip(KEYS, new):
            inertia.set(k, repr(v))
        fixed.append(name)
        log.warning(
            "model '%s' link '%s': inertia %s has principal moments %s, which pybullet would "
            'set to zero (one negative, or one above the sum of the other two; Gazebo/ODE '
            'takes it as it is); using %s (moments %s), the least change pybullet accepts',
            model,
            name,
            _shown(t),
            ' '.join('%.6g' % v for v in sorted(principal_moments(t))),
            _shown(new),
            ' '.join('%.6g' % v for v in sorted(principal_moments(new))),
        )
    return fixed
