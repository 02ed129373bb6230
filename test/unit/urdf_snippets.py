"""URDF and SDF pieces for hostile-description tests, ROS-free: shared by the unit tests and the
rostests (test/test_faults_sensors.py puts test/unit on its path)."""

LINK = (
    '<link name="{n}"><inertial><mass value="{m}"/>'
    '<inertia ixx="{i}" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>'
    '<collision><geometry><box size="0.05 0.05 0.05"/></geometry></collision></link>'
)


def link(name, mass='0.1', ixx='1e-4'):
    """A 5 cm box link of ``mass`` (text, so that tests can pass 'nan' and the like)."""
    return LINK.format(n=name, m=mass, i=ixx)


def joint(name, parent, child, kind='fixed'):
    """A joint 6 cm above its parent, about z; a revolute one limited to ±1 rad."""
    limit = '<limit lower="-1" upper="1" effort="1" velocity="1"/>' if kind == 'revolute' else ''
    return (
        '<joint name="%s" type="%s"><parent link="%s"/><child link="%s"/>'
        '<origin xyz="0 0 0.06"/><axis xyz="0 0 1"/>%s</joint>' % (name, kind, parent, child, limit)
    )


def sdf_tower(n):
    """An SDF model of ``n`` stacked box links joined by revolute joints, as one line."""
    links = ''.join(
        '<link name="l%d"><pose>0 0 %g 0 0 0</pose><collision name="c"><geometry><box>'
        '<size>0.1 0.1 0.1</size></box></geometry></collision></link>' % (i, 0.2 * i)
        for i in range(n)
    )
    joints = ''.join(
        '<joint name="j%d" type="revolute"><parent>l%d</parent><child>l%d</child>'
        '<axis><xyz>0 0 1</xyz></axis></joint>' % (i, i - 1, i)
        for i in range(1, n)
    )
    return '<sdf version="1.6"><model name="m">%s%s</model></sdf>' % (links, joints)
