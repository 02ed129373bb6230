"""What the state-sensor unit tests share: a world with or without a ground plane, URDF
pieces, and sensors that report every reading into a list."""

from __future__ import annotations

from typing import Any, Dict, List, Tuple

from _arm1sim.description.sdf_world import Shape, StaticModel, WorldConfig
from _arm1sim.sim.simulation import Model, Simulation

G = 9.8


def world(ground: bool = True, gravity: Tuple[float, float, float] = (0.0, 0.0, -G)) -> Simulation:
    models = [StaticModel('ground_plane', (0, 0, 0, 0, 0, 0), [Shape('plane', (0, 0, 1))])]
    return Simulation(WorldConfig(gravity=gravity, models=models if ground else []))


def inertial(mass: float, xyz: str = '0 0 0', i: float = 0.01) -> str:
    return (
        '<inertial><origin xyz="%s"/><mass value="%g"/>'
        '<inertia ixx="%g" ixy="0" ixz="0" iyy="%g" iyz="0" izz="%g"/></inertial>'
        % (xyz, mass, i, i, i)
    )


def box(name: str, mass: float = 1.0, size: float = 0.2) -> str:
    i = mass * size * size / 6
    return (
        '<link name="%s">%s<collision><geometry><box size="%g %g %g"/></geometry></collision>'
        '</link>' % (name, inertial(mass, i=i), size, size, size)
    )


def robot(body: str, gazebo: str = '', name: str = 'r') -> str:
    return '<robot name="%s">%s%s</robot>' % (name, body, gazebo)


def listen(model: Model) -> Dict[str, List[Tuple[int, Any]]]:
    """Every sensor of the model wanted, its readings by sensor name."""
    got: Dict[str, List[Tuple[int, Any]]] = {}
    for sensor in model.sensors:
        readings = got.setdefault(sensor.name, [])
        sensor.wanted = lambda: True
        sensor.deliver = lambda t, r, readings=readings: readings.append((t, r))
    return got


def steps(sim: Simulation, n: int) -> None:
    for _ in range(n):
        sim.step()
