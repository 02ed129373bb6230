"""MoveIt's planning without ROS: the robot model and its SRDF groups, a collision world of
its own (pybullet DIRECT), IK, OMPL planning, time parameterization and Cartesian paths.
The move_group stand-in (ros/moveit/) serves it."""
