"""The world node (``rosrun arm1 gzserver``): a Simulation with gazebo_ros's ROS API.

Physics runs on the main thread (WorldLoop); service calls arrive on rospy's threads
and are handed to it between two steps (SimThreadCalls), so pybullet is only touched there.
"""

from __future__ import annotations

import argparse
import gc
import os
import sys
from typing import Any, List, Optional, Sequence, Tuple

import rospy

from ...description.limits import LimitError, Limits
from ...description.resource_paths import ResourceNotFound, gazebo_paths
from ...description.sdf_world import SdfError, WorldConfig, read_world
from ...sim.pacer import Pacer, wall_period
from ...sim.simulation import Model, Simulation, SpawnError
from ..common.logs import route_core_logs
from ..common.packages import gazebo_exports
from .gazebo_ros_api import GazeboRosApi
from .gazebo_state_api import GazeboStateApi
from .master_watch import MasterWatch
from .sim_clock import SimClock
from .sim_thread import SimThreadCalls
from .unapplied_options import unapplied_options
from .world_loop import WorldLoop


class WorldNode:
    """What ``start_world`` builds: the simulation, its loop and its services."""

    def __init__(self, sim: Simulation, paused: bool = False) -> None:
        self.sim = sim
        self.calls = SimThreadCalls()
        clock = SimClock(rospy.get_param('~pub_clock_frequency', 100))
        self.loop = WorldLoop(sim, self.calls, clock, paused)
        self.api = GazeboRosApi(sim, self.calls, self.loop)
        self.pacer: Optional[Pacer] = None
        self.web: Optional[Any] = None  # web_view.WebView with --web
        self.state_api = GazeboStateApi(sim, self.calls, self.loop, self._set_update_rate)

    def _set_update_rate(self, rate: float) -> None:
        """set_physics_properties' max_update_rate (0: as fast as it goes). Physics thread."""
        c = self.sim.config
        if self.pacer is not None:
            self.pacer.period = wall_period(c.max_step_size, c.real_time_factor, rate)
            self.pacer.restart()

    def spawn(
        self, name: str, xml: str, xyz: Sequence[float], quat: Sequence[float], namespace: str = ''
    ) -> Model:
        return self.api.spawn(name, xml, xyz, quat, namespace)

    def spawn_world_models(self) -> None:
        """The world file's models (sdf_world), spawned as a request's would be, before
        physics starts; one that fails is reported with the world's other skipped parts."""
        config = self.sim.config
        for s in config.spawns:
            try:
                self.spawn(s.name, s.urdf, s.position, s.orientation)
            except SpawnError as exc:
                config.skipped.append((s.name, str(exc)))

    def run(self, pacer: Pacer) -> None:
        self.pacer = pacer
        self.loop.run(pacer)


def parse_args(argv: List[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog='gzserver',
        description=(
            'pybullet stand-in for gzserver with gazebo_ros: runs the world file, publishes /clock '
            'and offers the /gazebo services.'
        ),
    )
    parser.add_argument('world', nargs='?', help='SDF world file (default: an empty world)')
    parser.add_argument('-u', '--paused', action='store_true', help='start with physics paused')
    parser.add_argument(
        '--gui', action='store_true', help="open pybullet's window if a display exists"
    )
    parser.add_argument('-e', '--physics', default='ode', help='ignored: pybullet is the engine')
    parser.add_argument('--verbose', action='store_true')
    parser.add_argument(
        '--lockstep',
        action='store_true',
        help=(
            'physics waits for every camera frame (deterministic; the real-time factor drops '
            'instead of the image rate)'
        ),
    )
    parser.add_argument(
        '--web',
        action='store_true',
        help='serve a browser view of the world (docs/web-view.md); its address is printed',
    )
    parser.add_argument(
        '--web-host',
        default='127.0.0.1',
        help='interface the browser view listens on (default: loopback only; see the docs\' '
        'Security section before choosing another)',
    )
    parser.add_argument(
        '--web-port', type=int, default=8080, help='its port (taken: the next free one; 0: any)'
    )
    parser.add_argument('--real-time-factor', type=float, help='overrides the world file')
    parser.add_argument('--real-time-update-rate', type=float, help='overrides the world file')
    parser.add_argument('-r', '--record', action='store_true', help='accepted, not applied')
    # gzserver's options taking a value (empty_world.launch's extra_gazebo_args): accepted,
    # logged as not applied, so their values are not taken for the world file
    for flags in GZSERVER_VALUE_OPTIONS:
        parser.add_argument(*flags, dest='gz_' + flags[-1].lstrip('-'), action='append')
    args, unknown = parser.parse_known_args(argv)
    for flags in GZSERVER_VALUE_OPTIONS:
        for value in getattr(args, 'gz_' + flags[-1].lstrip('-')) or []:
            unknown += [flags[-1], value]
    args.unknown = unknown
    return args


GZSERVER_VALUE_OPTIONS = (
    ('-s', '--server-plugin'),
    ('--seed',),
    ('--iters',),
    ('-p', '--play'),
    ('-o', '--profile'),
    ('--record_path',),
    ('--record_period',),
    ('--record_filter',),
    ('--record_encoding',),
)


def world_config(args: argparse.Namespace) -> WorldConfig:
    """The world file, with the command line's and the ``~limits`` parameters' overrides."""
    config = WorldConfig()
    if args.world:
        # As Gazebo: a name like worlds/empty.world is looked up on GAZEBO_RESOURCE_PATH.
        paths = gazebo_paths(os.environ, gazebo_exports())
        config = read_world(paths.find_world(args.world), paths.find_model)
    config.lockstep = args.lockstep
    config.limits = Limits.from_mapping(
        rospy.get_param('~limits', {}), rospy.resolve_name('~limits'), config.limits
    )
    for attr in ('real_time_factor', 'real_time_update_rate'):
        if getattr(args, attr) is not None:
            setattr(config, attr, getattr(args, attr))
    return config


SWITCH_INTERVAL = 0.0002  # s a thread holds the interpreter lock while another waits
GC_THRESHOLDS = (10000, 10, 100)  # a full collection every ~10 M allocations, not ~70 k


def pace_the_interpreter() -> None:
    """Keep the physics thread's interpreter-lock waits short (issue 22, case 1).

    Python's 5 ms switch interval lets a thread decoding a big message (a 100 000-point goal
    is 0.4 s of genpy) hold the physics thread off for 5 ms at each of its 1 ms steps; and its
    full collections, which hold the lock throughout, scan every live object: 100-250 ms
    while such a goal's million objects arrive. The world built so far is frozen out of them.
    """
    sys.setswitchinterval(SWITCH_INTERVAL)
    gc.collect()
    gc.freeze()
    gc.set_threshold(*GC_THRESHOLDS)


def start_world(args: argparse.Namespace) -> Tuple[WorldNode, Pacer]:
    """Init the node and build the world of parsed gzserver ``args``."""
    rospy.init_node('gazebo')
    route_core_logs()
    MasterWatch()  # a restarted master learns the world's topics and services again
    try:
        config = world_config(args)
    except (SdfError, LimitError, ResourceNotFound) as exc:
        rospy.logfatal(str(exc))
        sys.exit(1)
    for note in unapplied_options(
        args.physics, args.record, args.unknown, rospy.get_param('~', {})
    ):
        rospy.loginfo('gzserver: %s', note)
    node = WorldNode(Simulation(config, gui=args.gui), paused=args.paused)
    node.spawn_world_models()
    if config.skipped:
        rospy.logwarn('world: not built: %s', '; '.join('%s (%s)' % s for s in config.skipped))
    period = wall_period(
        config.max_step_size, config.real_time_factor, config.real_time_update_rate
    )
    rospy.loginfo(
        'world ready: step %.4f s, real-time factor %g, update rate %g Hz%s',
        config.max_step_size,
        config.real_time_factor,
        config.real_time_update_rate,
        ' (paused)' if args.paused else '',
    )
    if args.web:
        start_web_view(node, args.web_host, args.web_port)
    pace_the_interpreter()
    return node, Pacer(period)


def start_web_view(node: WorldNode, host: str, port: int) -> None:
    """The browser view (imported only when asked: viser is large); its address is printed,
    logged and left in ``~web_url``."""
    try:
        from ..web.web_view import WebView
    except ImportError as exc:  # viser missing: the world runs on without its page
        rospy.logerr('web view: cannot start (%s); run make setup', exc)
        return
    try:
        node.web = WebView(
            node.sim, node.calls, node.loop, host, port, node.api._set_paused
        )  # the pause services' own path
    except OSError as exc:
        rospy.logerr('web view: cannot listen on %s port %d: %s', host, port, exc)
        return
    rospy.set_param('~web_url', node.web.url)
    rospy.loginfo('web view: open %s in a browser', node.web.url)
    print('web view: open %s in a browser' % node.web.url, flush=True)


def main(argv: Optional[List[str]] = None) -> None:
    node, pacer = start_world(parse_args(rospy.myargv(sys.argv if argv is None else argv)[1:]))
    try:
        node.run(pacer)
    finally:
        if node.web is not None:
            node.web.close()
        node.sim.close()
