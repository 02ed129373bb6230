"""``libgazebo_grasp_fix.so`` (gazebo_grasp_plugin) on a spawned robot: its parameters read
as GazeboGraspFix::Load reads them, its arms resolved to the robot's links, and the
physics.grasp.GraspFix that does the work."""

from __future__ import annotations

import logging
import math
from typing import List, Optional

from ...description.gazebo_plugins import PluginSpec
from ...description.limits import Limits
from ...physics.contact import collision_name
from ...physics.grasp import (
    DEFAULT_FORCES_ANGLE_TOLERANCE,
    DEFAULT_MAX_GRIP_COUNT,
    DEFAULT_RELEASE_TOLERANCE,
    DEFAULT_UPDATE_RATE,
    GraspArm,
    GraspFix,
    GraspParams,
)
from ...physics.robot import Robot
from .registry import PluginType, register

log = logging.getLogger('_arm1sim.physics')

GRASP_PLUGIN = 'libgazebo_grasp_fix.so'


def grasp_params(plugin: PluginSpec) -> GraspParams:
    """The plugin's parameters with upstream's defaults; values that make no sense are
    replaced by the default, with a warning naming the plugin."""
    where = plugin.where
    angle = plugin.number('forces_angle_tolerance', DEFAULT_FORCES_ANGLE_TOLERANCE)
    if not 90.0 <= angle <= 180.0:
        # upstream's CheckGrip refuses under 90 degrees: nothing would ever be gripped
        log.warning(
            '%s: <forces_angle_tolerance> %g must be 90 to 180 degrees (the least angle '
            'between two opposing forces): nothing is gripped, as upstream',
            where,
            angle,
        )
    rate = plugin.number('update_rate', DEFAULT_UPDATE_RATE)
    if not 0.0 < rate < math.inf:
        log.warning('%s: <update_rate> %g is not a rate: %g Hz', where, rate, DEFAULT_UPDATE_RATE)
        rate = DEFAULT_UPDATE_RATE
    max_count = _count(plugin, 'max_grip_count', DEFAULT_MAX_GRIP_COUNT)
    threshold = _count(plugin, 'grip_count_threshold', max_count // 2)
    release = plugin.number('release_tolerance', DEFAULT_RELEASE_TOLERANCE)
    if not 0.0 <= release < math.inf:
        log.warning(
            '%s: <release_tolerance> %g is not a distance: %g',
            where,
            release,
            DEFAULT_RELEASE_TOLERANCE,
        )
        release = DEFAULT_RELEASE_TOLERANCE
    return GraspParams(
        forces_angle_tolerance=math.radians(angle),
        update_rate=rate,
        max_grip_count=max_count,
        grip_count_threshold=threshold,
        release_tolerance=release,
        disable_collisions_on_attach=_true(plugin.text('disable_collisions_on_attach', 'false')),
    )


def _true(text: str) -> bool:
    """Upstream's reading: "true" or "1", anything else is false."""
    return text in ('true', '1')


def _count(plugin: PluginSpec, tag: str, default: int) -> int:
    value = plugin.number(tag, default)
    if not (0 <= value < math.inf) or value != int(value):
        log.warning("%s: <%s> %g is not a count: %d", plugin.where, tag, value, default)
        return default
    return int(value)


def grasp_arms(model: str, plugin: PluginSpec, robot: Robot) -> List[GraspArm]:
    """Each ``<arm>`` with its palm and the gripper links that have collisions; an arm
    missing one of them is left out with an error, as upstream does."""
    import pybullet as p

    arms: List[GraspArm] = []
    for element in plugin.element.findall('arm'):
        name = (element.findtext('arm_name') or '').strip()
        palm = (element.findtext('palm_link') or '').strip()
        fingers = [(e.text or '').strip() for e in element.findall('gripper_link')]
        if not (name and palm and fingers):
            log.error(
                "model '%s': %s: an <arm> needs <arm_name>, <palm_link> and <gripper_link>: "
                'left out',
                model,
                plugin.where,
            )
            continue
        if name in (a.name for a in arms):
            log.error("model '%s': %s: arm '%s' given twice", model, plugin.where, name)
            continue
        if palm not in robot.link_index and robot.lumped_link(palm) is None:
            log.error(
                "model '%s': %s: arm '%s': palm link '%s' is not a link of the model: left out",
                model,
                plugin.where,
                name,
                palm,
            )
            continue
        links: List[int] = []
        for finger in fingers:
            if finger not in robot.link_index and robot.lumped_link(finger) is None:
                log.error(
                    "model '%s': %s: arm '%s': gripper link '%s' is not a link of the model",
                    model,
                    plugin.where,
                    name,
                    finger,
                )
                continue
            index = robot.frame(finger)[0]
            shapes = p.getCollisionShapeData(robot.body, index, physicsClientId=robot.client)
            if shapes and index not in links:
                links.append(index)
        if not links:
            log.error(
                "model '%s': %s: arm '%s' has no gripper link with a collision: left out",
                model,
                plugin.where,
                name,
            )
            continue
        arms.append(GraspArm(name, robot.frame(palm)[0], links))
    return arms


def build_grasp_fix(
    model: str, plugin: PluginSpec, robot: Robot, ns: str, limits: Limits
) -> Optional[GraspFix]:
    """The plugin, or None (said why) when no arm could be set up: upstream then does
    nothing either."""
    params = grasp_params(plugin)
    limits.check('sensor_update_rate', params.update_rate, plugin.where)
    arms = grasp_arms(model, plugin, robot)
    if not arms:
        log.error(
            "model '%s': %s: no arms were configured successfully: the plugin does nothing",
            model,
            plugin.where,
        )
        return None
    client = robot.client
    fix = GraspFix(
        model, plugin.name, robot, arms, params, lambda b, i: collision_name(client, b, i)
    )
    fix.namespace = ns
    return fix


register(
    PluginType(
        GRASP_PLUGIN,
        build_model=build_grasp_fix,
        publisher='grasp_plugin:grasp_event_publisher',
    )
)
