"""A spawned URDF made ready for pybullet as Gazebo's URDF-to-SDF conversion makes it ready
for ODE: fixed joints lumped (lumping), and the per-link ``<gazebo reference>`` physics tags
turned into what World.load_robot applies (BodyOptions).

Per-link tags, as sdformat reads them into every collision of the link:
``mu1``/``mu2``/``kp``/``kd`` (and bounce, from an SDF model) -> the link's
surface.Surface, SDF's defaults where a tag is missing (an untagged link has mu 1, as in
Gazebo); the physics layer combines two touching links' friction as ODE does (the smaller).
``selfCollide`` -> self-collision of that link with the model's other links (a pair collides
when either link says so, never across a joint), ``turnGravityOff`` or ``<gravity>false`` ->
the link's weight cancelled each step. ``maxVel``, ``minDepth``, ``fdir1``, a ``mu2`` other
than ``mu1``, ``dampingFactor`` and the ODE joint tags have no pybullet counterpart: each is
named once in a warning at spawn. A lumped link's tags move to the link it was merged into;
that link's own win.

Joint ``<dynamics damping friction>`` need nothing here: pybullet reads both from the URDF,
applies damping as a viscous joint torque as Gazebo does, and Robot turns friction into the
joint's velocity motor at rest with that force (Gazebo's fmax with vel 0).
"""

from __future__ import annotations

import logging
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from typing import Dict, List, Tuple

from . import safe_xml
from .inertia import correct_inertias
from .lumping import TRUE_WORDS, Lumped, Pose, lump_fixed_joints, warn_moving_massless
from .surface import NOT_APPLIED, Surface, SurfaceError, surface_from_tags
from .urdf_model import RobotModel, UrdfError

log = logging.getLogger('_arm1sim.description')

# Tags Gazebo reads that pybullet has no per-link or per-joint setting for (the surface's
# are surface.NOT_APPLIED).
UNSUPPORTED = {
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
    # link -> pybullet changeDynamics keyword arguments (contact stiffness and damping)
    dynamics: Dict[str, Dict[str, float]] = field(default_factory=dict)
    # every link's contact surface (friction and bounce: the world combines pairs as ODE)
    surfaces: Dict[str, Surface] = field(default_factory=dict)
    self_collide: List[str] = field(default_factory=list)  # links with selfCollide true
    no_gravity: List[str] = field(default_factory=list)  # links whose weight is cancelled


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
            _surface(tags, "<gazebo reference='%s'>" % name)
    for link in links:
        tags = effective_tags(refs, lumped, link)
        surface, skipped = _surface(tags, "<gazebo reference='%s'>" % link)
        options.surfaces[link] = surface
        for what in skipped:
            unsupported.setdefault(what, []).append(link)
        if surface.kp is not None and surface.kd is not None:
            options.dynamics[link] = {'contactStiffness': surface.kp, 'contactDamping': surface.kd}
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
            if tag in UNSUPPORTED or tag in NOT_APPLIED:
                why = UNSUPPORTED.get(tag) or NOT_APPLIED[tag]
                unsupported.setdefault('%s (%s)' % (tag, why), []).append(name)
    for what, names in unsupported.items():
        log.warning(
            "model '%s': <gazebo> tag %s of %s is not applied: pybullet has no such setting",
            model,
            what,
            ', '.join(sorted(set(names))),
        )
    return options


def _surface(tags: Dict[str, str], where: str) -> Tuple[Surface, List[str]]:
    try:
        return surface_from_tags(tags, where)
    except SurfaceError as exc:
        raise UrdfError(str(exc)) from None


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
    root = safe_xml.parse_trusted(urdf_text)
    try:
        lumped = lump_fixed_joints(root, description.gazebo_refs)
    except ValueError as exc:
        raise UrdfError(str(exc)) from None
    warn_moving_massless(lumped, model)
    inertias = correct_inertias(root, model)  # after lumping: what pybullet is handed
    links = [link.get('name', '') for link in root.findall('link')]
    options = link_options(description.gazebo_refs, lumped, links, model)
    short = max(len(line) for line in urdf_text.splitlines() or ['']) <= PYBULLET_LINE
    if short and not (lumped.frames or lumped.weightless or inertias):
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
