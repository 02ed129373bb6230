"""The control plugin's namespace as Gazebo picks it: the plugin's <robotNamespace>, else the
one spawn_model sends (its caller's, '/' at top level), else the model name."""

import pytest
from conftest import box_link, control_plugin, transmission

from arm1.description.sdf_world import WorldConfig
from arm1.ros.spawn_model import parse_args
from arm1.sim.simulation import Simulation

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
