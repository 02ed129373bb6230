"""moveit_commander.RobotCommander: the robot model's groups, links and joints and the current
state, as robot.py and the C++ RobotInterface do (noetic)."""

from __future__ import annotations

from typing import Dict, List, Optional

from geometry_msgs.msg import PoseStamped
from moveit_msgs.msg import RobotState

from . import client, conversions
from .exception import MoveItCommanderException
from .move_group import MoveGroupCommander


class RobotCommander:
    class Joint:
        def __init__(self, robot: 'RobotCommander', name: str) -> None:
            self._robot, self._name = robot, name

        def name(self) -> str:
            return self._name

        def variable_count(self) -> int:
            return 1 if self._name in self._robot._model.limits else 0

        def bounds(self) -> List[Optional[float]]:
            lower, upper = self._robot._model.limits.get(self._name, (None, None))
            return [lower, upper]

        def min_bound(self) -> Optional[float]:
            return self.bounds()[0]

        def max_bound(self) -> Optional[float]:
            return self.bounds()[1]

        def value(self) -> float:
            return client.current_values(self._robot._model, [self._name])[0]

        def move(self, position: float, wait: bool = True) -> bool:
            """Move this joint alone, through the first group that holds it."""
            group = self._robot.get_default_owner_group(self._name)
            if group is None:
                raise MoveItCommanderException(
                    'There is no known group containing joint %s. Cannot move.' % self._name
                )
            gc = self._robot.get_group(group)
            gc.set_joint_value_target({self._name: position})
            return gc.go(wait=wait)

    class Link:
        def __init__(self, robot: 'RobotCommander', name: str) -> None:
            self._robot, self._name = robot, name

        def name(self) -> str:
            return self._name

        def pose(self) -> PoseStamped:
            model = self._robot._model
            return client.forward_kinematics(
                model, [self._name], client.current_robot_state(model)
            )[0]

    def __init__(self, robot_description: str = 'robot_description', ns: str = '') -> None:
        self._robot_description = robot_description
        self._ns = ns
        self._model = client.semantic_model(robot_description)
        client.state_monitor()
        self._groups: Dict[str, MoveGroupCommander] = {}
        self._joint_owner_groups: Dict[str, str] = {}

    def get_planning_frame(self) -> str:
        return self._model.model_frame

    def get_robot_root_link(self) -> str:
        return self._model.root_link

    def get_robot_name(self) -> str:
        return self._model.robot_name

    def get_group_names(self) -> List[str]:
        return list(self._model.groups)

    def has_group(self, name: str) -> bool:
        return name in self._model.groups

    def get_joint_names(self, group: Optional[str] = None) -> List[str]:
        if group is None:
            return list(self._model.joint_order)
        return list(client.group(self._model, group).joints)

    def get_active_joint_names(self, group: Optional[str] = None) -> List[str]:
        if group is None:
            return list(self._model.variable_joints)
        return list(client.group(self._model, group).active_joints)

    def get_link_names(self, group: Optional[str] = None) -> List[str]:
        if group is None:
            model = self._model
            return [model.root_link] + [model.joint_child[j] for j in model.joint_order]
        return list(client.group(self._model, group).links)

    def get_group_default_states(self, group: str) -> List[str]:
        return list(self._model.group_states.get(group, {}))

    def get_current_state(self) -> RobotState:
        return client.current_robot_state(self._model)

    def get_current_variable_values(self) -> Dict[str, float]:
        names = self._model.variable_joints
        return dict(zip(names, client.current_values(self._model, names)))

    def get_joint(self, name: str) -> 'RobotCommander.Joint':
        if name not in self._model.joint_order:
            raise MoveItCommanderException('There is no joint named %s' % name)
        return RobotCommander.Joint(self, name)

    def get_link(self, name: str) -> 'RobotCommander.Link':
        if name not in self.get_link_names():
            raise MoveItCommanderException('There is no link named %s' % name)
        return RobotCommander.Link(self, name)

    def get_link_pose(self, name: str) -> List[float]:
        return conversions.pose_to_list(self.get_link(name).pose().pose)

    def get_group(self, name: str) -> MoveGroupCommander:
        if name not in self._groups:
            if not self.has_group(name):
                raise MoveItCommanderException('There is no group named %s' % name)
            self._groups[name] = MoveGroupCommander(name, self._robot_description, self._ns)
        return self._groups[name]

    def get_default_owner_group(self, joint_name: str) -> Optional[str]:
        """The smallest group holding the joint (upstream's choice for Joint.move)."""
        if joint_name not in self._joint_owner_groups:
            owners = [g for g in self._model.groups.values() if joint_name in g.variables]
            if owners:
                self._joint_owner_groups[joint_name] = min(owners, key=lambda g: len(g.joints)).name
        return self._joint_owner_groups.get(joint_name)

    def __getattr__(self, name: str):
        """robot.<group>, robot.<joint> or robot.<link>, as upstream allows."""
        if name.startswith('_'):
            raise AttributeError(name)
        model = self.__dict__.get('_model')
        if model is None:
            raise AttributeError(name)
        if name in model.groups:
            return self.get_group(name)
        if name in model.joint_order:
            return self.get_joint(name)
        if name in self.get_link_names():
            return self.get_link(name)
        raise AttributeError("'RobotCommander' object has no attribute '%s'" % name)
