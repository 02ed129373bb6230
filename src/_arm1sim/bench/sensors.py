"""What one laser scan costs: rrbot's hokuyo (720 rays over 180 degrees, 0.1..30 m, gaussian
noise) on a mast in a room of four walls, measured as the world measures it, in one process
(no master needed).

Parts: the ray cast (pose, one rayTestBatch) with the ranges' masking and noise, which run on
the physics thread at each update instant while someone subscribes; then the LaserScan built
and serialized, as rospy does for a subscriber. The sum is what a subscribed laser adds to
the physics thread per scan.
"""

from __future__ import annotations

import io
from typing import Any, Dict

from ..description.sdf_world import WorldConfig
from ..physics.laser import Laser
from ..sim.simulation import Simulation
from .probes import median_ms

RAY = """<ray><scan><horizontal><samples>%d</samples><resolution>1</resolution>
  <min_angle>-1.570796</min_angle><max_angle>1.570796</max_angle></horizontal></scan>
  <range><min>0.10</min><max>30.0</max><resolution>0.01</resolution></range>
  <noise><type>gaussian</type><mean>0.0</mean><stddev>0.01</stddev></noise></ray>"""

MAST = """<robot name="mast"><link name="world"/>
  <link name="mast">
    <inertial><origin xyz="0 0 0.5"/><mass value="1"/>
      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.001"/></inertial>
    <collision><origin xyz="0 0 0.5"/><geometry><box size="0.05 0.05 1"/></geometry></collision>
  </link>
  <joint name="fix" type="fixed"><parent link="world"/><child link="mast"/>
    <origin xyz="0 0 0"/></joint>
  <link name="hokuyo_link">
    <inertial><mass value="0.1"/>
      <inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
  <joint name="head" type="fixed"><parent link="mast"/><child link="hokuyo_link"/>
    <origin xyz="0 0 1.05"/></joint>
  <gazebo reference="hokuyo_link">
    <sensor type="gpu_ray" name="hokuyo"><update_rate>40</update_rate>%s
      <plugin name="laser" filename="libgazebo_ros_gpu_laser.so">
        <topicName>/mast/laser/scan</topicName><frameName>hokuyo_link</frameName>
      </plugin>
    </sensor>
  </gazebo>
</robot>"""

WALL = """<robot name="%s"><link name="world"/>
  <link name="wall">
    <inertial><mass value="10"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
    <collision><geometry><box size="%s"/></geometry></collision>
  </link>
  <joint name="fix" type="fixed"><parent link="world"/><child link="wall"/>
    <origin xyz="%s 1"/></joint>
</robot>"""
# a 6 x 8 m room around the mast, its back wall behind the scan (which covers the front half)
WALLS = [
    ('front', '0.2 8 2', '3 0'),
    ('left', '6 0.2 2', '0 4'),
    ('right', '6 0.2 2', '0 -4'),
    ('back', '0.2 8 2', '-3 0'),
]


def laser_scan(count: int = 200, rays: int = 720) -> Dict[str, Any]:
    """Median milliseconds over ``count`` scans of each part, and their sum."""
    from ..ros.plugins.laser_plugin import laser_message

    sim = Simulation(WorldConfig())
    try:
        for name, size, xy in WALLS:
            sim.spawn_urdf(name, WALL % (name, size, xy))
        (laser,) = sim.spawn_urdf('mast', MAST % (RAY % rays)).sensors
        assert isinstance(laser, Laser)
        sim.step()
        reading = laser.measure(sim.time_ns)
        finite = int((abs(reading.ranges) < 1e9).sum())
        cast_ms = median_ms(lambda: laser.measure(sim.time_ns), count)

        def message() -> None:
            laser_message(sim.time_ns, 'hokuyo_link', laser, reading).serialize(io.BytesIO())

        message_ms = median_ms(message, count)
    finally:
        sim.close()
    return {
        'scan_ms': cast_ms + message_ms,
        'cast_ms': cast_ms,
        'message_ms': message_ms,
        'rays': rays,
        'hits': finite,  # rays that met a wall (a check that the room is there)
    }
