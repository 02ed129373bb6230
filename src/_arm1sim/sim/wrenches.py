"""apply_body_wrench and apply_joint_effort, ROS-free: forces and efforts held over a span of
sim time, applied again before every step (pybullet's external forces last one step).

Status messages as gazebo_ros_api_plugin's (``StateError``). Sim thread only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Dict, List, Sequence, Tuple

from ..description.pose_math import conjugate as q_inv
from ..description.pose_math import multiply as q_mul
from ..description.pose_math import rotate
from ..physics import body_state
from .model_state import (
    StateError,
    Vec,
    _add,
    _link_state,
    _sub,
    find_joint,
    find_link,
    finite,
    frame_state,
)
from .simulation import Model, Simulation


@dataclass
class WrenchJob:
    model: Model
    link: str
    force: Vec
    torque: Vec
    start_ns: int
    duration_ns: int  # negative: until cleared


@dataclass
class Wrenches:
    """apply_body_wrench jobs: pybullet's external forces last one step, so each active job
    is applied again before every step, between its start and start + duration."""

    jobs: List[WrenchJob] = field(default_factory=list)

    def add(
        self,
        sim: Simulation,
        body: str,
        reference: str,
        point: Sequence[float],
        force: Sequence[float],
        torque: Sequence[float],
        start_ns: int,
        duration_ns: int,
    ) -> None:
        found = find_link(sim, body)
        if found is None:
            raise StateError('ApplyBodyWrench: body [%s] does not exist' % body)
        if not finite(point, force, torque):
            raise StateError('ApplyBodyWrench: wrench on [%s] is not all finite numbers' % body)
        try:
            frame = frame_state(sim, reference)
        except KeyError:
            raise StateError('ApplyBodyWrench: reference_frame [%s] not found' % reference)
        torque = _add(torque, body_state.cross(point, force))
        if frame is not None:
            # As upstream: rotated into the frame's axes as seen from the body, then applied
            # as world-axis vectors (gazebo_ros_pkgs#310).
            link = _link_state(*found)
            q = q_mul(q_inv(link.orientation), frame.orientation)
            offset = rotate(q_inv(link.orientation), _sub(frame.position, link.position))
            force, torque = rotate(q, force), rotate(q, torque)
            torque = _add(torque, body_state.cross(offset, force))
        self.jobs.append(
            WrenchJob(
                found[0],
                found[1],
                (force[0], force[1], force[2]),
                (torque[0], torque[1], torque[2]),
                max(start_ns, sim.time_ns),
                duration_ns,
            )
        )

    def clear(self, scoped_body: str) -> None:
        """clear_body_wrenches: only the scoped ``model::link`` name matches, as upstream."""
        self.jobs = [j for j in self.jobs if '%s::%s' % (j.model.name, j.link) != scoped_body]

    def forget_model(self, name: str) -> None:
        self.jobs = [j for j in self.jobs if j.model.name != name]

    def apply(self, sim: Simulation, now_ns: int) -> None:
        """Before a step from ``now_ns``: the step ends at t = now + step, as Gazebo's update."""
        t = now_ns + sim.step_ns
        keep: List[WrenchJob] = []
        latest: Dict[Tuple[int, str], WrenchJob] = {}
        for job in self.jobs:
            if job.model.name not in sim.models or sim.models[job.model.name] is not job.model:
                continue  # its model was deleted
            end = job.start_ns + job.duration_ns
            if job.duration_ns >= 0 and t > end:
                continue
            keep.append(job)
            if job.start_ns <= t:
                latest[(id(job.model), job.link)] = job  # upstream replaces: the later job acts
        self.jobs = keep
        for job in latest.values():
            body_state.apply_wrench(job.model.robot, job.link, job.force, job.torque)


@dataclass
class EffortJob:
    model: Model
    joint: str
    effort: float
    start_ns: int
    duration_ns: int  # negative: until cleared


@dataclass
class JointEfforts:
    """apply_joint_effort jobs: added to whatever the controllers command, each step between
    start and start + duration; several on one joint add up, capped at its effort limit."""

    jobs: List[EffortJob] = field(default_factory=list)

    def add(
        self, sim: Simulation, joint: str, effort: float, start_ns: int, duration_ns: int
    ) -> None:
        found = find_joint(sim, joint)
        if found is None:
            raise StateError('ApplyJointEffort: joint [%s] not found' % joint)
        if not math.isfinite(effort):
            raise StateError(
                'ApplyJointEffort: effort %r for joint [%s] is not finite' % (effort, joint)
            )
        self.jobs.append(
            EffortJob(found[0], found[1], effort, max(start_ns, sim.time_ns), duration_ns)
        )

    def clear(self, joint: str) -> None:
        """clear_joint_forces: the bare joint name, in every model, as upstream."""
        self.jobs = [j for j in self.jobs if j.joint != joint]

    def apply(self, sim: Simulation, now_ns: int) -> None:
        t = now_ns + sim.step_ns
        keep: List[EffortJob] = []
        totals: Dict[Tuple[int, str], Tuple[Model, float]] = {}
        for job in self.jobs:
            if sim.models.get(job.model.name) is not job.model:
                continue  # its model was deleted
            if job.duration_ns >= 0 and t > job.start_ns + job.duration_ns:
                continue
            keep.append(job)
            if job.start_ns <= t:
                key = (id(job.model), job.joint)
                totals[key] = (job.model, totals.get(key, (job.model, 0.0))[1] + job.effort)
        self.jobs = keep
        for (_, joint), (model, effort) in totals.items():
            limit = body_state.effort_limit(model.robot, joint)
            if limit > 0:
                effort = max(-limit, min(limit, effort))
            body_state.apply_joint_effort(model.robot, joint, effort)
