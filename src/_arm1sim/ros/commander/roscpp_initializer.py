"""roscpp_initialize / roscpp_shutdown: upstream starts roscpp inside the Python process for
its C++ wrappers; here every part is rospy, so there is nothing to start. The scripts call
rospy.init_node themselves, as upstream requires."""

from __future__ import annotations

from typing import Sequence

_args: list = []


def roscpp_initialize(args: Sequence[str]) -> None:
    # upstream drops __name:= so the wrappers' roscpp node keeps its own name
    _args[:] = [a for a in args if not a.startswith('__name:=')]


def roscpp_shutdown() -> None:
    _args.clear()
