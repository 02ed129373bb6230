"""The seam for physics sensors: <sensor>/<plugin> parsing, the builder tables, measuring only
when wanted and due, release on delete, and the warning that names unimplemented plugins."""

import logging

import pytest
from conftest import WORLD_FILE, box_link

from _arm1sim.description.gazebo_plugins import sensor_specs, topic
from _arm1sim.description.sdf_world import read_world
from _arm1sim.description.urdf_model import UrdfError, parse_urdf
from _arm1sim.physics.sim_sensor import SimSensor
from _arm1sim.sim.plugins import PLUGINS, PluginType
from _arm1sim.sim.simulation import Simulation, SpawnError

PLUGIN = 'libarm1_test_counter.so'


def probe_urdf(rate='10', plugin=PLUGIN, extra=''):
    return """<robot name="probe">%s
  <gazebo reference="body">
    <sensor type="counter" name="tick">
      <pose>0 0 0.1 0 0 0</pose><update_rate>%s</update_rate>
      <plugin name="p" filename="%s"><topicName>ticks</topicName></plugin>
    </sensor>
  </gazebo>%s
</robot>""" % (box_link('body'), rate, plugin, extra)


class Counter(SimSensor):
    kind = 'counter'

    def measure(self, now_ns):
        return now_ns


@pytest.fixture
def registered(monkeypatch):
    built = []

    def build(model, sensor, plugin, robot, ns, limits):
        s = Counter(model, sensor.name, sensor.update_rate)
        s.topic = topic(ns, plugin.text('topicName', 'default'))
        built.append(s)
        return s

    monkeypatch.setitem(PLUGINS, PLUGIN, PluginType(PLUGIN, build_sensor=build))
    return built


@pytest.fixture
def sim():
    s = Simulation(read_world(WORLD_FILE))
    yield s
    s.close()


def test_sensor_specs_read_pose_rate_and_plugins():
    (spec,) = sensor_specs(parse_urdf(probe_urdf()))
    assert (spec.name, spec.type, spec.link) == ('tick', 'counter', 'body')
    assert spec.pose == (0, 0, 0.1, 0, 0, 0)
    assert spec.update_rate == 10
    assert spec.plugin(PLUGIN).text('topicName') == 'ticks'
    assert spec.plugin(PLUGIN).number('missing', 2.5) == 2.5


@pytest.mark.parametrize('rate', ['fast', '-1', 'nan'])
def test_a_bad_update_rate_names_the_sensor(rate):
    with pytest.raises(UrdfError, match="sensor 'tick' on link 'body'"):
        sensor_specs(parse_urdf(probe_urdf(rate)))


def test_a_sensor_is_measured_only_when_wanted_and_at_its_rate(sim, registered):
    model = sim.spawn_urdf('probe', probe_urdf(), robot_namespace='/ns')
    (sensor,) = model.sensors
    assert sensor.topic == '/ns/ticks'
    got = []
    sensor.deliver = lambda stamp, reading: got.append(stamp)
    for _ in range(500):  # 0.5 s; nobody wants it yet
        sim.step()
    assert got == []
    sensor.wanted = lambda: True
    for _ in range(1000):  # 1 s at 10 Hz
        sim.step()
    assert len(got) == 10
    assert all(b - a == 100_000_000 for a, b in zip(got, got[1:]))


def test_delete_closes_and_forgets_the_sensors(sim, registered):
    sim.spawn_urdf('probe', probe_urdf())
    (sensor,) = registered
    sim.delete_model('probe')
    assert sensor.deliver is None and not sensor.wanted()
    assert sim._sensors == []
    sim.step()


def test_a_failing_builder_fails_the_spawn_and_leaves_nothing(sim, monkeypatch):
    def build(*args):
        raise UrdfError("sensor 'tick': broken")

    monkeypatch.setitem(PLUGINS, PLUGIN, PluginType(PLUGIN, build_sensor=build))
    with pytest.raises(SpawnError, match="cannot spawn 'probe': sensor 'tick': broken"):
        sim.spawn_urdf('probe', probe_urdf())
    assert 'probe' not in sim.models and sim._sensors == []


def test_unimplemented_plugins_are_named_once_at_spawn(sim, caplog):
    extra = '<gazebo><plugin name="odd" filename="libgazebo_ros_odd.so"/></gazebo>'
    with caplog.at_level(logging.WARNING, logger='_arm1sim.physics'):
        sim.spawn_urdf('probe', probe_urdf(plugin='libgazebo_ros_nothing.so', extra=extra))
    text = [r.getMessage() for r in caplog.records]
    assert sum('libgazebo_ros_nothing.so' in t for t in text) == 1
    assert sum('libgazebo_ros_odd.so' in t for t in text) == 1
    assert all("model 'probe'" in t for t in text if 'libgazebo_ros_' in t)


@pytest.mark.parametrize(
    'element, request_ns, expected',
    [
        ('', '/', '/'),  # absent: spawn_model's namespace, as Gazebo's spawn writes it in
        ('<robotNamespace>/mine</robotNamespace>', '/', '/mine'),  # its own wins
        ('<robotNamespace/>', '/', 'probe'),  # empty: the model name (GetRobotNamespace)
    ],
)
def test_plugin_namespace_as_gazebo_plugins_read_it(sim, registered, element, request_ns, expected):
    xml = probe_urdf().replace('<topicName>', element + '<topicName>')
    model = sim.spawn_urdf('probe', xml, robot_namespace=request_ns)
    assert model.sensors[0].topic == topic(expected, 'ticks')
