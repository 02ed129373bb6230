"""python -m _arm1sim.tryout: the same as rosrun arm1 try_robot."""

import sys

from _arm1sim.tryout.cli import main

sys.exit(main())
