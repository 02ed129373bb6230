"""ros/common/publishers.py: whether a physics-thread topic has a subscriber, lock-free."""

import rospy
from std_msgs.msg import Float64

from _arm1sim.ros.common.publishers import subscribed, synchronous_publisher


def test_subscribed_follows_rospys_connection_list():
    pub = synchronous_publisher('/arm1_unit_test/subscribed', Float64)
    try:
        assert not subscribed(pub)
        # rospy replaces the list on each change (copy on write), as here
        pub.impl.connections = pub.impl.connections + [object()]
        assert subscribed(pub) and pub.get_num_connections() == 1
        pub.impl.connections = []
        assert not subscribed(pub)
    finally:
        pub.unregister()
    assert not subscribed(pub)  # unregistered: no impl any more
    assert isinstance(pub, rospy.Publisher)
