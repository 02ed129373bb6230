"""Reads a Gazebo SDF world: physics settings, gravity and its models.

Static models of planes only (ground_plane) become fixed scenery; every other ``<model>``
and ``<include>``d model becomes a URDF (sdf_model) that the simulation spawns at start,
so the model services see it under its SDF name.

Parsed with defusedxml (no DTD, hence no entity expansion; see safe_xml). The
world's limits on spawned content come from the plugin LIMITS_PLUGIN.
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from typing import Callable, Dict, Optional

from . import safe_xml, sdf_model, sdf_to_urdf
from .limits import LimitError, Limits
from .resource_paths import ResourceNotFound
from .surface import Surface, SurfaceError, sdf_surface_tags, surface_from_tags

# model://NAME -> the SDF file (ResourcePaths.find_model); raises ResourceNotFound.
FindModel = Callable[[str], str]

SHAPES = ('plane', 'box', 'sphere', 'cylinder')
# <plugin name="arm1_limits" filename="libarm1_limits.so"><camera_pixels>...</...></plugin>
LIMITS_PLUGIN = 'libarm1_limits.so'


class SdfError(ValueError):
    """The world file is unusable; the message names the file and the culprit."""


@dataclass
class Shape:
    kind: str  # one of SHAPES
    size: tuple  # plane: normal; box: xyz; sphere: (r,); cylinder: (r, length)
    pose: tuple = (0, 0, 0, 0, 0, 0)
    color: tuple = (0.8, 0.8, 0.8, 1.0)


@dataclass
class StaticModel:
    name: str
    pose: tuple
    shapes: list
    surface: Surface = field(default_factory=Surface)  # its first collision's <surface>


@dataclass
class WorldConfig:
    max_step_size: float = 0.001
    real_time_factor: float = 1.0
    real_time_update_rate: float = 1000.0
    gravity: tuple = (0.0, 0.0, -9.8)
    models: list = field(default_factory=list)
    spawns: list = field(default_factory=list)  # sdf_to_urdf.ModelSpawn, spawned at start
    skipped: list = field(default_factory=list)  # (name, why) of what could not be built
    limits: Limits = field(default_factory=Limits)  # what spawned content may cost
    lockstep: bool = False  # gzserver --lockstep: physics waits for every sensor frame


def _numbers(text, n, what):
    try:
        values = tuple(float(v) for v in (text or '').split())
    except ValueError:
        raise SdfError('%s: %r is not %d numbers' % (what, text, n))
    if len(values) != n:
        raise SdfError('%s: %r is not %d numbers' % (what, text, n))
    return values


def _pose(element, what):
    text = element.findtext('pose') if element is not None else None
    return _numbers(text, 6, what + ' <pose>') if text and text.strip() else (0.0,) * 6


def _shape(geometry, what):
    for kind in SHAPES:
        g = geometry.find(kind)
        if g is None:
            continue
        if kind == 'plane':
            return Shape(kind, _numbers(g.findtext('normal') or '0 0 1', 3, what))
        if kind == 'box':
            return Shape(kind, _numbers(g.findtext('size'), 3, what + ' box size'))
        if kind == 'sphere':
            return Shape(kind, _numbers(g.findtext('radius'), 1, what + ' radius'))
        return Shape(
            kind,
            _numbers(g.findtext('radius'), 1, what + ' radius')
            + _numbers(g.findtext('length'), 1, what + ' length'),
        )
    return None


def _scenery(model: ET.Element) -> Optional[StaticModel]:
    """A static model made of planes only (ground_plane): built as fixed scenery, as before."""
    if not _bool(model.findtext('static')):
        return None
    name = model.get('name', '?')
    shapes = []
    for link in model.findall('link'):
        link_pose = _pose(link, 'model %s link' % name)
        for collision in link.findall('collision'):
            geometry = collision.find('geometry')
            if geometry is None or geometry.find('plane') is None:
                return None
            shape = _shape(geometry, 'model %s' % name)
            if shape is None:
                return None
            pose = _pose(collision, 'model %s collision' % name)
            shape.pose = tuple(a + b for a, b in zip(link_pose, pose))  # sums are right for xyz
            shapes.append(shape)
    if not shapes or model.findall('joint'):
        return None
    first = model.find('link/collision')
    where = 'model %s <surface>' % name
    try:
        tags = sdf_surface_tags(first.find('surface') if first is not None else None, where)
        surface, _ = surface_from_tags(tags, where)  # a plane has no direction to apply fdir1 to
    except SurfaceError as exc:
        raise SdfError(str(exc)) from None
    return StaticModel(name, _pose(model, 'model %s' % name), shapes, surface)


def _bool(text: Optional[str]) -> bool:
    return (text or '').strip() in ('1', 'true')


def _model(
    model: ET.Element,
    config: WorldConfig,
    base_dir: Optional[str] = None,
    find_model: Optional[FindModel] = None,
) -> None:
    """Add the model to ``config``: ground planes as scenery, the rest as URDF spawns."""
    name = model.get('name', '?')
    try:
        scenery = _scenery(model)
    except SdfError:
        scenery = None  # sdf_model names the culprit below
    if scenery is not None:
        config.models.append(scenery)
        return
    try:
        parsed = sdf_model.parse_model(model, config.limits, base_dir, _model_dirs(find_model))
        spawn = sdf_to_urdf.model_spawn(parsed)
    except sdf_model.SdfModelError as exc:
        config.skipped.append((name, str(exc)))
        return
    config.spawns.append(spawn)
    config.skipped.extend((name, why) for why in spawn.warnings)


def _model_dirs(find_model: Optional[FindModel]) -> Optional[sdf_model.FindModelDir]:
    """model://NAME/... meshes: the folder of the model NAME the world's search finds."""
    if find_model is None:
        return None

    def find(name: str) -> str:
        try:
            return os.path.dirname(find_model('model://' + name))
        except ResourceNotFound as exc:
            raise LookupError(str(exc)) from None

    return find


def _limits(world: ET.Element, source: str) -> Limits:
    """Limits of the world's arm1_limits plugin over the defaults (the defaults without one)."""
    plugins = [p for p in world.findall('plugin') if p.get('filename') == LIMITS_PLUGIN]
    if len(plugins) > 1:
        raise SdfError('%s: more than one <plugin filename="%s">' % (source, LIMITS_PLUGIN))
    values: Dict[str, str] = {}
    for plugin in plugins:
        for child in plugin:
            if child.tag in values:
                raise SdfError('%s: limit %s is given twice' % (source, child.tag))
            values[child.tag] = (child.text or '').strip()
    try:
        return Limits.from_mapping(values, '%s <plugin %s>' % (source, LIMITS_PLUGIN))
    except LimitError as exc:
        raise SdfError(str(exc)) from None


def parse_world(xml_text, source='world', find_model: Optional[FindModel] = None):
    # The world file is the user's own, so no size limits; but no DTD either (no entities).
    # Blank lines before the <?xml?> declaration are no error to Gazebo (TinyXML skips
    # them; kinova-ros's jaco.world starts with one), so they are none here.
    try:
        root = safe_xml.parse(xml_text.lstrip(), source)
    except safe_xml.XmlRefused as exc:
        raise SdfError(str(exc)) from None
    world = root.find('world') if root.tag == 'sdf' else None
    if world is None:
        raise SdfError('%s has no <sdf><world>' % source)
    config = WorldConfig(limits=_limits(world, source))
    physics = world.find('physics')
    if physics is not None:
        for tag in ('max_step_size', 'real_time_factor', 'real_time_update_rate'):
            text = physics.findtext(tag)
            if text is not None:
                setattr(config, tag, _numbers(text, 1, '%s <physics><%s>' % (source, tag))[0])
    if config.max_step_size <= 0:
        raise SdfError('%s: <max_step_size> must be positive' % source)
    gravity = world.findtext('gravity')
    if gravity is not None:
        config.gravity = _numbers(gravity, 3, source + ' <gravity>')
    base_dir = os.path.dirname(os.path.abspath(source)) if os.path.isfile(source) else None
    for model in world.findall('model'):
        _model(model, config, base_dir, find_model)
    for include in world.findall('include'):
        _include(include, config, find_model)
    return config


def _include(include: ET.Element, config: WorldConfig, find_model: Optional[FindModel]) -> None:
    """Build an <include>d model as Gazebo would: its <name>, <pose>, <static> win."""
    uri = (include.findtext('uri') or '').strip()
    name = (include.findtext('name') or uri).strip()
    if find_model is None:
        config.skipped.append((name, 'included from %s, which this stand-in cannot fetch' % uri))
        return
    try:
        path = find_model(uri)
        with open(path) as f:
            root = safe_xml.parse(f.read().lstrip(), path)
    except ResourceNotFound as exc:
        config.skipped.append((name, str(exc)))
        return
    except OSError as exc:
        config.skipped.append((name, 'cannot read %s: %s' % (uri, exc.strerror)))
        return
    except safe_xml.XmlRefused as exc:
        config.skipped.append((name, str(exc)))
        return
    model = root.find('model') if root.tag == 'sdf' else None
    if model is None:
        return  # a light (model://sun) or other non-model: nothing physical to build
    for tag in ('name', 'pose', 'static'):
        text = include.findtext(tag)
        if text is None:
            continue
        if tag == 'name':
            model.set('name', text.strip())
            continue
        element = model.find(tag)
        if element is None:
            element = ET.SubElement(model, tag)
        element.text = text
    _model(model, config, os.path.dirname(path), find_model)


def read_world(path, find_model: Optional[FindModel] = None):
    try:
        with open(path) as f:
            text = f.read()
    except OSError as exc:
        raise SdfError('cannot read world file %s: %s' % (path, exc.strerror))
    return parse_world(text, path, find_model)
