"""What look_away decides, free of ROS (the node: ros/look_away.py)."""


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
        self.still = (
            last is not None
            and len(last) == len(self._last)
            and all(abs(a - b) < self.still_threshold for a, b in zip(last, self._last))
        )

    def decide(self, uniform):
        """True if the arm should move now; the caller calls ``done()`` once it has."""
        if self.busy or not (uniform and self.still):
            return False
        self.busy = True
        return True

    def done(self):
        self.busy = False
