"""franka_hw's FrankaStateInterface and FrankaModelInterface, ROS-free.

A hardware offering them (hw_sim.py) hands controllers a FrankaRobotState (the
fields of libfranka's RobotState, as franka_msgs/FrankaState carries them) and a model of
the arm's dynamics. Matrices are lists: 4x4 transforms column-major (16 values) as in
libfranka, the 7x7 mass matrix and 6x7 Jacobians as lists of rows.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import Any, Dict, List, Protocol, runtime_checkable

from ...control.interfaces import RobotHW

FRANKA_STATE_INTERFACE = 'franka_hw/FrankaStateInterface'
FRANKA_MODEL_INTERFACE = 'franka_hw/FrankaModelInterface'

# franka_msgs/FrankaState's robot_mode values
ROBOT_MODE_OTHER, ROBOT_MODE_IDLE, ROBOT_MODE_MOVE = 0, 1, 2
ROBOT_MODE_USER_STOPPED = 5

IDENTITY_TRANSFORM = [1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0]


def _zeros(n: int) -> Any:
    return field(default_factory=lambda: [0.0] * n)


def _identity() -> Any:
    return field(default_factory=lambda: list(IDENTITY_TRANSFORM))


@dataclass
class FrankaRobotState:
    """libfranka's RobotState as far as the simulation knows it (errors: none, ever)."""

    q: List[float] = _zeros(7)
    q_d: List[float] = _zeros(7)
    dq: List[float] = _zeros(7)
    dq_d: List[float] = _zeros(7)
    ddq_d: List[float] = _zeros(7)
    theta: List[float] = _zeros(7)
    dtheta: List[float] = _zeros(7)
    tau_J: List[float] = _zeros(7)
    dtau_J: List[float] = _zeros(7)
    tau_J_d: List[float] = _zeros(7)
    tau_ext_hat_filtered: List[float] = _zeros(7)
    joint_contact: List[float] = _zeros(7)
    joint_collision: List[float] = _zeros(7)
    cartesian_contact: List[float] = _zeros(6)
    cartesian_collision: List[float] = _zeros(6)
    K_F_ext_hat_K: List[float] = _zeros(6)
    O_F_ext_hat_K: List[float] = _zeros(6)
    O_dP_EE_d: List[float] = _zeros(6)
    O_dP_EE_c: List[float] = _zeros(6)
    O_ddP_EE_c: List[float] = _zeros(6)
    O_ddP_O: List[float] = field(default_factory=lambda: [0.0, 0.0, -9.81])
    elbow: List[float] = _zeros(2)
    elbow_d: List[float] = _zeros(2)
    elbow_c: List[float] = _zeros(2)
    delbow_c: List[float] = _zeros(2)
    ddelbow_c: List[float] = _zeros(2)
    m_ee: float = 0.0
    F_x_Cee: List[float] = _zeros(3)
    I_ee: List[float] = _zeros(9)
    m_load: float = 0.0
    F_x_Cload: List[float] = _zeros(3)
    I_load: List[float] = _zeros(9)
    m_total: float = 0.0
    F_x_Ctotal: List[float] = _zeros(3)
    I_total: List[float] = _zeros(9)
    O_T_EE: List[float] = _identity()
    O_T_EE_d: List[float] = _identity()
    O_T_EE_c: List[float] = _identity()
    F_T_EE: List[float] = _identity()
    F_T_NE: List[float] = _identity()
    NE_T_EE: List[float] = _identity()
    EE_T_K: List[float] = _identity()
    time: float = 0.0  # s
    control_command_success_rate: float = 0.0
    robot_mode: int = ROBOT_MODE_IDLE

    def as_fields(self) -> Dict[str, Any]:
        """franka_msgs/FrankaState's fields (header and errors aside), copied."""
        out: Dict[str, Any] = {}
        for f in fields(self):
            value = getattr(self, f.name)
            out[f.name] = list(value) if isinstance(value, list) else value
        return out


class FrankaModel(Protocol):
    """franka_hw's FrankaModelHandle, at the hardware's current state."""

    def mass(self) -> List[List[float]]:
        """7x7 joint-space inertia matrix."""
        ...

    def coriolis(self) -> List[float]:
        """Coriolis and centrifugal torques C(q, dq) dq."""
        ...

    def gravity(self) -> List[float]:
        """Gravity torques at q."""
        ...

    def zero_jacobian(self) -> List[List[float]]:
        """6x7 Jacobian of the end effector in the base frame."""
        ...

    def pose(self) -> List[float]:
        """The end effector's pose in the base frame (O_T_EE), column-major 4x4."""
        ...


@runtime_checkable
class FrankaHW(RobotHW, Protocol):
    """A RobotHW with franka_hw's interfaces (names: ``<arm_id>_robot``, ``<arm_id>_model``)."""

    arm_id: str

    def franka_state(self, name: str, controller_ns: str) -> FrankaRobotState:
        """The state behind FrankaStateHandle ``name``; ControllerError when there is none."""
        ...

    def franka_model(self, name: str, controller_ns: str) -> FrankaModel:
        """The model behind FrankaModelHandle ``name``; ControllerError when there is none."""
        ...
