"""URDF <mimic> joints and roboticsgroup's mimic joint plugin: parsed into (follower, leader,
multiplier, offset), and followed in real pybullet physics."""

import os

import pytest
from conftest import REPO_ROOT, WORLD_FILE

from _arm1sim.description.sdf_world import read_world
from _arm1sim.description.urdf_model import UrdfError, parse_urdf
from _arm1sim.sim.simulation import Simulation

GRIPPER = os.path.join(REPO_ROOT, 'test', 'config', 'gripper_bot.urdf')

TWO_ARMS = """<robot name="two">
  <link name="world"/><link name="base"/><link name="a"/><link name="b"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <joint name="lead" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="5" velocity="1"/></joint>
  <joint name="follow" type="revolute"><parent link="base"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="5" velocity="1"/>%s</joint>
  %s
</robot>"""

PLUGIN = """<gazebo><plugin name="m" filename="%s">
    <joint>lead</joint><mimicJoint>follow</mimicJoint><multiplier>0.5</multiplier>
    <offset>0.2</offset><maxEffort>3</maxEffort><sensitiveness>0.01</sensitiveness>
  </plugin></gazebo>"""


def urdf(mimic='', plugin=''):
    return TWO_ARMS.replace('<link name="a"/>', _link('a')).replace(
        '<link name="b"/>', _link('b')
    ) % (mimic, plugin)


def _link(name):
    return (
        '<link name="%s"><inertial><origin xyz="0.1 0 0"/><mass value="0.1"/><inertia ixx="1e-4" '
        'ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial></link>' % name
    )


def test_urdf_mimic_is_read_with_its_multiplier_and_offset():
    model = parse_urdf(urdf('<mimic joint="lead" multiplier="-2" offset="0.3"/>'))
    (m,) = model.mimics
    assert (m.follower, m.leader, m.multiplier, m.offset, m.max_effort) == (
        'follow',
        'lead',
        -2.0,
        0.3,
        None,
    )


def test_mimic_defaults_are_multiplier_one_offset_zero():
    (m,) = parse_urdf(urdf('<mimic joint="lead"/>')).mimics
    assert (m.multiplier, m.offset) == (1.0, 0.0)


@pytest.mark.parametrize(
    'filename',
    [
        'libroboticsgroup_upatras_gazebo_mimic_joint_plugin.so',
        'libroboticsgroup_gazebo_mimic_joint_plugin.so',
    ],
)
def test_roboticsgroup_plugin_is_read_as_a_mimic(filename):
    (m,) = parse_urdf(urdf(plugin=PLUGIN % filename)).mimics
    assert (m.follower, m.leader, m.multiplier, m.offset, m.max_effort, m.sensitiveness) == (
        'follow',
        'lead',
        0.5,
        0.2,
        3.0,
        0.01,
    )


def test_a_mimic_of_an_unknown_joint_names_it():
    with pytest.raises(UrdfError, match="leader 'nope'"):
        parse_urdf(urdf('<mimic joint="nope"/>'))


def test_a_non_numeric_multiplier_names_the_joint():
    with pytest.raises(UrdfError, match="joint 'follow' <mimic>"):
        parse_urdf(urdf('<mimic joint="lead" multiplier="x"/>'))


@pytest.fixture
def sim():
    s = Simulation(read_world(WORLD_FILE))
    yield s
    s.close()


def positions(model, names):
    return [pos for pos, _ in model.robot.read(model.robot.indices(names))]


def test_a_mimic_joint_follows_its_leader_times_multiplier_plus_offset(sim):
    model = sim.spawn_urdf('two', urdf('<mimic joint="lead" multiplier="-0.5" offset="0.3"/>'))
    model.robot.set_joint_positions({'lead': 1.0})
    for _ in range(500):
        sim.step()
    lead, follow = positions(model, ['lead', 'follow'])
    assert follow == pytest.approx(lead * -0.5 + 0.3, abs=1e-3)


def test_a_plugin_mimic_follows_a_moving_leader(sim):
    model = sim.spawn_urdf(
        'two', urdf(plugin=PLUGIN % 'libroboticsgroup_gazebo_mimic_joint_plugin.so')
    )
    i = model.robot.indices(['lead'])
    for k in range(1000):  # the leader sweeps at 1 rad/s
        model.robot.set_velocity_motors(i, [1.0], [50.0])
        sim.step()
    lead, follow = positions(model, ['lead', 'follow'])
    assert lead == pytest.approx(1.0, abs=0.05)
    assert follow == pytest.approx(lead * 0.5 + 0.2, abs=0.02)


def test_gripper_mimic_finger_mirrors_the_leader(sim):
    with open(GRIPPER) as f:
        model = sim.spawn_urdf('gripper', f.read())
    model.robot.set_joint_positions({'left_finger_joint': 0.03})
    for _ in range(300):
        sim.step()
    left, right = positions(model, ['left_finger_joint', 'right_finger_joint'])
    assert right == pytest.approx(-left, abs=1e-3)
    assert left > 0.02  # the leader was not dragged back by the follower's motor


# ------------------------------------------------ a follower on the leader's own child link
# lead turns link a about z at the origin; follow turns link b about z at 0.1 m along a, b's
# centre of mass on its axis (no swing of b's mass can turn a), b a 6 cm bar along a's y.
CHAIN = """<robot name="chain"><link name="world"/>
  <link name="base"><inertial><mass value="1"/>
    <inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial></link>
  <link name="a"><inertial><origin xyz="0.05 0 0"/><mass value="0.1"/>
    <inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial></link>
  <link name="b"><inertial><mass value="0.05"/>
    <inertia ixx="2e-5" ixy="0" ixz="0" iyy="2e-5" iyz="0" izz="2e-5"/></inertial>
    <collision><origin xyz="0.03 0 0"/><geometry><box size="0.06 0.01 0.01"/></geometry>
    </collision></link>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <joint name="lead" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="%(lead_effort)s" velocity="2"/></joint>
  <joint name="follow" type="revolute"><parent link="a"/><child link="b"/>
    <origin xyz="0.1 0 0" rpy="0 0 1.5708"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="%(follow_effort)s" velocity="2"/>
    <mimic joint="lead" offset="%(offset)s"/></joint>
</robot>"""


@pytest.fixture
def bare():
    """A bare pybullet client without gravity: nothing but the joints' own forces."""
    import pybullet as pb

    cid = pb.connect(pb.DIRECT)
    pb.setTimeStep(0.001, physicsClientId=cid)
    pb.setGravity(0, 0, 0, physicsClientId=cid)
    yield cid
    pb.disconnect(cid)


def chain_robot(client, tmp_path, lead_effort=1.0, follow_effort=2.0, offset=0.3):
    from _arm1sim.physics.robot import Robot

    path = tmp_path / 'chain.urdf'
    path.write_text(
        CHAIN % dict(lead_effort=lead_effort, follow_effort=follow_effort, offset=offset)
    )
    robot = Robot(client, str(path), fixed_base=True)
    robot.set_mimics([('follow', 'lead', 1.0, offset, follow_effort, 0.0)])
    return robot


def step_chain(client, robot, steps, lead_torque=None):
    """``lead_torque(position, velocity)``: the leader's controller, None for a free joint."""
    import pybullet as pb

    lead = robot.joint_index['lead']
    for _ in range(steps):
        if lead_torque is not None:
            q, v = pb.getJointState(robot.body, lead, physicsClientId=client)[:2]
            robot.apply_efforts([lead], [lead_torque(q, v)])
        robot.follow_mimics()
        pb.stepSimulation(physicsClientId=client)
        robot.measure_mimics()
    return [pos for pos, _ in robot.read(robot.indices(['lead', 'follow']))]


def test_a_follower_on_the_leaders_child_puts_no_torque_into_a_free_leader(bare, tmp_path):
    robot = chain_robot(bare, tmp_path)
    lead, follow = step_chain(bare, robot, 500)
    assert follow == pytest.approx(0.3, abs=1e-3)  # from 0 to leader + offset
    assert lead == pytest.approx(0.0, abs=1e-4)  # the free leader did not turn back


def test_without_handing_on_the_reaction_the_free_leader_would_turn(bare, tmp_path):
    """The test above can fail: the motor's reaction alone turns a free leader visibly."""
    robot = chain_robot(bare, tmp_path)
    robot.mimics[0].reroute = None
    lead, _ = step_chain(bare, robot, 500)
    assert lead < -5e-3


def _pushing_on_a_post(client, robot, reroute=True):
    """b turns toward a static post (a's leader held at 0 by a weak PD, 0.5 N m at most)
    and is stopped there: returns (leader position, follower position, motor effort)."""
    import pybullet as pb

    if not reroute:
        robot.mimics[0].reroute = None
    post = pb.createCollisionShape(
        pb.GEOM_BOX, halfExtents=[0.005, 0.04, 0.02], physicsClientId=client
    )
    pb.createMultiBody(0, post, -1, [0.065, 0.05, 0], physicsClientId=client)

    def pd(q, v):
        return max(-0.5, min(0.5, -5.0 * q - 0.1 * v))

    lead, follow = step_chain(client, robot, 2000, pd)
    effort = pb.getJointState(robot.body, robot.joint_index['follow'], physicsClientId=client)[3]
    return lead, follow, effort


def test_a_blocked_follower_pushes_with_its_effort_limit_and_the_leader_holds(bare, tmp_path):
    robot = chain_robot(bare, tmp_path, lead_effort=0.5, follow_effort=2.0, offset=0.6)
    lead, follow, effort = _pushing_on_a_post(bare, robot)
    assert follow < 0.5  # stopped by the post short of its 0.6
    assert abs(effort) == pytest.approx(2.0, rel=1e-3)  # pushing with all it has
    assert abs(lead) < 0.01  # the 0.5 N m leader was not pushed off by 2 N m
    _, velocity = robot.read(robot.indices(['lead']))[0]
    assert abs(velocity) < 1e-3


def test_without_handing_on_the_reaction_a_blocked_follower_pushes_its_leader_away(bare, tmp_path):
    robot = chain_robot(bare, tmp_path, lead_effort=0.5, follow_effort=2.0, offset=0.6)
    lead, _, effort = _pushing_on_a_post(bare, robot, reroute=False)
    assert abs(lead) > 0.05
    assert abs(effort) < 1.0


def test_the_hardware_interface_never_writes_a_mimic_follower():
    """gripper_bot's right finger has an effort transmission and a <mimic>: it is read
    (joint_states carry it) but no effort is ever written to it."""
    from conftest import FakeRobot

    from _arm1sim.sim.robot_hw_sim import DefaultRobotHWSim

    with open(GRIPPER) as f:
        model = parse_urdf(f.read())
    robot = FakeRobot(list(model.joints))
    hw = DefaultRobotHWSim(model, robot, 0.001)
    assert 'right_finger_joint' in hw.joint_names()
    robot.set('right_finger_joint', 0.02, 0.1)
    hw.read()
    assert hw.handles['right_finger_joint'].position == 0.02
    for h in hw.handles.values():
        h.command = 3.0
    hw.write()
    follower = robot.joint_index['right_finger_joint']
    ((indices, efforts),) = robot.applied
    assert follower not in indices
    assert robot.joint_index['left_finger_joint'] in indices
    assert hw.handles['right_finger_joint'].effort == 0.0


# ------------------------------------------------ a four-bar gripper (Robotiq 2F-85's kinematics)
FOURBAR = os.path.join(REPO_ROOT, 'test', 'config', 'fourbar_gripper.urdf')
FOURBAR_FOLLOWERS = {
    'left_inner_finger_joint',
    'left_inner_knuckle_joint',
    'right_outer_knuckle_joint',
    'right_inner_finger_joint',
    'right_inner_knuckle_joint',
}


def test_a_follower_declared_twice_is_one_mimic_the_plugins():
    """Gazebo classic drops a URDF <mimic> (sdformat's URDF reader has none): with both, the
    plugin is what acts. Here the plugin's multiplier and offset win over the <mimic>'s."""
    both = urdf(
        '<mimic joint="lead" multiplier="-2" offset="0.3"/>',
        PLUGIN % 'libroboticsgroup_gazebo_mimic_joint_plugin.so',
    )
    (m,) = parse_urdf(both).mimics
    assert (m.multiplier, m.offset, m.max_effort) == (0.5, 0.2, 3.0)


def test_the_fourbars_five_followers_push_with_their_effort_limit():
    """Declared by <mimic> and by the plugin without <maxEffort>: the plugin's default, the
    follower's effort limit (Joint::GetEffortLimit), caps each."""
    from _arm1sim.sim.simulation import mimic_links

    with open(FOURBAR) as f:
        model = parse_urdf(f.read())
    assert {m.follower for m in model.mimics} == FOURBAR_FOLLOWERS
    assert {(m.leader, m.multiplier, m.offset, m.max_effort) for m in model.mimics} == {
        ('drive_joint', 1.0, 0.0, None)
    }
    assert {force for _, _, _, _, force, _ in mimic_links(model)} == {100.0}


def test_the_fourbar_closes_on_a_box_and_its_leader_holds_still(sim):
    """Followers on the base, on the leader's child and on a follower's child, a PD leader
    (p 10, d 0.1, 10 N m at most) closing in 0.5 s past a 5 cm box: the pads stop on it, every
    follower keeps the leader's angle, and the leader does not run away."""
    with open(FOURBAR) as f:
        model = sim.spawn_urdf('fourbar', f.read())
    box = (
        '<robot name="box"><link name="box"><inertial><mass value="0.1"/><inertia ixx="4e-5" '
        'ixy="0" ixz="0" iyy="4e-5" iyz="0" izz="4e-5"/></inertial><collision><geometry>'
        '<box size="0.05 0.05 0.05"/></geometry></collision></link></robot>'
    )
    sim.spawn_urdf('box', box, position=(0, 0, 0.026))
    robot = model.robot
    drive, lift = robot.indices(['drive_joint', 'lift_joint'])
    fastest = 0.0
    for k in range(1500):
        (q, v), (z, vz) = robot.read([drive, lift])
        fastest = max(fastest, abs(v))
        goal = min(0.4, k * 0.0008)  # reached in 0.5 s, as a trajectory would
        effort = max(-10.0, min(10.0, 10.0 * (goal - q) - 0.1 * v))
        robot.apply_efforts([drive, lift], [effort, 3000.0 * -z - 100.0 * vz + 7.0])
        sim.step()
    names = ['drive_joint'] + sorted(FOURBAR_FOLLOWERS)
    lead, *followers = positions(model, names)
    assert lead == pytest.approx(0.353, abs=0.005)  # on the box, short of the goal's 0.4
    assert followers == pytest.approx([lead] * 5, abs=0.005)
    assert fastest < 3.0


PID_PLUGIN = """<gazebo>
  <plugin name="m" filename="libroboticsgroup_upatras_gazebo_mimic_joint_plugin.so">
    <joint>lead</joint><mimicJoint>follow</mimicJoint><multiplier>0.5</multiplier>
    <offset>0.2</offset>%s%s</plugin></gazebo>"""


@pytest.mark.parametrize(
    'tags, namespace',
    [
        ('<hasPID/>', '/gazebo_ros_control/pid_gains/follow'),
        (
            '<hasPID/><robotNamespace>/arm</robotNamespace>',
            '/arm/gazebo_ros_control/pid_gains/follow',
        ),
        ('<hasPID>my_gains</hasPID><robotNamespace>arm</robotNamespace>', '/arm/my_gains'),
        ('', None),
    ],
)
def test_has_pid_reads_its_gains_where_the_plugin_does(tags, namespace):
    mimic = parse_urdf(urdf(plugin=PID_PLUGIN % (tags, ''))).mimics[0]
    assert mimic.pid_gains == namespace


def pid_sim_model(sim, gains, max_effort='<maxEffort>0.05</maxEffort>'):
    from _arm1sim.sim.plugins.mimic import attach_mimic_pids

    model = sim.spawn_urdf('two', urdf(plugin=PID_PLUGIN % ('<hasPID/>', max_effort)))
    asked = []

    def params_at(namespace):
        asked.append(namespace)
        return gains

    attach_mimic_pids(model.description, model.robot, params_at, sim.period)
    assert asked == ['/gazebo_ros_control/pid_gains/follow']
    model.robot.set_joint_positions({'lead': 1.0})
    return model


def test_has_pid_drives_the_follower_with_its_gains_clamped_at_max_effort(sim):
    # target 0.7 rad; the PID (p 2, d 0.05) alone would get there in a few hundredths of
    # a second, but clamped at 0.05 N m it turns b (izz 1e-4 + 0.1 kg at 0.1 m:
    # 1.1e-3 kg m^2) at 45 rad/s^2 at most: 0.23 rad in the first 0.1 s
    model = pid_sim_model(sim, {'p': 2.0, 'd': 0.05})
    for _ in range(100):
        sim.step()
    assert 0.1 < positions(model, ['follow'])[0] < 0.23
    for _ in range(2900):
        sim.step()
    lead, follow = positions(model, ['lead', 'follow'])
    assert follow == pytest.approx(lead * 0.5 + 0.2, abs=0.01)


def test_has_pid_without_a_p_gain_leaves_the_follower_free(sim, caplog):
    model = pid_sim_model(sim, {})
    for _ in range(500):
        sim.step()
    assert positions(model, ['follow'])[0] == pytest.approx(0.0, abs=1e-3)
    assert 'No p gain specified for pid' in caplog.text


def test_pid_effort_is_clamped_and_idle_within_sensitiveness():
    from _arm1sim.physics.mimic import MimicJoint, pid_effort

    m = MimicJoint(1, 0, 1.0, 0.0, 2.0, 0.1, pid=lambda error: 100.0 * error)
    assert pid_effort(1.0, 0.0, m) == 2.0  # clamped at maxEffort
    assert pid_effort(-1.0, 0.0, m) == -2.0
    assert pid_effort(0.05, 0.0, m) == 0.0  # within sensitiveness: no effort
    assert pid_effort(0.0, 0.005, m) == 0.0
    assert pid_effort(0.3, float('nan'), m) == 0.0  # a NaN position: nothing applied
