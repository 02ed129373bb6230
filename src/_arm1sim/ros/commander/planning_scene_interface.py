"""moveit_commander.PlanningSceneInterface: world and attached collision objects through
move_group's get_planning_scene / apply_planning_scene services (synchronous, the default)
or its collision_object / attached_collision_object topics (synchronous=False), as
planning_scene_interface.py and its C++ PlanningSceneInterface do (noetic).
"""

from __future__ import annotations

import os
from typing import Dict, Iterable, Optional, Sequence

import rospy
from geometry_msgs.msg import Point, Pose, PoseStamped
from moveit_msgs.msg import (
    AttachedCollisionObject,
    CollisionObject,
    PlanningScene,
    PlanningSceneComponents,
)
from moveit_msgs.srv import ApplyPlanningScene, GetPlanningScene
from rosgraph.names import ns_join
from shape_msgs.msg import Mesh, MeshTriangle, Plane, SolidPrimitive

from . import client
from .exception import MoveItCommanderException

SERVICE_WAIT = 5.0  # seconds, as PlanningSceneInterfaceImpl waits for its services


class PlanningSceneInterface:
    """The planning scene of move_group, seen and changed from a script."""

    def __init__(self, ns: str = '', synchronous: bool = True) -> None:
        self._ns = ns
        self._synchronous = synchronous
        self._get = rospy.ServiceProxy(
            ns_join(ns, client.GET_PLANNING_SCENE_SERVICE), GetPlanningScene
        )
        self._apply = rospy.ServiceProxy(
            ns_join(ns, client.APPLY_PLANNING_SCENE_SERVICE), ApplyPlanningScene
        )
        for proxy in (self._get, self._apply):
            try:
                proxy.wait_for_service(SERVICE_WAIT)
            except rospy.ROSException:
                rospy.logwarn(
                    "PlanningSceneInterface: service '%s' is not available after %.0f s "
                    '(is move_group running?)' % (proxy.resolved_name, SERVICE_WAIT)
                )
        if not synchronous:
            self._pub_co = rospy.Publisher(
                ns_join(ns, client.COLLISION_OBJECT_TOPIC), CollisionObject, queue_size=100
            )
            self._pub_aco = rospy.Publisher(
                ns_join(ns, client.ATTACHED_COLLISION_OBJECT_TOPIC),
                AttachedCollisionObject,
                queue_size=100,
            )

    # --- changing the scene
    def _submit(self, obj, attach: bool = False) -> None:
        if self._synchronous:
            scene = PlanningScene(is_diff=True)
            scene.robot_state.is_diff = True
            if attach:
                scene.robot_state.attached_collision_objects = [obj]
            else:
                scene.world.collision_objects = [obj]
            self.apply_planning_scene(scene)
        elif attach:
            self._pub_aco.publish(obj)
        else:
            self._pub_co.publish(obj)

    def apply_planning_scene(self, planning_scene_message: PlanningScene) -> bool:
        try:
            return bool(self._apply(planning_scene_message).success)
        except (rospy.ServiceException, rospy.ROSException) as e:
            rospy.logwarn('Failed to call service %s: %s' % (self._apply.resolved_name, e))
            return False

    def add_object(self, collision_object: CollisionObject) -> None:
        self._submit(collision_object)

    def add_box(self, name: str, pose: PoseStamped, size=(1, 1, 1)) -> None:
        self._submit(self.make_box(name, pose, size))

    def add_sphere(self, name: str, pose: PoseStamped, radius: float = 1) -> None:
        self._submit(self.make_sphere(name, pose, radius))

    def add_cylinder(self, name: str, pose: PoseStamped, height: float, radius: float) -> None:
        self._submit(self.make_cylinder(name, pose, height, radius))

    def add_cone(self, name: str, pose: PoseStamped, height: float, radius: float) -> None:
        self._submit(self.make_cone(name, pose, height, radius))

    def add_mesh(self, name: str, pose: PoseStamped, filename: str, size=(1, 1, 1)) -> None:
        self._submit(self.make_mesh(name, pose, filename, size))

    def add_plane(self, name: str, pose: PoseStamped, normal=(0, 0, 1), offset: float = 0) -> None:
        self._submit(self.make_plane(name, pose, normal, offset))

    def attach_object(
        self, object, link: Optional[str] = None, touch_links: Optional[Sequence[str]] = None
    ) -> None:
        if isinstance(object, str):
            object = self._make_existing(object)
        if isinstance(object, CollisionObject):
            object = AttachedCollisionObject(object=object)
        if link is not None:
            object.link_name = link
        object.touch_links = list(touch_links) if touch_links is not None else [object.link_name]
        self._submit(object, attach=True)

    def attach_box(
        self,
        link: str,
        name: str,
        pose: Optional[PoseStamped] = None,
        size=(1, 1, 1),
        touch_links: Optional[Sequence[str]] = None,
    ) -> None:
        co = self.make_box(name, pose, size) if pose is not None else self._make_existing(name)
        self.attach_object(co, link, touch_links)

    def attach_sphere(
        self,
        link: str,
        name: str,
        pose: Optional[PoseStamped] = None,
        radius: float = 1,
        touch_links: Optional[Sequence[str]] = None,
    ) -> None:
        co = self.make_sphere(name, pose, radius) if pose is not None else self._make_existing(name)
        self.attach_object(co, link, touch_links)

    def attach_cylinder(
        self,
        link: str,
        name: str,
        pose: Optional[PoseStamped] = None,
        height: float = 1,
        radius: float = 1,
        touch_links: Optional[Sequence[str]] = None,
    ) -> None:
        co = (
            self.make_cylinder(name, pose, height, radius)
            if pose is not None
            else self._make_existing(name)
        )
        self.attach_object(co, link, touch_links)

    def attach_mesh(
        self,
        link: str,
        name: str,
        pose: Optional[PoseStamped] = None,
        filename: str = '',
        size=(1, 1, 1),
        touch_links: Optional[Sequence[str]] = None,
    ) -> None:
        co = (
            self.make_mesh(name, pose, filename, size)
            if pose is not None and filename
            else self._make_existing(name)
        )
        self.attach_object(co, link, touch_links)

    def remove_world_object(self, name: Optional[str] = None) -> None:
        """Remove one world object, or all of them when no name is given."""
        co = CollisionObject(operation=CollisionObject.REMOVE)
        if name is not None:
            co.id = name
        self._submit(co)

    def remove_attached_object(
        self, link: Optional[str] = None, name: Optional[str] = None
    ) -> None:
        """Detach an object (or all on ``link``, or all): it stays in the world."""
        aco = AttachedCollisionObject()
        aco.object.operation = CollisionObject.REMOVE
        if link is not None:
            aco.link_name = link
        if name is not None:
            aco.object.id = name
        self._submit(aco, attach=True)

    def clear(self) -> bool:
        """Remove every world and attached object."""
        scene = PlanningScene(is_diff=True)
        scene.robot_state.is_diff = True
        aco = AttachedCollisionObject()
        aco.object.operation = CollisionObject.REMOVE
        scene.robot_state.attached_collision_objects = [aco]
        scene.world.collision_objects = [CollisionObject(operation=CollisionObject.REMOVE)]
        return self.apply_planning_scene(scene)

    # --- reading the scene
    def get_planning_scene(self, components) -> PlanningScene:
        if isinstance(components, int):
            components = PlanningSceneComponents(components=components)
        try:
            return self._get(components).scene
        except (rospy.ServiceException, rospy.ROSException) as e:
            rospy.logwarn(
                'Could not call planning scene service %s: %s' % (self._get.resolved_name, e)
            )
            return PlanningScene()

    def _world(self, what: int) -> list:
        return list(self.get_planning_scene(what).world.collision_objects)

    def get_known_object_names(self, with_type: bool = False) -> list:
        return [
            o.id
            for o in self._world(PlanningSceneComponents.WORLD_OBJECT_NAMES)
            if not with_type or o.type.key
        ]

    def get_known_object_names_in_roi(
        self, minx, miny, minz, maxx, maxy, maxz, with_type: bool = False
    ) -> list:
        """Objects whose (first shape's) position lies in the box, as upstream tests it."""
        out = []
        for o in self._world(PlanningSceneComponents.WORLD_OBJECT_GEOMETRY):
            if with_type and not o.type.key:
                continue
            poses = list(o.primitive_poses) + list(o.mesh_poses) + list(o.plane_poses) or [Pose()]
            for p in poses:
                x, y, z = (
                    o.pose.position.x + p.position.x,
                    o.pose.position.y + p.position.y,
                    o.pose.position.z + p.position.z,
                )
                if minx <= x <= maxx and miny <= y <= maxy and minz <= z <= maxz:
                    out.append(o.id)
                    break
        return out

    def get_object_poses(self, object_ids: Iterable[str]) -> Dict[str, Pose]:
        wanted = set(object_ids)
        return {
            o.id: o.pose
            for o in self._world(PlanningSceneComponents.WORLD_OBJECT_GEOMETRY)
            if o.id in wanted
        }

    def get_objects(self, object_ids: Sequence[str] = ()) -> Dict[str, CollisionObject]:
        wanted = set(object_ids)
        return {
            o.id: o
            for o in self._world(PlanningSceneComponents.WORLD_OBJECT_GEOMETRY)
            if not wanted or o.id in wanted
        }

    def get_attached_objects(
        self, object_ids: Sequence[str] = ()
    ) -> Dict[str, AttachedCollisionObject]:
        wanted = set(object_ids)
        scene = self.get_planning_scene(PlanningSceneComponents.ROBOT_STATE_ATTACHED_OBJECTS)
        return {
            a.object.id: a
            for a in scene.robot_state.attached_collision_objects
            if not wanted or a.object.id in wanted
        }

    # --- making objects
    @staticmethod
    def _make_existing(name: str) -> CollisionObject:
        return CollisionObject(id=name)

    @staticmethod
    def _make_primitive(name: str, pose: PoseStamped, kind: int, dims) -> CollisionObject:
        co = CollisionObject(operation=CollisionObject.ADD, id=name)
        co.header = pose.header
        co.pose = pose.pose
        # no primitive_poses, as upstream: the shape sits at the object's own pose
        co.primitives = [SolidPrimitive(type=kind, dimensions=list(dims))]
        return co

    @staticmethod
    def make_box(name: str, pose: PoseStamped, size) -> CollisionObject:
        return PlanningSceneInterface._make_primitive(name, pose, SolidPrimitive.BOX, size)

    @staticmethod
    def make_sphere(name: str, pose: PoseStamped, radius: float) -> CollisionObject:
        return PlanningSceneInterface._make_primitive(name, pose, SolidPrimitive.SPHERE, [radius])

    @staticmethod
    def make_cylinder(
        name: str, pose: PoseStamped, height: float, radius: float
    ) -> CollisionObject:
        return PlanningSceneInterface._make_primitive(
            name, pose, SolidPrimitive.CYLINDER, [height, radius]
        )

    @staticmethod
    def make_cone(name: str, pose: PoseStamped, height: float, radius: float) -> CollisionObject:
        return PlanningSceneInterface._make_primitive(
            name, pose, SolidPrimitive.CONE, [height, radius]
        )

    @staticmethod
    def make_mesh(name: str, pose: PoseStamped, filename: str, scale=(1, 1, 1)) -> CollisionObject:
        """A mesh object from an STL file (upstream reads any format through pyassimp, which
        Debian 12's python3-pyassimp cannot load; STL is read with numpy-stl)."""
        if os.path.splitext(filename)[1].lower() != '.stl':
            raise MoveItCommanderException(
                "add_mesh reads STL files here (pyassimp is unusable on Debian 12): '%s'" % filename
            )
        try:
            from stl import mesh as stl_mesh

            data = stl_mesh.Mesh.from_file(filename)
        except (OSError, ValueError, AssertionError) as e:
            raise MoveItCommanderException("cannot read mesh '%s': %s" % (filename, e)) from None
        if len(data.vectors) == 0:
            raise MoveItCommanderException('There are no faces in the mesh')
        mesh = Mesh()
        index: Dict[tuple, int] = {}
        for tri in data.vectors:
            ids = []
            for v in tri:
                key = (float(v[0]) * scale[0], float(v[1]) * scale[1], float(v[2]) * scale[2])
                if key not in index:
                    index[key] = len(mesh.vertices)
                    mesh.vertices.append(Point(*key))
                ids.append(index[key])
            mesh.triangles.append(MeshTriangle(vertex_indices=ids))
        co = CollisionObject(operation=CollisionObject.ADD, id=name)
        co.header = pose.header
        co.pose = pose.pose
        co.meshes = [mesh]
        return co

    @staticmethod
    def make_plane(
        name: str, pose: PoseStamped, normal=(0, 0, 1), offset: float = 0
    ) -> CollisionObject:
        co = CollisionObject(operation=CollisionObject.ADD, id=name)
        co.header = pose.header
        co.planes = [Plane(coef=list(normal) + [offset])]
        co.plane_poses = [pose.pose]
        return co
