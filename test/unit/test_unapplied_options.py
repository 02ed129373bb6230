"""What the world node logs about gzserver options and gazebo_ros launch arguments it accepts
but cannot apply (ros/world/unapplied_options.py): one line each, none for the defaults."""

from arm1.ros.world.unapplied_options import unapplied_options

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
