"""Reads a rosbag of a run for the tuner: each position controller's commands and its
joint's positions (``<ns>/joint_states`` header stamps; commands at their record time).

Record one with e.g.::

    rosbag record -O run.bag /arm1/joint_states -e '/arm1/.*_position_controller/command'
"""

from typing import Any, Dict, List, Tuple

import rosbag


def read_run(path, namespace, controllers):
    """``{joint: (commands [(t, value)], samples [(t, position)])}`` for ``controllers``
    (``{controller name: joint}``) under ``namespace``."""
    ns = '/' + namespace.strip('/')
    command_topics = {'%s/%s/command' % (ns, c): j for c, j in controllers.items()}
    states_topic = '%s/joint_states' % ns
    out: Dict[str, Tuple[List[Any], List[Any]]] = {j: ([], []) for j in controllers.values()}
    with rosbag.Bag(path) as bag:
        for topic, msg, t in bag.read_messages(topics=list(command_topics) + [states_topic]):
            if topic == states_topic:
                stamp = msg.header.stamp.to_sec() if msg.header.stamp else t.to_sec()
                for name, pos in zip(msg.name, msg.position):
                    if name in out:
                        out[name][1].append((stamp, pos))
            else:
                out[command_topics[topic]][0].append((t.to_sec(), msg.data))
    return out
