"""Sim time in the core's integer nanoseconds <-> rospy's Time and Duration."""

from typing import Any

import rospy


def to_time(ns: int) -> rospy.Time:
    return rospy.Time(ns // 1000000000, ns % 1000000000)


def duration_ns(d: Any) -> int:
    return int(d.secs) * 1000000000 + int(d.nsecs)
