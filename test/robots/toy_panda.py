#!/usr/bin/env python3
"""A seven-joint arm with a two-finger hand, described as franka_description describes a
Panda for Gazebo (written here, primitives only): every arm joint with an effort, a position
and a velocity SimpleTransmission, franka_hw's FrankaStateInterface and FrankaModelInterface
transmissions, effort fingers, and gazebo_ros_control with robotSimType
franka_gazebo/FrankaHWSim. Its link lengths are of the Panda's order; masses are round.

    toy_panda.py [ARM_ID]     the URDF on stdout (default arm_id: toy)
"""

import sys
from typing import List

# joint: (parent offset xyz, axis, lower, upper, effort, velocity); link masses after
ARM = [
    ((0, 0, 0.333), (0, 0, 1), -2.8973, 2.8973, 87, 2.175),
    ((0, 0, 0), (0, 1, 0), -1.7628, 1.7628, 87, 2.175),
    ((0, 0, 0.316), (0, 0, 1), -2.8973, 2.8973, 87, 2.175),
    ((0.0825, 0, 0), (0, -1, 0), -3.0718, -0.0698, 87, 2.175),
    ((-0.0825, 0, 0.384), (0, 0, 1), -2.8973, 2.8973, 12, 2.61),
    ((0, 0, 0), (0, -1, 0), -0.0175, 3.7525, 12, 2.61),
    ((0.088, 0, 0), (0, 0, -1), -2.8973, 2.8973, 12, 2.61),
]
MASSES = [3.0, 3.0, 2.5, 2.5, 2.0, 1.5, 0.5]
LENGTHS = [0.05, 0.316, 0.05, 0.384, 0.05, 0.05, 0.05]  # each link's body along z
INTERFACES = ('PositionJointInterface', 'VelocityJointInterface', 'EffortJointInterface')


def _link(name: str, mass: float, length: float, radius: float = 0.06) -> str:
    ixx = mass * (3 * radius**2 + length**2) / 12
    izz = mass * radius**2 / 2
    shape = '<cylinder radius="%g" length="%g"/>' % (radius, length)
    origin = '<origin xyz="0 0 %g"/>' % (length / 2)
    return (
        '<link name="{n}"><inertial>{o}<mass value="{m}"/>'
        '<inertia ixx="{i}" iyy="{i}" izz="{z}" ixy="0" ixz="0" iyz="0"/></inertial>'
        '<visual>{o}<geometry>{s}</geometry></visual>'
        '<collision>{o}<geometry>{s}</geometry></collision></link>'
    ).format(n=name, o=origin, m=mass, i=ixx, z=izz, s=shape)


def _transmission(joint: str, interface: str) -> str:
    return (
        '<transmission name="{j}_{i}"><type>transmission_interface/SimpleTransmission</type>'
        '<joint name="{j}"><hardwareInterface>hardware_interface/{i}</hardwareInterface></joint>'
        '<actuator name="{j}_motor"><hardwareInterface>hardware_interface/{i}'
        '</hardwareInterface></actuator></transmission>'
    ).format(j=joint, i=interface)


def urdf(arm_id: str = 'toy') -> str:
    parts: List[str] = ['<?xml version="1.0"?>', '<robot name="%s">' % arm_id]
    parts.append('<link name="world"/>')
    parts.append(_link(arm_id + '_link0', 4.0, 0.1, 0.06))
    parts.append(
        '<joint name="world_joint" type="fixed"><parent link="world"/>'
        '<child link="%s_link0"/></joint>' % arm_id
    )
    for i, ((x, y, z), axis, lower, upper, effort, velocity) in enumerate(ARM, start=1):
        parts.append(_link('%s_link%d' % (arm_id, i), MASSES[i - 1], LENGTHS[i - 1]))
        parts.append(
            '<joint name="{a}_joint{i}" type="revolute"><parent link="{a}_link{p}"/>'
            '<child link="{a}_link{i}"/><origin xyz="{x} {y} {z}"/>'
            '<axis xyz="{ax} {ay} {az}"/><dynamics damping="0.0"/>'
            '<limit lower="{lo}" upper="{up}" effort="{e}" velocity="{v}"/></joint>'.format(
                a=arm_id,
                i=i,
                p=i - 1,
                x=x,
                y=y,
                z=z,
                ax=axis[0],
                ay=axis[1],
                az=axis[2],
                lo=lower,
                up=upper,
                e=effort,
                v=velocity,
            )
        )
    # The flange (link8), the hand on it and two fingers, as franka_description names them.
    parts.append('<link name="%s_link8"/>' % arm_id)
    parts.append(
        '<joint name="{a}_joint8" type="fixed"><parent link="{a}_link7"/><child link="{a}_link8"/>'
        '<origin xyz="0 0 -0.107"/></joint>'.format(a=arm_id)
    )
    parts.append(_link(arm_id + '_hand', 0.73, 0.06, 0.1))
    parts.append(
        '<joint name="{a}_hand_joint" type="fixed"><parent link="{a}_link8"/>'
        '<child link="{a}_hand"/><origin xyz="0 0 0" rpy="3.14159265 0 0"/></joint>'.format(
            a=arm_id
        )
    )
    for n, sign in ((1, 1), (2, -1)):
        finger = '%s_%sfinger' % (arm_id, 'left' if n == 1 else 'right')
        parts.append(
            '<link name="{f}"><inertial><mass value="0.015"/><inertia ixx="2.4e-6" iyy="2.4e-6" '
            'izz="1e-6" ixy="0" ixz="0" iyz="0"/></inertial><collision><origin xyz="0 {y} 0.03"/>'
            '<geometry><box size="0.02 0.01 0.04"/></geometry></collision></link>'.format(
                f=finger, y=sign * 0.005
            )
        )
        parts.append(
            '<joint name="{a}_finger_joint{n}" type="prismatic"><parent link="{a}_hand"/>'
            '<child link="{f}"/><origin xyz="0 0 0.0584"/><axis xyz="0 {s} 0"/>'
            '<limit lower="0" upper="0.04" effort="100" velocity="0.2"/><dynamics damping="0.3"/>'
            '</joint>'.format(a=arm_id, f=finger, n=n, s=sign)
        )
        parts.append(_transmission('%s_finger_joint%d' % (arm_id, n), 'EffortJointInterface'))
    for interface in INTERFACES:
        for i in range(1, 8):
            parts.append(_transmission('%s_joint%d' % (arm_id, i), interface))
    state = ''.join(
        '<joint name="{a}_joint{i}"><hardwareInterface>franka_hw/FrankaStateInterface'
        '</hardwareInterface></joint>'.format(a=arm_id, i=i)
        for i in range(1, 8)
    )
    parts.append(
        '<transmission name="%s_franka_state"><type>franka_hw/FrankaStateInterface</type>%s'
        '</transmission>' % (arm_id, state)
    )
    parts.append(
        '<transmission name="{a}_franka_model"><type>franka_hw/FrankaModelInterface</type>'
        '<joint name="{a}_joint1"><role>root</role><hardwareInterface>'
        'franka_hw/FrankaModelInterface</hardwareInterface></joint>'
        '<joint name="{a}_joint8"><role>tip</role><hardwareInterface>'
        'franka_hw/FrankaModelInterface</hardwareInterface></joint></transmission>'.format(a=arm_id)
    )
    parts.append(
        '<gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so">'
        '<controlPeriod>0.001</controlPeriod><robotSimType>franka_gazebo/FrankaHWSim'
        '</robotSimType></plugin></gazebo>'
    )
    parts.append('</robot>')
    return '\n'.join(parts) + '\n'


if __name__ == '__main__':
    sys.stdout.write(urdf(sys.argv[1] if len(sys.argv) > 1 else 'toy'))
