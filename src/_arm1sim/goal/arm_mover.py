"""What arm_mover decides, free of ROS (the node: ros/arm_mover.py): joint ranges from the
URDF, clamping a request into them, and when the arm has arrived."""

import math

from ..description.urdf_model import parse_urdf


def joint_limits(urdf_xml):
    """{joint: (lower, upper)} of the URDF's revolute and prismatic joints."""
    return {
        j.name: (j.limits.lower, j.limits.upper)
        for j in parse_urdf(urdf_xml).joints.values()
        if j.type in ('revolute', 'prismatic') and j.limits.lower is not None
    }


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
            warnings.append(
                '%s = %.3f is out of range [%.3f, %.3f]: clamped to %.3f'
                % (joint, value, lower, upper, targets[joint])
            )
    return targets, warnings


def off_target(positions, targets, tolerance):
    """The joints of ``targets`` farther than ``tolerance`` from them (or not in ``positions``)."""
    return [
        j
        for j, t in targets.items()
        if j not in positions or not abs(positions[j] - t) <= tolerance
    ]


def describe(joints, positions, targets):
    """'joint2 at 1.569 (target 3.000), ...' for an error message."""
    return ', '.join(
        '%s at %s (target %.3f)'
        % (j, '%.3f' % positions[j] if j in positions else 'unknown', targets[j])
        for j in joints
    )
