"""arm1: a pybullet-backed stand-in for Gazebo + gazebo_ros_control.

Layers, as in ros_control: ``physics`` (pybullet world, robots; no ROS),
``control`` (hardware interface, PID, controllers, controller manager; no ROS),
``simulation`` (ties the two together; no ROS) and ``ros`` (thin wiring).
"""
