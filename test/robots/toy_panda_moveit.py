#!/usr/bin/env python3
"""The SRDF of test/robots/toy_panda.py, as the MoveIt Setup Assistant writes one for a
Panda (panda_moveit_config's group and state names with the arm_id prefix); the other
files of its MoveIt configuration are test/config/toy_panda_moveit.yaml. Disabled
collision pairs: every pair of links adjacent in the tree (through links without
geometry) or two apart, the hand's among themselves, and the pairs in contact at the
all-zero state (the Setup Assistant's "Default").

    toy_panda_moveit.py srdf [ARM_ID]     the SRDF on stdout
"""

import sys


def srdf(arm_id: str = 'toy') -> str:
    a = arm_id
    fingers = ['%s_leftfinger' % a, '%s_rightfinger' % a]
    pairs = set()
    chain = ['%s_link%d' % (a, i) for i in range(0, 8)]
    for x, y in zip(chain, chain[1:]):
        pairs.add((x, y))
    # link8 has no geometry: link7 touches the hand through it; links two apart in the arm
    # touch at their shared joint, as the Setup Assistant finds them "never" colliding
    pairs |= {
        (chain[-1], '%s_hand' % a),
        (chain[-1], '%s_link8' % a),
        ('%s_link8' % a, '%s_hand' % a),
    }
    for x, y in zip(chain, chain[2:]):
        pairs.add((x, y))
    for f in fingers:
        pairs |= {('%s_hand' % a, f), (chain[-1], f), ('%s_link6' % a, f)}
    pairs.add((fingers[0], fingers[1]))
    pairs.add(('%s_link6' % a, '%s_hand' % a))
    # in contact at the all-zero state (the Setup Assistant's "Default" pairs)
    for x in ['%s_link7' % a, '%s_hand' % a] + fingers:
        pairs.add(('%s_link4' % a, x))
    out = ['<?xml version="1.0"?>', '<robot name="%s">' % a]
    out.append(
        '<virtual_joint name="virtual_joint" type="fixed" parent_frame="world" '
        'child_link="%s_link0"/>' % a
    )
    out.append(
        '<group name="%s_arm"><chain base_link="%s_link0" tip_link="%s_link8"/></group>' % (a, a, a)
    )
    out.append(
        '<group name="hand"><link name="{a}_hand"/><link name="{a}_leftfinger"/>'
        '<link name="{a}_rightfinger"/><joint name="{a}_finger_joint1"/>'
        '<joint name="{a}_finger_joint2"/></group>'.format(a=a)
    )
    out.append(
        '<group name="%s_arm_hand"><group name="%s_arm"/><group name="hand"/></group>' % (a, a)
    )
    ready = [0, -0.785398163, 0, -2.35619449, 0, 1.57079632679, 0.785398163397]
    extended = [0, 0, 0, -0.0698, 0, 3.14159, 0.785398163397]
    for name, values in (('ready', ready), ('extended', extended)):
        out.append(
            '<group_state name="%s" group="%s_arm">%s</group_state>'
            % (
                name,
                a,
                ''.join(
                    '<joint name="%s_joint%d" value="%s"/>' % (a, i + 1, v)
                    for i, v in enumerate(values)
                ),
            )
        )
    for name, width in (('open', '0.035'), ('close', '0')):
        out.append(
            '<group_state name="%s" group="hand">%s</group_state>'
            % (
                name,
                ''.join(
                    '<joint name="%s_finger_joint%d" value="%s"/>' % (a, n, width) for n in (1, 2)
                ),
            )
        )
    out.append(
        '<end_effector name="hand" parent_link="%s_link8" group="hand" parent_group="%s_arm"/>'
        % (a, a)
    )
    for x, y in sorted(pairs):
        out.append('<disable_collisions link1="%s" link2="%s" reason="Never"/>' % (x, y))
    out.append('</robot>')
    return '\n'.join(out) + '\n'


if __name__ == '__main__':
    if len(sys.argv) < 2 or sys.argv[1] != 'srdf':
        sys.exit(__doc__)
    sys.stdout.write(srdf(sys.argv[2] if len(sys.argv) > 2 else 'toy'))
