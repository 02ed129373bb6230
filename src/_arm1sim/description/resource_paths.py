"""Where Gazebo finds world files and ``model://`` models, restated for the stand-in.

Gazebo searches GAZEBO_RESOURCE_PATH for a world name such as ``worlds/empty.world`` and
GAZEBO_MODEL_PATH for ``model://NAME``; gazebo_ros adds every package's
``<export><gazebo_ros gazebo_model_path=... gazebo_media_path=.../></export>``. ROS-free:
the ROS layer passes the package exports in. arm1's own ``gazebo_share`` (standard worlds
and the sun and ground_plane models, written here) comes last, so anybody's own wins.
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from typing import List, Mapping, Optional, Sequence

from ..paths import repo_path

SHARE = repo_path('gazebo_share')


class ResourceNotFound(ValueError):
    """A world or model is on none of the search paths; the message lists the paths tried."""


@dataclass
class PackageExports:
    """What one package's ``<gazebo_ros .../>`` export adds (``${prefix}`` already expanded)."""

    model_paths: List[str] = field(default_factory=list)
    media_paths: List[str] = field(default_factory=list)


@dataclass
class ResourcePaths:
    resource: List[str]  # world files and media, GAZEBO_RESOURCE_PATH order
    model: List[str]  # model://, GAZEBO_MODEL_PATH order

    def find_world(self, name: str, cwd: Optional[str] = None) -> str:
        """The world file ``name`` names: absolute, relative to ``cwd``, or on the resource path."""
        if os.path.isabs(name):
            if os.path.isfile(name):
                return name
            raise ResourceNotFound('world file %s does not exist' % name)
        tried = [os.path.join(cwd or os.getcwd(), name)]
        tried += [os.path.join(base, name) for base in self.resource]
        for path in tried:
            if os.path.isfile(path):
                return path
        raise ResourceNotFound(
            'world %s not found; tried: %s (set GAZEBO_RESOURCE_PATH)' % (name, ', '.join(tried))
        )

    def find_model(self, uri: str) -> str:
        """The SDF file of ``model://NAME``: model.config's <sdf>, else model.sdf."""
        if not uri.startswith('model://'):
            raise ResourceNotFound('%s is not a model:// URI' % uri)
        name = uri[len('model://') :].strip('/')
        if not name or '..' in name.split('/'):
            raise ResourceNotFound('%s names no model' % uri)
        tried = []
        for base in self.model:
            folder = os.path.join(base, name)
            tried.append(folder)
            if os.path.isdir(folder):
                sdf = _model_sdf(folder)
                if sdf:
                    return sdf
        raise ResourceNotFound(
            'model %s not found; tried: %s (set GAZEBO_MODEL_PATH or export gazebo_model_path)'
            % (uri, ', '.join(tried))
        )


def _split(value: str) -> List[str]:
    return [p for p in value.split(':') if p]


def _model_sdf(folder: str) -> Optional[str]:
    config = os.path.join(folder, 'model.config')
    names: List[str] = []
    try:
        root = ET.parse(config).getroot()
        names = [(e.text or '').strip() for e in root.findall('sdf') if (e.text or '').strip()]
    except (OSError, ET.ParseError):
        pass
    for name in names + ['model.sdf']:
        path = os.path.join(folder, name)
        if os.path.isfile(path):
            return path
    return None


def gazebo_paths(
    env: Mapping[str, str], exports: Sequence[PackageExports] = (), share: str = SHARE
) -> ResourcePaths:
    """The search paths Gazebo with gazebo_ros would use under environment ``env``."""
    resource = _split(env.get('GAZEBO_RESOURCE_PATH', ''))
    model = _split(env.get('GAZEBO_MODEL_PATH', ''))
    for e in exports:
        model += [p for p in e.model_paths if p not in model]
        resource += [p for p in e.media_paths if p not in resource]
    if share not in resource:
        resource.append(share)
    models = os.path.join(share, 'models')
    if models not in model:
        model.append(models)
    return ResourcePaths(resource, model)
