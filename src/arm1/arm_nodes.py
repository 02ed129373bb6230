"""What arm_mover and look_away decide, free of ROS (the nodes: ros/arm_mover.py, look_away.py)."""
import math

from .description.urdf_model import parse_urdf


# ------------------------------------------------------------------- arm_mover
def joint_limits(urdf_xml):
    """{joint: (lower, upper)} of the URDF's revolute and prismatic joints."""
    return {j.name: (j.limits.lower, j.limits.upper) for j in parse_urdf(urdf_xml).joints.values()
            if j.type in ('revolute', 'prismatic') and j.limits.lower is not None}


def clamp_request(request, ranges):
    """``(targets, warnings)``: each value of ``request`` clamped into its ``ranges`` entry.

    Raises ValueError for a value that is not a finite number.
    """
    targets, warnings = {}, []
    for joint, value in request.items():
        if not math.isfinite(value):
            raise ValueError('%s: %r is not a finite angle' % (joint, value))
        lower, upper = ranges[joint]
        targets[joint] = min(max(value, lower), upper)
        if targets[joint] != value:
            warnings.append('%s = %.3f is out of range [%.3f, %.3f]: clamped to %.3f'
                            % (joint, value, lower, upper, targets[joint]))
    return targets, warnings


def off_target(positions, targets, tolerance):
    """The joints of ``targets`` farther than ``tolerance`` from them (or not in ``positions``)."""
    return [j for j, t in targets.items()
            if j not in positions or not abs(positions[j] - t) <= tolerance]


def describe(joints, positions, targets):
    """'joint2 at 1.569 (target 3.000), ...' for an error message."""
    return ', '.join('%s at %s (target %.3f)' % (
        j, '%.3f' % positions[j] if j in positions else 'unknown', targets[j]) for j in joints)


# ------------------------------------------------------------------- look_away
class LookAwayPolicy:
    """When to look away: a uniform image while the arm is still, one move at a time.

    Still: every joint moved less than ``still_threshold`` since the previous joint state.
    """

    def __init__(self, still_threshold=0.0005):
        self.still_threshold = still_threshold
        self.still = False
        self.busy = False
        self._last = None

    def joint_positions(self, positions):
        last, self._last = self._last, list(positions)
        self.still = (last is not None and len(last) == len(self._last)
                      and all(abs(a - b) < self.still_threshold for a, b in zip(last, self._last)))

    def decide(self, uniform):
        """True if the arm should move now; the caller calls ``done()`` once it has."""
        if self.busy or not (uniform and self.still):
            return False
        self.busy = True
        return True

    def done(self):
        self.busy = False
