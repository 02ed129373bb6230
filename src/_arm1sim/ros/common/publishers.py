"""Publishers for the physics thread's topics."""

import warnings
from typing import Any

import rospy


def subscribed(pub: rospy.Publisher) -> bool:
    """Whether ``pub`` has a subscriber now, without get_num_connections' lock: rospy
    replaces a topic's connection list on every change (copy on write), so reading it is
    safe from any thread; the physics thread asks this every step or so."""
    impl = pub.impl
    return impl is not None and bool(impl.connections)


def synchronous_publisher(topic: str, msg_class: type, **kwargs: Any) -> rospy.Publisher:
    """A publisher that writes in the caller's thread, for the physics thread's topics.

    rospy's queued publisher (queue_size set) ends every publish with ``time.sleep(0)``
    to hand the message to a writer thread: about 0.1 ms each here, a third of the
    top speed at 50 Hz joint_states and 100 Hz /clock of sim time. Written
    synchronously, a small message on loopback costs a few tens of microseconds.
    """
    with warnings.catch_warnings():
        warnings.simplefilter('ignore')  # rospy warns when queue_size is None
        return rospy.Publisher(topic, msg_class, queue_size=None, **kwargs)
