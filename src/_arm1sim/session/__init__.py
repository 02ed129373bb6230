"""Private ROS sessions the project's own commands start (make demo, make soak, tests)."""
