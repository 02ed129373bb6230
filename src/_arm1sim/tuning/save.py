"""Found gains into the parameter tree, and the tree into a controllers yaml."""

from __future__ import annotations

import copy
from typing import Any, Dict, Mapping

import yaml

from .steps import Protocol, yaml_pid


def with_gains(
    params: Mapping[str, Any],
    namespace: str,
    controllers: Mapping[str, str],
    gains: Mapping[str, Mapping[str, Any]],
) -> Dict[str, Any]:
    """A copy of the parameter tree with each controller's ``pid`` replaced."""
    out: Dict[str, Any] = copy.deepcopy(dict(params))
    node = out
    for part in [p for p in namespace.split('/') if p]:
        node = node.setdefault(part, {})
    for joint, cname in controllers.items():
        if joint in gains:
            node[cname]['pid'] = yaml_pid(gains[joint])
    return out


def save_params(path: str, params: Mapping[str, Any], protocol: Protocol) -> None:
    """The controllers yaml with found gains, headed by how they were found."""
    with open(path, 'w') as f:
        f.write('# Gains found by `rosrun arm1 tune --search` (%s).\n' % protocol.describe())
        yaml.safe_dump(dict(params), f, default_flow_style=None, sort_keys=False)
