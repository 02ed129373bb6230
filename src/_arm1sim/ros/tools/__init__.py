"""Command-line tools: spawn_model, spawner, the controller_manager CLI, xacro,
camera_snapshot, bag reading.
"""
