"""What ``tune``'s arguments name: the robot description, its parameters, the world, the
step protocol and the criteria."""

from __future__ import annotations

import argparse
import os
from typing import Any, Dict, List, Optional

import yaml

from ..ros.common.packages import find_package
from ..ros.tools import xacro_bridge
from .metrics import Criteria
from .steps import ARM1_POSES, ARM1_START, Protocol, StepRig


def arm1_file(rel: str) -> str:
    """A file of the arm1 package: where ROS finds it, else in this source tree."""
    return os.path.join(find_package('arm1'), rel)


def parse_pose(items: List[str]) -> Dict[str, float]:
    """``['joint2=0.6', 'joint3=0.5']`` -> ``{'joint2': 0.6, 'joint3': 0.5}``."""
    pose = {}
    for item in items:
        joint, sep, value = item.partition('=')
        try:
            pose[joint.strip()] = float(value)
        except ValueError:
            raise SystemExit("tune: a pose is JOINT=RAD, not '%s'" % item) from None
        if not sep or not joint.strip():
            raise SystemExit("tune: a pose is JOINT=RAD, not '%s'" % item)
    return pose


class Setup:
    """The description, parameters, world, protocol and criteria of parsed arguments."""

    def __init__(self, args: argparse.Namespace) -> None:
        self.arm1 = args.urdf is None
        self.urdf_path: str = args.urdf or arm1_file('urdf/arm1.urdf.xacro')
        if self.urdf_path.endswith('.xacro'):
            mappings = dict(a.split(':=', 1) for a in args.xacro_arg)
            self.urdf = xacro_bridge.expand(self.urdf_path, mappings)
        else:
            with open(self.urdf_path) as f:
                self.urdf = f.read()
        self.controllers_path: str = args.controllers or arm1_file('config/controllers.yaml')
        with open(self.controllers_path) as f:
            self.params: Dict[str, Any] = yaml.safe_load(f) or {}
        self.world: Optional[str] = args.world or (
            arm1_file('worlds/willow_garage.world') if self.arm1 else None
        )
        start = dict(ARM1_START) if self.arm1 else {}
        start.update(parse_pose(args.start))
        if args.pose is None:
            poses = [dict(p) for p in ARM1_POSES] if self.arm1 else []
        else:
            poses = [parse_pose(p.split(',')) for p in args.pose if p.strip() != 'none']
        self.protocol = Protocol(start, args.step, args.settle, args.hold, poses)
        self.criteria = Criteria(args.max_overshoot, args.max_jitter)

    def rig(self, params: Optional[Dict[str, Any]] = None) -> StepRig:
        """A fresh headless simulation of the robot with ``params`` (default: the yaml's)."""
        return StepRig(self.urdf, params or self.params, self.world, find_package)
