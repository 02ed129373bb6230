"""Tuning the position controllers' PID gains, free of ROS.

``metrics`` (step-response figures from any sampled response), ``local_ros`` (an
in-process node handle so the real ControllerManager runs without a master),
``steps`` (the step protocol on a headless Simulation at top speed), ``search``
(gain search per joint), ``recorded`` (steps found in a recorded run), ``plot``
(PNG plots, matplotlib Agg), and ``rosrun arm1 tune``: ``cli`` (arguments), ``inputs``
(what they name), ``session`` (measure, search, check, save, plot), ``report`` (what is
printed), ``save`` (gains into the controllers yaml) and ``bag_report`` (``--bag``).
"""
