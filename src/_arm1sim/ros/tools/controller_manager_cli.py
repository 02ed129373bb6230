"""``rosrun controller_manager controller_manager COMMAND [NAME...]``: controller_manager's
command-line tool (load, unload, start, stop, spawn, kill, list, list-types,
reload-libraries) over the stand-in's controller manager services.

As upstream's: the services are ``controller_manager/...`` relative to the node's namespace
(a launch file's ``ns`` or ``__ns:=``), each is waited for without a time limit, every name
is handled in turn, and spawn/kill do all loads (stops) before the one switch (unloads).
"""

import sys
from typing import Callable, Dict, List, Optional

USAGE = """Commands:
    load <name>          - Load the controller named <name>
    unload <name>        - Unload the controller named <name>
    start <name>         - Start the controller named <name>
    stop <name>          - Stop the controller named <name>
    spawn <name>         - Load and start the controller named <name>
    kill <name>          - Stop and unload the controller named <name>
    list                 - List active controllers
    list-types           - List controller Types
    reload-libraries     - Reloads all plugin controller libraries"""

ALIASES = {'sp': 'spawn', 'kl': 'kill', 'lc': 'list', 'lt': 'list-types'}
STRICT = 2
BEST_EFFORT = 1

Call = Callable[..., object]


class Manager:
    """The controller manager's services, as callables (rospy proxies, or fakes in tests)."""

    def __init__(self, services: Dict[str, Call], out: Callable[[str], None] = print) -> None:
        self.services = services
        self.out = out

    def load(self, name: str) -> bool:
        ok = bool(self.services['load_controller'](name).ok)  # type: ignore[attr-defined]
        self.out('Loaded %s' % name if ok else 'Error when loading %s' % name)
        return ok

    def unload(self, name: str) -> bool:
        ok = bool(self.services['unload_controller'](name).ok)  # type: ignore[attr-defined]
        self.out('Unloaded %s successfully' % name if ok else 'Error when unloading %s' % name)
        return ok

    def switch(self, names: List[str], start: bool) -> bool:
        reply = self.services['switch_controller'](
            names if start else [], [] if start else names, STRICT, False, 0.0
        )
        ok = bool(reply.ok)  # type: ignore[attr-defined]
        verb = 'Started' if start else 'Stopped'
        self.out(
            '%s %s successfully' % (verb, names)
            if ok
            else 'Error when %s %s' % ('starting' if start else 'stopping', names)
        )
        return ok

    def list(self) -> None:
        controllers = self.services['list_controllers']().controller  # type: ignore[attr-defined]
        if not controllers:
            self.out('No controllers are loaded in mechanism control')
        for c in controllers:
            ifaces = '+'.join(sorted({r.hardware_interface for r in c.claimed_resources}))
            self.out('%s - %s ( %s )' % (c.name, ifaces, c.state))

    def list_types(self) -> None:
        for t in self.services['list_controller_types']().types:  # type: ignore[attr-defined]
            self.out(t)

    def reload_libraries(self, restore: bool) -> bool:
        before = self.services['list_controllers']().controller if restore else []  # type: ignore
        ok = bool(self.services['reload_controller_libraries'](True).ok)  # type: ignore
        self.out(
            'Successfully reloaded libraries'
            if ok
            else 'Failed to reload libraries. Do you still have controllers loaded?'
        )
        if restore:
            for c in before:
                self.services['load_controller'](c.name)
            running = [c.name for c in before if c.state == 'running']
            self.services['switch_controller'](running, [], BEST_EFFORT, False, 0.0)
            self.out('Controllers restored to original state')
        return ok


def run(args: List[str], manager: Manager) -> int:
    """One command; 0 unless the command is unknown (upstream exits 0 on refusals too)."""
    if not args:
        manager.out(USAGE)
        return 0
    command, names = ALIASES.get(args[0], args[0]), args[1:]
    if command == 'load':
        for n in names:
            manager.load(n)
    elif command == 'unload':
        for n in names:
            manager.unload(n)
    elif command in ('start', 'stop'):
        for n in names:
            manager.switch([n], command == 'start')
    elif command == 'spawn':
        for n in names:
            manager.load(n)
        for n in names:
            manager.switch([n], True)
    elif command == 'kill':
        for n in names:
            manager.switch([n], False)
        for n in names:
            manager.unload(n)
    elif command == 'list':
        manager.list()
    elif command == 'list-types':
        manager.list_types()
    elif command == 'reload-libraries':
        manager.reload_libraries('--restore' in names)
    else:
        manager.out(USAGE)
        return 1
    return 0


def ros_services() -> Dict[str, Call]:
    """Proxies that wait (without limit, as upstream) for their service on first use."""
    import rospy
    from controller_manager_msgs import srv

    types = {
        'load_controller': srv.LoadController,
        'unload_controller': srv.UnloadController,
        'switch_controller': srv.SwitchController,
        'list_controllers': srv.ListControllers,
        'list_controller_types': srv.ListControllerTypes,
        'reload_controller_libraries': srv.ReloadControllerLibraries,
    }

    def proxy(name: str) -> Call:
        def call(*args: object) -> object:
            service = 'controller_manager/' + name
            rospy.wait_for_service(service)
            return rospy.ServiceProxy(service, types[name])(*args)

        return call

    return {name: proxy(name) for name in types}


def main(argv: Optional[List[str]] = None) -> int:
    import rospy

    args = rospy.myargv(sys.argv if argv is None else argv)[1:]
    rospy.init_node('controller_manager_cli', anonymous=True)
    return run(args, Manager(ros_services()))
