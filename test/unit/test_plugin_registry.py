"""sim/plugins' registry: one type per plugin file, each built one way and published by a
factory of ros/plugins/ that exists (needs the built workspace: it imports rospy)."""

import pytest

from _arm1sim.description.camera_sensor import CAMERA_PLUGIN, DEPTH_PLUGINS
from _arm1sim.description.gazebo_plugins import HANDLED_PLUGINS
from _arm1sim.description.urdf_model import MIMIC_PLUGINS
from _arm1sim.sim.plugins import PLUGINS, PluginType, register

# What the stand-in implements of gazebo_plugins and friends (docs/sensors.md)
PUBLISHED = {
    CAMERA_PLUGIN,
    *DEPTH_PLUGINS,
    'libgazebo_ros_laser.so',
    'libgazebo_ros_gpu_laser.so',
    'libgazebo_ros_imu_sensor.so',
    'libgazebo_ros_imu.so',
    'libgazebo_ros_p3d.so',
    'libgazebo_ros_bumper.so',
    'libgazebo_ros_ft_sensor.so',
    'libgazebo_ros_diff_drive.so',
    'libgazebo_grasp_fix.so',
}


def test_every_plugin_is_registered_once_by_file_name():
    assert set(PLUGINS) == PUBLISHED | set(MIMIC_PLUGINS)
    assert all(name == t.filename for name, t in PLUGINS.items())
    # only gazebo_ros_control is known outside the registry
    assert HANDLED_PLUGINS.isdisjoint(PLUGINS)


def test_every_publisher_named_is_a_factory_of_the_ros_layer():
    from _arm1sim.ros.plugins.sensor_plugins import publisher

    for name in PUBLISHED:
        assert callable(publisher(name)), name
    for name in MIMIC_PLUGINS:  # a mimic joint publishes nothing
        assert publisher(name) is None


@pytest.mark.parametrize(
    'bad, message',
    [
        (PluginType('', built_by='x'), 'needs a file name'),
        (PluginType(CAMERA_PLUGIN, built_by='x'), 'registered twice'),
        (PluginType('libnew.so'), 'give one of'),
        (PluginType('libnew.so', built_by='x', build_model=lambda *a: None), 'give one of'),
    ],
)
def test_a_type_without_a_name_taken_twice_or_built_two_ways_is_refused(bad, message):
    with pytest.raises(ValueError, match=message):
        register(bad)
    assert 'libnew.so' not in PLUGINS
