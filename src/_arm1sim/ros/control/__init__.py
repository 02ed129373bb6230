"""gazebo_ros_control's part: the node handle controllers get, their messages and actions, the
controller_manager services, dynamic_reconfigure of PID gains.
"""
