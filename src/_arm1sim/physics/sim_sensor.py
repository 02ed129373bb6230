"""Sensors measured on the physics thread from pybullet: ray (laser), imu, contact,
force_torque, and model plugins that report state (p3d).

ROS-free. Whoever publishes a sensor's readings sets ``wanted`` (is anyone
listening?) and ``deliver(stamp_ns, reading)``; the simulation measures a
sensor only when it is wanted and due, so a sensor nobody subscribes to costs
nothing. ``deliver`` runs on the physics thread and must not block.
"""

from __future__ import annotations

from typing import Any, Callable, Optional, Sequence, Tuple

import pybullet as p

Vec3 = Tuple[float, float, float]
Quat = Tuple[float, float, float, float]


def _nobody() -> bool:
    return False


class SimSensor:
    """One sensor of a spawned model; subclasses implement ``measure``."""

    kind = 'sensor'  # the SDF sensor type or plugin it stands for, for messages
    # Set by the ROS layer that publishes it: the topic, header.frame_id (before tf_prefix),
    # and the plugin's namespace, where its tf_prefix parameter is read.
    topic = ''
    frame_id = ''
    namespace = ''
    # The Gazebo plugin file it stands for (sim.plugins' registry key), set by its builder's
    # caller: the ROS layer finds its publisher by it.
    plugin_filename = ''

    def __init__(self, model: str, name: str, update_rate: float) -> None:
        self.model, self.name = model, name
        self.update_rate = update_rate
        self.period_ns = int(round(1e9 / update_rate)) if update_rate > 0 else 0
        self.next_ns = 0
        self.last_ns = -1
        self.readings = 0
        self.wanted: Callable[[], bool] = _nobody
        self.deliver: Optional[Callable[[int, Any], None]] = None

    def due(self, now_ns: int) -> bool:
        """True at the sensor's update instants (every step, if its rate is 0)."""
        if not self.period_ns:
            return True
        if now_ns < self.last_ns:  # time went back (reset_simulation)
            self.next_ns = now_ns
        self.last_ns = now_ns
        if now_ns < self.next_ns:
            return False
        self.next_ns += self.period_ns
        if self.next_ns <= now_ns:  # the first update, or after a pause in wanting
            self.next_ns = now_ns + self.period_ns
        return True

    def update(self, now_ns: int) -> None:
        """Measure and hand over, if wanted and due (physics thread)."""
        # due() first: a cheap comparison on most steps, the subscriber count only when due
        if self.deliver is not None and self.due(now_ns) and self.wanted():
            reading = self.measure(now_ns)
            self.readings += 1
            self.deliver(now_ns, reading)

    def measure(self, now_ns: int) -> Any:
        raise NotImplementedError

    def reset(self) -> None:
        """A plugin's Reset(): Gazebo calls it on reset_world and reset_simulation."""

    def close(self) -> None:
        """Release what the sensor holds in the physics (debug items, constraints)."""
        self.deliver = None
        self.wanted = _nobody


def compose(
    a: Tuple[Sequence[float], Sequence[float]], b: Tuple[Sequence[float], Sequence[float]]
) -> Tuple[Vec3, Quat]:
    """The pose b expressed in a's parent frame (a∘b), each (position, quaternion xyzw)."""
    pos, orn = p.multiplyTransforms(a[0], a[1], b[0], b[1])
    return tuple(pos), tuple(orn)


def pose_of(sdf_pose: Sequence[float]) -> Tuple[Vec3, Quat]:
    """An SDF pose (x y z roll pitch yaw) as (position, quaternion xyzw)."""
    x, y, z, roll, pitch, yaw = sdf_pose
    return (x, y, z), tuple(p.getQuaternionFromEuler((roll, pitch, yaw)))
