"""The velocity-limit saturation trap, diagnosed (Gazebo says nothing here; we do).

gazebo_ros_control's effort saturation zeroes any effort that pushes a joint further beyond
its velocity limit. When the controller's gains are stiff for the link, one step's effort
drives the joint past the limit one way, the cut leaves the next step to the controller
pushing back past it the other way, and the joint is held in a step-rate chatter: its
velocity flips sign every step, beyond the limit both ways, while it goes nowhere (a
trajectory goal then aborts). ``LimitChatterWatch`` sees that pattern per joint and says
once which joint, its velocity limit and the fix.
"""

from __future__ import annotations

from typing import List, Sequence, Tuple

STEPS = 50  # consecutive sign flips beyond the limit that make a chatter (50 ms at 1 kHz)


def chatter_message(joint: str, max_velocity: float) -> str:
    return (
        "joint '%s' is caught in a velocity-limit chatter: its velocity flips sign every step, "
        'beyond its velocity limit of %g both ways, so the effort saturation cuts the effort '
        'every other step and the joint goes nowhere. Lift the cut with the parameter '
        '<robotNamespace>/joint_limits/%s/has_velocity_limits: false (as '
        'config/controllers_trajectory.yaml does), or lower its controller gains'
        % (joint, max_velocity, joint)
    )


class LimitChatterWatch:
    """Per step, ``observe`` the joints' velocities (in the order given at construction);
    it returns (name, velocity limit) of the joints whose chatter has just been seen, each
    once."""

    def __init__(self, joints: Sequence[Tuple[str, float]]) -> None:
        """``joints``: (name, velocity limit) of the effort joints with a finite one."""
        self.joints = list(joints)
        self._limits = [limit for _, limit in self.joints]
        self._previous: Sequence[float] = [0.0] * len(self.joints)
        self._run = [0] * len(self.joints)
        self.reported: List[str] = []

    def observe(self, velocities: Sequence[float]) -> List[Tuple[str, float]]:
        """``velocities`` is kept as the next step's previous ones: hand a new sequence each
        step (it is read, never changed)."""
        found = []
        previous, self._previous = self._previous, velocities
        runs, limits = self._run, self._limits
        for k, v in enumerate(velocities):
            limit = limits[k]
            if -limit <= v <= limit:  # within the limit (every step, usually): no chatter
                if runs[k]:
                    runs[k] = 0
                continue
            before = previous[k]
            if abs(v) > limit and abs(before) > limit and (v > 0) != (before > 0):
                runs[k] += 1
                name = self.joints[k][0]
                if runs[k] == STEPS and name not in self.reported:
                    self.reported.append(name)
                    found.append((name, limit))
            else:
                runs[k] = 0
        return found
