"""controller_manager's command-line tool (open_manipulator's bringup runs
`controller_manager spawn joint_state_controller`): the service calls each command makes."""

from types import SimpleNamespace

from _arm1sim.ros.tools.controller_manager_cli import Manager, run


def fake(ok=True):
    calls = []

    def service(name):
        def call(*args):
            calls.append((name, args))
            if name == 'list_controllers':
                res = SimpleNamespace(hardware_interface='hardware_interface::EffortJointInterface')
                return SimpleNamespace(
                    controller=[
                        SimpleNamespace(name='a', state='running', claimed_resources=[res]),
                        SimpleNamespace(name='b', state='initialized', claimed_resources=[]),
                    ]
                )
            if name == 'list_controller_types':
                return SimpleNamespace(types=['t1', 't2'])
            return SimpleNamespace(ok=ok)

        return call

    names = [
        'load_controller',
        'unload_controller',
        'switch_controller',
        'list_controllers',
        'list_controller_types',
        'reload_controller_libraries',
    ]
    lines = []
    return Manager({n: service(n) for n in names}, lines.append), calls, lines


def test_spawn_loads_every_controller_then_starts_each_strictly():
    m, calls, lines = fake()
    assert run(['spawn', 'jsc', 'arm'], m) == 0
    assert calls == [
        ('load_controller', ('jsc',)),
        ('load_controller', ('arm',)),
        ('switch_controller', (['jsc'], [], 2, False, 0.0)),
        ('switch_controller', (['arm'], [], 2, False, 0.0)),
    ]
    assert lines[:2] == ['Loaded jsc', 'Loaded arm']


def test_kill_stops_then_unloads_and_aliases_work():
    m, calls, lines = fake()
    assert run(['kl', 'arm'], m) == 0
    assert calls == [
        ('switch_controller', ([], ['arm'], 2, False, 0.0)),
        ('unload_controller', ('arm',)),
    ]


def test_refusals_are_reported_and_list_shows_states():
    m, calls, lines = fake(ok=False)
    run(['load', 'x'], m)
    run(['start', 'x'], m)
    assert lines == ['Error when loading x', "Error when starting ['x']"]
    m, calls, lines = fake()
    run(['list'], m)
    assert lines == [
        'a - hardware_interface::EffortJointInterface ( running )',
        'b -  ( initialized )',
    ]


def test_reload_with_restore_reloads_and_restarts_the_running_ones():
    m, calls, lines = fake()
    run(['reload-libraries', '--restore'], m)
    assert ('reload_controller_libraries', (True,)) in calls
    assert calls[-1] == ('switch_controller', (['a'], [], 1, False, 0.0))


def test_an_unknown_command_prints_the_usage_and_fails():
    m, calls, lines = fake()
    assert run(['frobnicate'], m) == 1
    assert calls == [] and 'spawn <name>' in lines[0]
