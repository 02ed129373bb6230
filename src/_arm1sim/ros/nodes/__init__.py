"""The seed's nodes: arm_mover, look_away and the trajectory demo."""
