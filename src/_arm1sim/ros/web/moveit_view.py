"""MoveIt in the browser view (RViz's MotionPlanning display cannot exist here): the planning
scene's collision objects and a ghost of the arm along the last planned trajectory.

It listens as RViz does: ``move_group/monitored_planning_scene`` (the full scene move_group
publishes after every change) and ``move_group/display_planned_path`` (every plan, and what
a script publishes there, as the MoveIt tutorial does). The ghost is the simulated robot's
own visuals, translucent, at a few waypoints, placed by move_group's ``compute_fk`` (the
planning frame is taken as the world's, as a *_moveit_config's Gazebo launch spawns the
robot at the origin). Nothing runs while no page is open or nothing new arrived.
"""

from __future__ import annotations

import threading
from typing import Any, Dict, List, Optional, Tuple

import numpy as np
import rospy

from .web_snapshot import ModelView, Pose, Visual

GHOSTS = 5  # waypoints drawn along a trajectory, its first and last among them
GHOST_RGB = (0.35, 0.6, 1.0)
GHOST_OPACITY = 0.25
OBJECT_RGB = (0.2, 0.8, 0.3)
OBJECT_OPACITY = 0.6
ATTACHED_RGB = (0.9, 0.5, 0.1)
FK_TIMEOUT = 0.5  # s: move_group's compute_fk should answer at once


def _compose(a: Pose, b: Pose) -> Pose:
    from ...description.pose_math import multiply, rotate

    pos = tuple(x + y for x, y in zip(a[0], rotate(a[1], b[0])))
    return (pos, tuple(multiply(a[1], b[1])))  # type: ignore[return-value]


def _pose(msg: Any) -> Pose:
    p, q = msg.position, msg.orientation
    if q.x == q.y == q.z == q.w == 0.0:  # unset: the identity, as MoveIt reads it
        return ((p.x, p.y, p.z), (0.0, 0.0, 0.0, 1.0))
    return ((p.x, p.y, p.z), (q.x, q.y, q.z, q.w))


def ghost_waypoints(count: int, total: int) -> List[int]:
    """Indices of ``count`` waypoints spread over ``total``, first and last included."""
    if total <= 0:
        return []
    if total <= count:
        return list(range(total))
    return sorted({round(i * (total - 1) / (count - 1)) for i in range(count)})


class MoveItView:
    """The page's MoveIt layer; ``update`` is called by the view's thread with each frame."""

    def __init__(self, view: Any) -> None:
        from moveit_msgs.msg import DisplayTrajectory, PlanningScene

        self.view = view
        self._lock = threading.Lock()
        self._scene: Any = None
        self._trajectory: Any = None
        self._handles: Dict[str, List[Any]] = {'objects': [], 'ghost': []}
        self._fk: Any = None
        rospy.Subscriber(
            '/move_group/monitored_planning_scene', PlanningScene, self._on_scene, queue_size=1
        )
        rospy.Subscriber(
            '/move_group/display_planned_path', DisplayTrajectory, self._on_trajectory, queue_size=1
        )

    def _on_scene(self, msg: Any) -> None:
        with self._lock:
            self._scene = msg

    def _on_trajectory(self, msg: Any) -> None:
        with self._lock:
            self._trajectory = msg

    def update(self, models: Dict[str, ModelView]) -> None:
        with self._lock:
            scene, self._scene = self._scene, None
            trajectory, self._trajectory = self._trajectory, None
        if scene is not None:
            self._clear('objects')
            self._draw_objects(scene)
        if trajectory is not None:
            self._clear('ghost')
            self._draw_ghost(trajectory, models)

    def _clear(self, layer: str) -> None:
        while self._handles[layer]:
            self._handles[layer].pop().remove()

    # -- the planning scene
    def _draw_objects(self, scene: Any) -> None:
        from ..moveit.convert import shapes_of

        for obj in scene.world.collision_objects:
            self._draw_object(obj, _pose(obj.pose), OBJECT_RGB, shapes_of)
        for aco in scene.robot_state.attached_collision_objects:
            link = self._link_pose(aco.link_name, scene)
            if link is not None:
                self._draw_object(
                    aco.object, _compose(link, _pose(aco.object.pose)), ATTACHED_RGB, shapes_of
                )

    def _link_pose(self, link: str, scene: Any) -> Optional[Pose]:
        poses = self._fk_poses([link], scene.robot_state)
        return poses.get(link) if poses else None

    def _draw_object(
        self, obj: Any, origin: Pose, rgb: Tuple[float, float, float], shapes_of: Any
    ) -> None:
        try:
            shapes = shapes_of(obj)
        except ValueError as exc:
            rospy.logwarn_throttle(10, 'web view: %s', exc)
            return
        for k, shape in enumerate(shapes):
            mesh = self._mesh(shape)
            if mesh is None:
                continue
            self._add(
                'objects',
                '/moveit/objects/%s/%d' % (obj.id or 'object', k),
                mesh,
                _compose(origin, shape.pose),
                rgb,
                OBJECT_OPACITY,
            )

    def _add(
        self,
        layer: str,
        name: str,
        mesh: Any,
        pose: Pose,
        rgb: Tuple[float, float, float],
        opacity: float,
    ) -> None:
        pos, quat = pose
        self._handles[layer].append(
            self.view.server.scene.add_mesh_simple(
                name,
                np.asarray(mesh.vertices, dtype=np.float32),
                np.asarray(mesh.faces, dtype=np.uint32),
                color=rgb,
                opacity=opacity,
                position=pos,
                wxyz=(quat[3], quat[0], quat[1], quat[2]),
                flat_shading=True,
            )
        )

    @staticmethod
    def _mesh(shape: Any) -> Any:
        import trimesh

        d = shape.dimensions
        if shape.kind == 'box':
            return trimesh.creation.box(extents=d[:3])
        if shape.kind == 'sphere':
            return trimesh.creation.icosphere(subdivisions=2, radius=d[0])
        if shape.kind == 'cylinder':
            return trimesh.creation.cylinder(radius=d[1], height=d[0], sections=24)
        if shape.kind == 'cone':
            return trimesh.creation.cone(radius=d[1], height=d[0], sections=24)
        if shape.kind == 'mesh' and shape.vertices:
            return trimesh.Trimesh(vertices=shape.vertices, faces=shape.triangles, process=False)
        return None  # a plane: nothing finite to draw

    # -- the ghost
    def _robot_model(self, models: Dict[str, ModelView], model_id: str) -> Optional[ModelView]:
        if model_id in models:
            return models[model_id]
        moving = [m for m in models.values() if not m.static]  # else the one with most links
        return max(moving, key=lambda m: len(m.links), default=None)

    def _draw_ghost(self, display: Any, models: Dict[str, ModelView]) -> None:
        model = self._robot_model(models, display.model_id)
        scene_model = self.view.models.get(model.name) if model is not None else None
        visuals: List[Visual] = getattr(scene_model, 'visuals', [])
        if model is None or not visuals or not display.trajectory:
            return
        start = display.trajectory_start
        names = list(start.joint_state.name)
        values = list(start.joint_state.position)
        n = 0
        for part in display.trajectory:
            jt = part.joint_trajectory
            for i in ghost_waypoints(GHOSTS, len(jt.points)):
                state = dict(zip(names, values))
                state.update(zip(jt.joint_names, jt.points[i].positions))
                self._draw_pose(model, visuals, state, start, n)
                n += 1
            if jt.points:  # the next part starts where this one ends
                state = dict(zip(names, values))
                state.update(zip(jt.joint_names, jt.points[-1].positions))
                names, values = list(state), list(state.values())

    def _draw_pose(
        self, model: ModelView, visuals: List[Visual], state: Dict[str, float], start: Any, n: int
    ) -> None:
        import copy

        robot_state = copy.deepcopy(start)
        robot_state.joint_state.name = list(state)
        robot_state.joint_state.position = list(state.values())
        robot_state.joint_state.velocity = []
        robot_state.joint_state.effort = []
        poses = self._fk_poses(list(model.links), robot_state)
        if not poses:
            return
        for k, v in enumerate(visuals):
            if not 0 <= v.link + 1 < len(model.links):
                continue
            link_pose = poses.get(model.links[v.link + 1])
            mesh = self.view.meshes.get(v)
            if link_pose is None or mesh is None:
                continue
            self._add(
                'ghost',
                '/moveit/ghost/%d/%d' % (n, k),
                mesh,
                _compose(link_pose, v.pose),
                GHOST_RGB,
                GHOST_OPACITY,
            )

    def _fk_poses(self, links: List[str], robot_state: Any) -> Dict[str, Pose]:
        """Link poses in the planning frame from move_group's compute_fk ({} without it)."""
        from moveit_msgs.srv import GetPositionFK, GetPositionFKRequest

        if self._fk is None:
            self._fk = rospy.ServiceProxy('/compute_fk', GetPositionFK)
        known = self._known_links()
        req = GetPositionFKRequest()
        req.fk_link_names = [link for link in links if link in known]
        req.robot_state = robot_state
        try:
            self._fk.wait_for_service(FK_TIMEOUT)
            res = self._fk(req)
        except (rospy.ROSException, rospy.ServiceException) as exc:
            rospy.logwarn_throttle(30, 'web view: no ghost without compute_fk: %s', exc)
            return {}
        if res.error_code.val != 1:
            return {}
        return {name: _pose(ps.pose) for name, ps in zip(res.fk_link_names, res.pose_stamped)}

    _links: Optional[frozenset] = None

    def _known_links(self) -> frozenset:
        """The links of move_group's robot model (robot_description), read once."""
        if self._links is None:
            from ...description.urdf_model import parse_urdf

            try:
                urdf = parse_urdf(rospy.get_param('robot_description'))
                self._links = frozenset(urdf.links)
            except (KeyError, ValueError):
                return frozenset()
        return self._links
