"""Hostile descriptions that used to reach pybullet and fail there without naming the culprit
(or load with NaN in them): each is now refused by name, or loads."""

import pytest
from urdf_snippets import joint, link, sdf_tower

from _arm1sim.description.sdf_to_urdf import sdf_spawn
from _arm1sim.description.sdf_world import WorldConfig
from _arm1sim.description.urdf_model import UrdfError, parse_urdf
from _arm1sim.sim.simulation import Simulation, SpawnError


def robot(*parts):
    return '<robot name="r">%s</robot>' % ''.join(parts)


@pytest.fixture(scope='module')
def sim():
    s = Simulation(WorldConfig())
    yield s
    s.world.close()


def spawn(sim, name, urdf):
    model = sim.spawn_prepared(sim.prepare_urdf(name, urdf))
    for _ in range(20):
        sim.step()
    sim.delete_model(name)
    return model


def test_a_urdf_on_one_long_line_loads(sim):
    # pybullet reads files in line-sized chunks: a 21 kB line lost pieces mid-attribute
    n = 60
    urdf = robot(
        *[link('l%d' % i) for i in range(n)],
        *[joint('j%d' % i, 'l%d' % (i - 1), 'l%d' % i, 'revolute') for i in range(1, n)],
    )
    assert '\n' not in urdf and len(urdf) > 20000
    assert len(spawn(sim, 'one_line', urdf).robot.joint_index) == n - 1


def test_an_sdf_model_of_100_links_loads(sim):
    # sdf_model writes its URDF on one line: any model past ~50 links failed to load
    out = sdf_spawn(sdf_tower(100), 'tower')
    assert len(spawn(sim, 'tower', out.urdf).robot.joint_index) == 99


def test_a_1000_link_fixed_chain_lumps_and_loads(sim):
    n = 1000
    urdf = robot(
        *[link('l%d' % i) for i in range(n)],
        *[joint('j%d' % i, 'l%d' % (i - 1), 'l%d' % i) for i in range(1, n)],
    )
    model = spawn(sim, 'fixed_1000', urdf)
    assert model.robot.joint_index == {}


@pytest.mark.parametrize('kind', ['link', 'joint'])
def test_a_duplicate_name_is_refused_naming_it(kind):
    parts = [link('l0'), link('l1'), joint('j1', 'l0', 'l1')]
    parts.append(link('l1') if kind == 'link' else joint('j1', 'l0', 'l1'))
    with pytest.raises(
        UrdfError, match="%s '%s' is not unique" % (kind, 'l1' if kind == 'link' else 'j1')
    ):
        parse_urdf(robot(*parts))


@pytest.mark.parametrize(
    'mass, ixx, culprit',
    [
        ('nan', '1e-4', '<mass> value'),
        ('0.1', 'nan', '<inertia> ixx'),
        ('inf', '1e-4', '<mass> value'),
    ],
)
def test_a_non_finite_inertial_on_a_lumped_link_is_refused_naming_the_link(sim, mass, ixx, culprit):
    urdf = robot(link('l0'), link('l1', mass, ixx), joint('j1', 'l0', 'l1'))
    with pytest.raises(SpawnError) as info:
        sim.prepare_urdf('nan_inertia', urdf)
    assert "link 'l1' <inertial> %s" % culprit in str(info.value)
    assert 'not a finite number' in str(info.value)


def test_a_bad_number_in_a_lumped_links_gazebo_tags_is_refused_naming_that_link(sim):
    tags = '<gazebo reference="l1"><mu1>nan</mu1></gazebo>'
    urdf = robot(link('l0'), link('l1'), joint('j1', 'l0', 'l1'), tags)
    with pytest.raises(SpawnError, match=r"<gazebo reference='l1'> <mu1>: 'nan' is not a finite"):
        sim.prepare_urdf('lumped_mu', urdf)


@pytest.mark.parametrize(
    'samples, vertical, rate, charged',
    [('1000', '1000', '10', '10000000'), ('100000', '1', '0', '100000000')],
)
def test_a_laser_that_would_hold_physics_for_seconds_is_refused_naming_the_budget(
    sim, samples, vertical, rate, charged
):
    # within rays_per_laser, but cast on the physics thread at ~2 us a ray: one 1M-ray scan
    # held a step ~2 s; at 10 Hz (or every step) the world stood still for everyone
    laser = (
        '<gazebo reference="l0"><sensor type="ray" name="big"><update_rate>%s</update_rate>'
        '<ray><scan><horizontal><samples>%s</samples><min_angle>-1</min_angle>'
        '<max_angle>1</max_angle></horizontal><vertical><samples>%s</samples></vertical>'
        '</scan><range><min>0.1</min><max>10</max></range></ray>'
        '<plugin name="p" filename="libgazebo_ros_laser.so"/></sensor></gazebo>'
        % (rate, samples, vertical)
    )
    prepared = sim.prepare_urdf('big_laser', robot(link('l0'), laser))
    with pytest.raises(SpawnError) as info:
        sim.spawn_prepared(prepared)
    assert "sensor 'big' on link 'l0'" in str(info.value)
    assert 'ray casts per second is %s' % charged in str(info.value)
    assert 'big_laser' not in sim.models


@pytest.mark.parametrize(
    'geometry, culprit',
    [
        ('<box size="0.1 nan 0.1"/>', "<box size>: '0.1 nan 0.1'"),
        ('<box size="-1 0.1 0.1"/>', "<box size>: '-1 0.1 0.1'"),
        ('<cylinder radius="0.1" length="nan"/>', "<cylinder length>: 'nan'"),
        ('<sphere radius="inf"/>', "<sphere radius>: 'inf'"),
        ('<mesh filename="m.stl" scale="1 1"/>', "<mesh scale>: '1 1'"),
    ],
)
def test_a_non_finite_or_negative_shape_size_is_refused_naming_link_and_shape(geometry, culprit):
    # pybullet took them: a NaN box fell through the ground, a NaN cylinder flew off
    urdf = robot(
        '<link name="body"><collision><geometry>%s</geometry></collision></link>' % geometry
    )
    with pytest.raises(UrdfError, match="link 'body' <collision> " + culprit):
        parse_urdf(urdf)


def test_a_negative_mass_is_refused_naming_the_link():
    with pytest.raises(UrdfError, match="link 'l0' <inertial> <mass> -1 is negative"):
        parse_urdf(robot(link('l0', mass='-1')))


def test_a_mirrored_mesh_is_no_error():
    urdf = robot(
        '<link name="body"><visual><geometry><mesh filename="m.stl" scale="-1 1 1"/></geometry>'
        '</visual></link>'
    )
    assert parse_urdf(urdf).links == ['body']


def test_lasers_together_over_the_ray_budget_refuse_the_last_spawn_naming_it(sim):
    laser = (
        '<gazebo reference="l0"><sensor type="ray" name="scan"><update_rate>10</update_rate>'
        '<ray><scan><horizontal><samples>150000</samples></horizontal></scan>'
        '<range><min>0.1</min><max>10</max></range></ray>'
        '<plugin name="p" filename="libgazebo_ros_laser.so"/></sensor></gazebo>'
    )
    first = sim.spawn_prepared(sim.prepare_urdf('lidar_a', robot(link('l0'), laser)))
    try:
        with pytest.raises(SpawnError) as info:
            sim.spawn_prepared(sim.prepare_urdf('lidar_b', robot(link('l0'), laser)))
        assert "model 'lidar_b''s ray sensors with the world's others" in str(info.value)
        assert 'ray casts per second is 3000000' in str(info.value)
        assert 'lidar_b' not in sim.models
    finally:
        sim.delete_model(first.name)
    sim.delete_model(sim.spawn_prepared(sim.prepare_urdf('lidar_b', robot(link('l0'), laser))).name)


LASER_TOPIC = (
    '<gazebo reference="l0"><sensor type="ray" name="scan"><ray><scan><horizontal><samples>10'
    '</samples></horizontal></scan><range><min>0.1</min><max>10</max></range></ray>'
    '<plugin name="p" filename="libgazebo_ros_laser.so"><topicName>%s</topicName></plugin>'
    '</sensor></gazebo>'
)
DEPTH_CAMERA = (
    '<gazebo reference="l0"><sensor type="depth" name="eye"><camera><image><width>8</width>'
    '<height>6</height></image></camera><plugin name="k" filename="libgazebo_ros_openni_kinect.so">'
    '<cameraName>%s</cameraName></plugin></sensor></gazebo>'
)


@pytest.mark.parametrize(
    'extra, culprit',
    [
        (LASER_TOPIC % 'bad topic!', "topic '/bad topic!' is not a legal ROS name"),
        (LASER_TOPIC % 'scan//raw', "topic '/scan//raw' is not a legal ROS name"),
        (DEPTH_CAMERA % 'de pth', "sensor 'eye' on link 'l0': topic '/de pth/"),
    ],
)
def test_a_sensor_topic_that_is_no_legal_ros_name_is_refused_naming_it(sim, extra, culprit):
    # rospy logged FATAL, advertised nothing, and the spawn said success
    with pytest.raises(SpawnError) as info:
        sim.spawn_prepared(sim.prepare_urdf('bad_topic', robot(link('l0'), extra)))
    assert culprit in str(info.value)
    assert 'bad_topic' not in sim.models
