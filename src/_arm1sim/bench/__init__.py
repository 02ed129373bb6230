"""make bench: the stand-in against bare pybullet, and its real-time behaviour."""
