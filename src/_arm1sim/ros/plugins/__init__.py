"""gazebo_plugins's part: the ROS side of the sensor and model plugins a robot brings (camera,
depth camera, laser, IMU, p3d, bumper, ft_sensor, diff drive).
"""
