"""Thin ROS wiring: translates between rospy and the ROS-free simulation."""
