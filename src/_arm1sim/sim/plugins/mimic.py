"""roboticsgroup's mimic joint plugin (under its old and its current file name): parsed with
the joints (description.urdf_model, where a URDF ``<mimic>`` gives the same record) and
driven by physics.mimic; ``mimic_links`` is what the spawn hands the robot, and
``attach_mimic_pids`` what the plugin's Load does with ``<hasPID>`` once the parameters can be
read. Nothing is published.
"""

from __future__ import annotations

import logging
from typing import Any, Callable, List, Tuple

from ...control.pid import Pid, PidConfigError
from ...description.urdf_model import MIMIC_PLUGINS, RobotModel
from .registry import PluginType, register

log = logging.getLogger(__name__)


def mimic_links(description: RobotModel) -> List[Tuple[str, str, float, float, float, float]]:
    """The description's mimics as Robot.set_mimics takes them; the force cap is maxEffort,
    else the follower's effort limit, else (no limit given) a stiff 1000."""
    links = []
    for m in description.mimics:
        limit = description.joints[m.follower].limits.effort
        force = m.max_effort if m.max_effort is not None else limit if limit else 1000.0
        links.append((m.follower, m.leader, m.multiplier, m.offset, abs(force), m.sensitiveness))
    return links


def mimic_pid(gains: Any, namespace: str, period: float) -> Tuple[Callable[[float], float], str]:
    """hasPID's controller from the parameters under ``namespace`` (control_toolbox's
    Pid::init): its ``law(error) -> effort`` over one ``period`` and a warning ('' when
    none). Without a ``p`` the plugin goes on with Pid's zero gains: the follower hangs free."""
    try:
        pid, warning = Pid.from_params(gains, namespace), ''
    except PidConfigError as exc:
        pid, warning = Pid(), '%s: the mimic joint gets no effort, as in Gazebo' % exc

    def law(error: float) -> float:
        return pid.compute_command(error, period)

    return law, warning


def attach_mimic_pids(
    description: RobotModel, robot: Any, params_at: Callable[[str], Any], period: float
) -> None:
    """Each ``<hasPID>`` follower of ``robot`` driven by its PID, gains from
    ``params_at(namespace)`` (the parameter server's dict there, or None)."""
    for m in description.mimics:
        if m.pid_gains is None:
            continue
        law, warning = mimic_pid(params_at(m.pid_gains), m.pid_gains, period)
        if warning:
            log.warning("mimic joint '%s': %s", m.follower, warning)
        robot.set_mimic_pid(m.follower, law)


register(
    *(
        PluginType(name, built_by='physics.mimic (with the URDF <mimic> joints)')
        for name in MIMIC_PLUGINS
    )
)
