"""What a robot or world file says, read safely and checked against the world's limits.

No ROS and no pybullet: physics, control and the ROS layer all build on it.
"""
