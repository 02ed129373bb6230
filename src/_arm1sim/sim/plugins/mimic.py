"""roboticsgroup's mimic joint plugin (under its old and its current file name): parsed with
the joints (description.urdf_model, where a URDF ``<mimic>`` gives the same record) and
driven by physics.mimic; ``mimic_links`` is what the spawn hands the robot. Nothing is
published.
"""

from __future__ import annotations

from typing import List, Tuple

from ...description.urdf_model import MIMIC_PLUGINS, RobotModel
from .registry import PluginType, register


def mimic_links(description: RobotModel) -> List[Tuple[str, str, float, float, float, float]]:
    """The description's mimics as Robot.set_mimics takes them; the force cap is maxEffort,
    else the follower's effort limit, else (no limit given) a stiff 1000."""
    links = []
    for m in description.mimics:
        limit = description.joints[m.follower].limits.effort
        force = m.max_effort if m.max_effort is not None else limit if limit else 1000.0
        links.append((m.follower, m.leader, m.multiplier, m.offset, abs(force), m.sensitiveness))
    return links


register(
    *(
        PluginType(name, built_by='physics.mimic (with the URDF <mimic> joints)')
        for name in MIMIC_PLUGINS
    )
)
