"""gazebo_ros's part: the world node (gzserver), its loop and /clock, and the /gazebo services
and topics.
"""
