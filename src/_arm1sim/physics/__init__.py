"""ROS-free physics layer: pybullet world and robots, URDF and SDF reading."""
