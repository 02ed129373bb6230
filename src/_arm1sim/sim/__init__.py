"""The simulation, free of ROS: models, their controller managers and hardware, time and pacing."""
