"""What the world node logs about gzserver options and gazebo_ros launch arguments it accepts
but cannot apply (ros/world/unapplied_options.py): one line each, none for the defaults."""

from _arm1sim.ros.world.unapplied_options import unapplied_options

DEFAULTS = {'debug': False, 'gui_required': False, 'use_clock_frequency': True}


def test_defaults_say_nothing():
    assert unapplied_options('ode', False, [], DEFAULTS) == []


def test_each_unapplied_option_is_one_line_naming_it():
    params = {
        'debug': 'true',
        'gui_required': True,
        'use_clock_frequency': False,
        'pub_clock_frequency': 50,
        'enable_ros_network': False,
    }
    notes = unapplied_options('bullet', True, ['--seed', '5'], params)
    assert len(notes) == 7
    for word in (
        'physics bullet',
        'recording',
        '--seed 5',
        'debug',
        'gui_required',
        'use_clock_frequency',
        'enable_ros_network',
    ):
        assert sum(word in n for n in notes) == 1, (word, notes)
    assert '50 Hz' in notes[5]


def test_gzserver_command_line_takes_gazebos_options_without_mistaking_their_values():
    from _arm1sim.ros.world.world_node import parse_args

    args = parse_args(
        ['-u', '-r', '-e', 'bullet', '--seed', '7', '-s', 'libx.so', '--bogus', 'worlds/x.world']
    )
    assert args.world == 'worlds/x.world' and args.paused and args.record
    assert args.physics == 'bullet'
    assert args.unknown == ['--bogus', '--server-plugin', 'libx.so', '--seed', '7']
    plain = parse_args(['worlds/empty.world'])
    assert plain.unknown == [] and not plain.record and plain.physics == 'ode'
