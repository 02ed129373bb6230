"""python -m arm1.tryout: the same as rosrun arm1 try_robot."""

import sys

from arm1.tryout.cli import main

sys.exit(main())
