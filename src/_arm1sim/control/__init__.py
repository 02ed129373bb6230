"""ROS-free control layer mirroring ros_control: hardware interface, PID, controllers, manager."""
