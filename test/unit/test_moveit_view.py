"""ros/web/moveit_view.py: the planning scene's objects and the ghost of a planned path, as
the browser view draws them (a recording stand-in for viser's scene; no master)."""

import pytest
from moveit_msgs.msg import CollisionObject, DisplayTrajectory, PlanningScene, RobotTrajectory
from shape_msgs.msg import SolidPrimitive
from trajectory_msgs.msg import JointTrajectoryPoint

from _arm1sim.ros.web import moveit_view
from _arm1sim.ros.web.web_snapshot import ModelView, Visual
from _arm1sim.ros.web.web_view import MeshCache


class Handle:
    def __init__(self, name, kw):
        self.name, self.kw, self.removed = name, kw, False

    def remove(self):
        self.removed = True


class Scene:
    def __init__(self):
        self.added = []

    def add_mesh_simple(self, name, vertices, faces, **kw):
        h = Handle(name, dict(kw, vertices=vertices))
        self.added.append(h)
        return h


class View:
    def __init__(self, visuals=()):
        self.server = type('Server', (), {})()
        self.server.scene = Scene()
        self.meshes = MeshCache()
        self.models = {'robot': type('SceneModel', (), {'visuals': list(visuals)})()}


def layer(view):
    mv = moveit_view.MoveItView.__new__(moveit_view.MoveItView)
    mv.view = view
    mv._handles = {'objects': [], 'ghost': []}
    return mv


def test_waypoints_spread_over_the_path_first_and_last_included():
    assert moveit_view.ghost_waypoints(5, 14) == [0, 3, 6, 10, 13]
    assert moveit_view.ghost_waypoints(5, 3) == [0, 1, 2]
    assert moveit_view.ghost_waypoints(5, 0) == []


def test_a_box_without_shape_poses_is_drawn_at_its_object_pose_and_replaced():
    view = View()
    mv = layer(view)
    scene = PlanningScene()
    box = CollisionObject(id='box', operation=CollisionObject.ADD)
    box.pose.position.x, box.pose.position.y, box.pose.position.z = 0.4, 0.1, 0.2
    box.pose.orientation.w = 1.0
    box.primitives = [SolidPrimitive(type=SolidPrimitive.BOX, dimensions=[0.1, 0.2, 0.3])]
    scene.world.collision_objects = [box]
    mv._draw_objects(scene)
    (h,) = view.server.scene.added
    assert h.name == '/moveit/objects/box/0'
    assert h.kw['position'] == pytest.approx((0.4, 0.1, 0.2))
    extent = h.kw['vertices'].max(axis=0) - h.kw['vertices'].min(axis=0)
    assert extent == pytest.approx([0.1, 0.2, 0.3])
    assert h.kw['color'] == moveit_view.OBJECT_RGB
    mv._clear('objects')
    assert h.removed and mv._handles['objects'] == []


def test_the_ghost_is_the_robots_visuals_at_waypoint_poses_from_fk():
    # two links (base, arm) with one box visual on the arm, 0.1 above its frame
    visuals = [Visual(0, 'box', (0.1, 0.1, 0.1), '', ((0, 0, 0.1), (0, 0, 0, 1)), (1, 1, 1, 1))]
    view = View(visuals)
    mv = layer(view)
    asked = []

    def fk(links, robot_state):
        q = dict(zip(robot_state.joint_state.name, robot_state.joint_state.position))['j']
        asked.append(q)
        return {'arm': ((q, 0.0, 0.5), (0.0, 0.0, 0.0, 1.0))}

    mv._fk_poses = fk
    model = ModelView('robot', 1, ('base', 'arm'), (), '', ())
    display = DisplayTrajectory(model_id='six_arm')
    display.trajectory_start.joint_state.name = ['j']
    display.trajectory_start.joint_state.position = [0.0]
    part = RobotTrajectory()
    part.joint_trajectory.joint_names = ['j']
    part.joint_trajectory.points = [JointTrajectoryPoint(positions=[i / 10]) for i in range(11)]
    display.trajectory = [part]
    mv._draw_ghost(display, {'robot': model})
    assert asked == pytest.approx([0.0, 0.2, 0.5, 0.8, 1.0])
    positions = [c for h in view.server.scene.added for c in h.kw['position']]
    assert positions == pytest.approx([c for q in asked for c in (q, 0.0, 0.6)])
    assert all(h.kw['opacity'] == moveit_view.GHOST_OPACITY for h in view.server.scene.added)
