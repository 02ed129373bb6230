"""The control plugin's namespace as Gazebo picks it: the plugin's <robotNamespace>, else the
one spawn_model sends (its caller's, '/' at top level), else the model name."""

import pytest
from conftest import box_link, control_plugin, transmission

from _arm1sim.description.sdf_world import WorldConfig
from _arm1sim.ros.tools.spawn_model import parse_args
from _arm1sim.sim.simulation import Simulation

JOINT = """
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="5" velocity="1"/></joint>"""


def robot(namespace):
    return (
        '<robot name="nb"><link name="world"/>'
        '<joint name="w" type="fixed"><parent link="world"/><child link="base"/></joint>'
        + box_link('base')
        + box_link('arm')
        + JOINT
        + transmission('j')
        + control_plugin(namespace)
        + '</robot>'
    )


@pytest.mark.parametrize(
    'plugin_ns, request_ns, expected',
    [
        (None, '/', '/'),  # spawn_model's default at top level: /controller_manager
        (None, '/ur', '/ur'),  # a spawn_model started in namespace /ur
        (None, '', '/nb'),  # a direct service call with no namespace: the model name
        ('/mine', '/', '/mine'),  # the plugin's own value wins over the request's
        ('', '/ur', '/'),  # an empty <robotNamespace/> is the root, whatever the request
        ('', '', '/'),  # ... and not the model name either
    ],
)
def test_namespace_of_the_controller_manager(plugin_ns, request_ns, expected):
    sim = Simulation(WorldConfig())
    try:
        made = []
        model = sim.spawn_urdf(
            'nb',
            robot(plugin_ns),
            robot_namespace=request_ns,
            controller_manager_factory=lambda hw, ns: made.append(ns),
        )
        assert model.namespace == expected
        assert made == [expected]
    finally:
        sim.close()


def test_spawn_model_leaves_the_namespace_to_the_caller_by_default():
    # None means "the caller's namespace" (rospy.get_namespace() once the node is up).
    assert parse_args(['-urdf', '-file', 'x.urdf', '-model', 'm']).robot_namespace is None
    given = parse_args(['-urdf', '-file', 'x', '-model', 'm', '-robot_namespace', '/a'])
    assert given.robot_namespace == '/a'


CAMERA_BOX = (
    '<robot name="cam">'
    + box_link('body')
    + '<gazebo reference="body"><sensor type="camera" name="eye"><update_rate>1</update_rate>'
    '<camera><image><width>8</width><height>8</height></image></camera>'
    '<plugin filename="libgazebo_ros_camera.so"><cameraName>eye</cameraName>%s</plugin>'
    '</sensor></gazebo></robot>'
)


@pytest.mark.parametrize(
    'own, request_ns, expected',
    [
        ('', '/ur', '/ur/eye/image_raw'),  # none of its own: the request's goes in
        ('', '/', '/eye/image_raw'),  # spawn_model's top-level default
        ('<robotNamespace>/mine</robotNamespace>', '/ur', '/mine/eye/image_raw'),  # its own wins
    ],
)
def test_camera_plugin_gets_the_request_namespace_when_it_has_none(own, request_ns, expected):
    sim = Simulation(WorldConfig())
    try:
        model = sim.spawn_urdf('cam', CAMERA_BOX % own, robot_namespace=request_ns)
        assert [c.sensor.image_topic for c in model.cameras] == [expected]
    finally:
        sim.close()
