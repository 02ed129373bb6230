"""``make soak``: robot_spawn.launch under simple_mover with a camera viewer, for minutes on end.

One module per job: ``probes`` (what is sampled: /clock, joint_states and image stamps, the
world's memory, threads and CPU), ``run`` (the ROS session and its sampling loop), ``judge``
(per-minute figures and the goals' verdicts), ``report`` (the lines printed and the Soak
section of BENCHMARKS.md), ``plot`` (bench/soak.png) and ``__main__`` (the command line).
"""
