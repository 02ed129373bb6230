"""rospy helpers every room uses: sim-time stamps, synchronous publishers, log routing, package
lookup.
"""
