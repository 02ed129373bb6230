"""What a pick-and-place with pick_arm (test/robots/pick_arm) needs, free of ROS: the objects
it picks (as URDF), where its lift puts the finger tips, and whether a held object kept up
with the gripper (the node: ros/nodes/pick_place_demo.py; the rostests: test/test_pick.py)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

TABLE_TOP = 0.2  # z of the table top in pick_arm's worlds (m)
TIPS_AT_ZERO_LIFT = 0.37  # z of pick_arm's finger tips with lift_joint at 0 (m)
TIP_CLEARANCE = 0.004  # finger tips stop this far above the table when picking (m)
LIFT_RISE = 0.1  # how far a pick raises the gripper (m)
HOLD_S = 5.0  # how long a lifted object is held before it is judged (sim s)
MIN_RISE_RATIO = 0.95  # the object rises at least this fraction of the gripper's rise
MAX_SLIP = 0.002  # the object moves at most this far against the gripper while held (m)


@dataclass(frozen=True)
class PickObject:
    """A box (size x, y, z) or an upright cylinder (radius, length), mass in kg, ``mu`` its
    <mu1>/<mu2>."""

    name: str
    shape: str  # 'box' or 'cylinder'
    dims: Sequence[float]
    mass: float
    mu: float = 1.0

    @property
    def height(self) -> float:
        return self.dims[2] if self.shape == 'box' else self.dims[1]

    def urdf(self) -> str:
        if self.shape == 'box':
            x, y, z = self.dims
            geometry = '<box size="%g %g %g"/>' % (x, y, z)
            ixx, iyy, izz = (y * y + z * z), (x * x + z * z), (x * x + y * y)
            ixx, iyy, izz = (self.mass * v / 12 for v in (ixx, iyy, izz))
        else:
            r, length = self.dims
            geometry = '<cylinder radius="%g" length="%g"/>' % (r, length)
            ixx = iyy = self.mass * (3 * r * r + length * length) / 12
            izz = self.mass * r * r / 2
        return (
            '<robot name="%s"><link name="link">'
            '<inertial><mass value="%g"/>'
            '<inertia ixx="%g" ixy="0" ixz="0" iyy="%g" iyz="0" izz="%g"/></inertial>'
            '<visual><geometry>%s</geometry></visual>'
            '<collision><geometry>%s</geometry></collision></link>'
            '<gazebo reference="link"><mu1>%g</mu1><mu2>%g</mu2></gazebo></robot>'
            % (self.name, self.mass, ixx, iyy, izz, geometry, geometry, self.mu, self.mu)
        )


# The rostests' objects: three boxes and a cylinder, all narrower than the open fingers (0.09).
OBJECTS = (
    PickObject('box30', 'box', (0.03, 0.03, 0.03), 0.03),
    PickObject('box40', 'box', (0.04, 0.04, 0.04), 0.06),
    PickObject('box50', 'box', (0.05, 0.05, 0.05), 0.1),
    PickObject('can40', 'cylinder', (0.02, 0.05), 0.05),
)


def pick_lift(obj: PickObject) -> float:
    """lift_joint position that puts the finger tips just above the table, pads around obj
    (the pads are 0.06 tall: an object up to that height is gripped along all its sides)."""
    del obj  # every object stands on the table: the tips go as low as the table allows
    return TABLE_TOP + TIP_CLEARANCE - TIPS_AT_ZERO_LIFT


@dataclass(frozen=True)
class HoldVerdict:
    """How a lifted object kept up with the gripper: ``rise_ratio`` its rise over the
    gripper's, ``slip`` the most it moved against the gripper during the hold (m)."""

    gripper_rise: float
    object_rise: float
    slip: float

    @property
    def rise_ratio(self) -> float:
        return self.object_rise / self.gripper_rise if self.gripper_rise > 0 else 0.0

    @property
    def held(self) -> bool:
        return self.rise_ratio >= MIN_RISE_RATIO and self.slip <= MAX_SLIP

    def __str__(self) -> str:
        return 'rose %.1f of %.1f mm (%.1f %%), slipped %.2f mm: %s' % (
            self.object_rise * 1e3,
            self.gripper_rise * 1e3,
            self.rise_ratio * 100,
            self.slip * 1e3,
            'held' if self.held else 'NOT held',
        )


def judge_hold(
    gripper_before: float,
    object_before: float,
    gripper_after: float,
    object_after: float,
    offsets_during_hold: Sequence[float],
) -> HoldVerdict:
    """Heights (world z, m) of the gripper and the object once closed (before) and once
    lifted (after), and the object's height relative to the gripper sampled through the
    hold (the first taken at its start)."""
    if not offsets_during_hold:
        raise ValueError('no samples of the hold')
    first = offsets_during_hold[0]
    return HoldVerdict(
        gripper_rise=gripper_after - gripper_before,
        object_rise=object_after - object_before,
        slip=max(abs(o - first) for o in offsets_during_hold),
    )
