"""A world file with a blank line before its <?xml?> declaration (kinova-ros's jaco.world)
loads, as Gazebo loads it (TinyXML skips leading whitespace)."""

from _arm1sim.description.sdf_world import parse_world

WORLD = '''
<?xml version="1.0" ?>
<sdf version="1.4">
  <world name="default">
    <gravity>0 0 -9.8</gravity>
    <physics type="ode"><max_step_size>0.002</max_step_size></physics>
  </world>
</sdf>
'''


def test_a_blank_line_before_the_declaration_is_no_error():
    config = parse_world(WORLD, 'jaco.world')
    assert config.max_step_size == 0.002
    assert tuple(config.gravity) == (0.0, 0.0, -9.8)
