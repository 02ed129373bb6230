"""A spawned URDF made ready for pybullet as Gazebo's URDF-to-SDF conversion makes it ready
for ODE: fixed joints lumped (lumping), and the per-link ``<gazebo reference>`` physics tags
turned into what World.load_robot applies (BodyOptions).

Per-link tags, as sdformat reads them into every collision of the link:
``mu1``/``mu2`` -> pybullet's lateral friction (isotropic: mu1; a different mu2 is warned),
``kp``/``kd`` -> contact stiffness/damping (SDF's defaults 1e12 and 1 fill in the other),
``selfCollide`` -> self-collision of that link with the model's other links (a pair collides
when either link says so, never across a joint), ``turnGravityOff`` or ``<gravity>false`` ->
the link's weight cancelled each step. ``maxVel``, ``minDepth``, ``fdir1``, ``dampingFactor``
and the ODE joint tags have no pybullet counterpart: each is named once in a warning at
spawn. A lumped link's tags move to the link it was merged into; that link's own win.

Joint ``<dynamics damping friction>`` need nothing here: pybullet reads both from the URDF,
applies damping as a viscous joint torque as Gazebo does, and Robot turns friction into the
joint's velocity motor at rest with that force (Gazebo's fmax with vel 0).
"""

from __future__ import annotations

import logging
import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from typing import Dict, List, Tuple

from .lumping import TRUE_WORDS, Lumped, Pose, lump_fixed_joints, warn_moving_massless
from .urdf_model import RobotModel, UrdfError

log = logging.getLogger('arm1.description')

KP_DEFAULT = 1e12  # SDF <surface><contact><ode><kp>
KD_DEFAULT = 1.0  # SDF <surface><contact><ode><kd>

# Tags Gazebo reads that pybullet has no per-link or per-joint setting for.
UNSUPPORTED = {
    'maxVel': 'ODE max correcting velocity',
    'minDepth': 'ODE contact min depth',
    'fdir1': 'friction direction (pybullet friction is isotropic)',
    'dampingFactor': 'link velocity decay',
    'stopCfm': 'joint limit cfm',
    'stopErp': 'joint limit erp',
    'fudgeFactor': 'joint fudge factor',
    'implicitSpringDamper': 'implicit spring damper',
    'cfmDamping': 'implicit spring damper',
    'springStiffness': 'joint spring',
    'springReference': 'joint spring',
}


@dataclass
class BodyOptions:
    """What a robot needs beyond its URDF file at load (pickled to the render processes)."""

    # lumped link -> (link it lives on, pose of its frame in that link's frame)
    frames: Dict[str, Tuple[str, Pose]] = field(default_factory=dict)
    # link -> pybullet changeDynamics keyword arguments
    dynamics: Dict[str, Dict[str, float]] = field(default_factory=dict)
    self_collide: List[str] = field(default_factory=list)  # links with selfCollide true
    no_gravity: List[str] = field(default_factory=list)  # links whose weight is cancelled


def _number(text: str, where: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value):
        raise UrdfError('%s: %r is not a finite number' % (where, text))
    return value


def effective_tags(refs: Dict[str, Dict[str, str]], lumped: Lumped, link: str) -> Dict[str, str]:
    """The link's own tags, completed by those of the links merged into it."""
    tags = dict(refs.get(link, {}))
    for name in lumped.merged_into(link):
        for tag, text in refs.get(name, {}).items():
            tags.setdefault(tag, text)
    return tags


def link_options(
    refs: Dict[str, Dict[str, str]], lumped: Lumped, links: List[str], model: str
) -> BodyOptions:
    """BodyOptions of the links left after lumping; warns once about unsupported tags."""
    options = BodyOptions(frames=dict(lumped.frames))
    unsupported: Dict[str, List[str]] = {}
    # Numbers checked under the reference the user wrote: a lumped link's tags move on to the
    # link it was merged into, whose name would not lead them to the bad one.
    for name, tags in refs.items():
        if name in lumped.frames:
            for tag in ('mu1', 'mu2', 'kp', 'kd'):
                if tag in tags:
                    _number(tags[tag], "<gazebo reference='%s'> <%s>" % (name, tag))
    for link in links:
        tags = effective_tags(refs, lumped, link)
        where = "<gazebo reference='%s'>" % link
        dyn: Dict[str, float] = {}
        mu1, mu2 = tags.get('mu1'), tags.get('mu2')
        if mu1 is not None or mu2 is not None:
            mu = _number(mu1 if mu1 is not None else mu2 or '', where + ' mu1/mu2')
            dyn['lateralFriction'] = abs(mu)
            if mu1 is not None and mu2 is not None and _number(mu2, where + ' <mu2>') != mu:
                unsupported.setdefault('mu2 (different from mu1)', []).append(link)
        if 'kp' in tags or 'kd' in tags:
            kp = _number(tags['kp'], where + ' <kp>') if 'kp' in tags else KP_DEFAULT
            kd = _number(tags['kd'], where + ' <kd>') if 'kd' in tags else KD_DEFAULT
            dyn['contactStiffness'], dyn['contactDamping'] = kp, kd
        if dyn:
            options.dynamics[link] = dyn
        if tags.get('selfCollide', '').strip().lower() in TRUE_WORDS:
            options.self_collide.append(link)
        if _gravity_off(tags):
            options.no_gravity.append(link)
        for tag in tags:
            if tag in UNSUPPORTED:
                unsupported.setdefault('%s (%s)' % (tag, UNSUPPORTED[tag]), []).append(link)
    # Joint tags (a reference may name a joint) that pybullet cannot honour.
    for name, tags in refs.items():
        if name in links or name in lumped.frames:
            continue
        for tag in tags:
            if tag in UNSUPPORTED:
                unsupported.setdefault('%s (%s)' % (tag, UNSUPPORTED[tag]), []).append(name)
    for what, names in unsupported.items():
        log.warning(
            "model '%s': <gazebo> tag %s of %s is not applied: pybullet has no such setting",
            model,
            what,
            ', '.join(sorted(set(names))),
        )
    return options


def _gravity_off(tags: Dict[str, str]) -> bool:
    """``turnGravityOff`` true (sdformat: anything but false/no/0) or ``<gravity>`` false."""
    off = tags.get('turnGravityOff')
    if off is not None and off.strip().lower() not in ('false', 'no', '0'):
        return True
    gravity = tags.get('gravity')
    return gravity is not None and gravity.strip().lower() in ('false', '0')


def prepare_body(urdf_text: str, description: RobotModel, model: str) -> Tuple[str, BodyOptions]:
    """The URDF pybullet loads (fixed joints lumped, frames weightless) and its BodyOptions.

    ``urdf_text`` was already parsed once safely (our own serialisation of the request);
    raises UrdfError naming the culprit.
    """
    root = ET.fromstring(urdf_text)
    try:
        lumped = lump_fixed_joints(root, description.gazebo_refs)
    except ValueError as exc:
        raise UrdfError(str(exc)) from None
    warn_moving_massless(lumped, model)
    links = [link.get('name', '') for link in root.findall('link')]
    options = link_options(description.gazebo_refs, lumped, links, model)
    short = max(len(line) for line in urdf_text.splitlines() or ['']) <= PYBULLET_LINE
    if short and not (lumped.frames or lumped.weightless):
        return urdf_text, options
    _break_lines(root)
    return ET.tostring(root, encoding='unicode'), options


# Longest line handed to pybullet as it is (lines of ~18 kB were seen to load, ~20 kB not).
PYBULLET_LINE = 4096


def _break_lines(root: ET.Element) -> None:
    """One element per line: pybullet reads a URDF file in fixed-size line chunks, and a line
    longer than that (a URDF on one line, e.g. an SDF model converted here) loses a piece
    mid-attribute: "Cannot load URDF file" or a silently changed value."""
    for element in root.iter():
        if len(element) and not (element.text or '').strip():
            element.text = '\n'
        if not (element.tail or '').strip():
            element.tail = '\n'
