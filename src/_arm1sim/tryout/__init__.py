"""try_robot: robot package repositories built unchanged and run on the stand-in, reported."""
