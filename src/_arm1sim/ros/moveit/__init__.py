"""MoveIt's move_group stand-in: the ROS node around the planning core (planning/)."""
