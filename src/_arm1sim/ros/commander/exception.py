"""moveit_commander's one exception type."""


class MoveItCommanderException(Exception):
    """What moveit_commander raises for a request it cannot honour (bad target, no
    end effector, unknown group)."""
