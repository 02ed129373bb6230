"""The seed's goal, free of ROS: what arm_mover and look_away decide, and the image test."""
