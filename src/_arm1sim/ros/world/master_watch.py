"""Registering a node again with a ROS master that was restarted.

rospy (like roscpp) registers a node's topics and services with the master once, when they
are created. A master killed and started again knows none of them: connections made before
keep working, but no new node finds the world's ``/clock`` or ``/gazebo/*`` services. A
MasterWatch asks the master once a ``period`` whether it knows this node; when a reachable
master does not, it registers every publication, subscription and service again and tells
the node of the publishers of its subscriptions. Parameters are not restored: they went with
the old master (``robot_description``, the controllers' parameters, ``/use_sim_time``).
"""

from __future__ import annotations

import logging
import threading
import time
import xmlrpc.client

import rosgraph
import rospy
from rospy.impl.registration import get_service_manager, get_topic_manager

log = logging.getLogger('_arm1sim.ros')


class MasterWatch:
    """A daemon thread that re-registers this node when the master forgets it."""

    def __init__(self, period: float = 1.0) -> None:
        self.period = period
        self.registrations = 0  # times this node was registered again
        self._thread = threading.Thread(target=self._run, name='master_watch', daemon=True)
        self._thread.start()

    def _run(self) -> None:
        caller_id = rospy.get_name()
        master = rosgraph.Master(caller_id)
        gone = False
        while not rospy.core.is_shutdown():
            time.sleep(self.period)
            try:
                master.lookupNode(caller_id)
                gone = False
            except rosgraph.MasterError:  # a master is there but does not know this node
                gone = False
                self._register(master)
            except (OSError, xmlrpc.client.Error) as exc:
                if not gone:
                    rospy.logwarn(
                        '%s: the ROS master at %s is unreachable (%s); connections '
                        'made so far still work, and this node registers again when '
                        'a master is back',
                        caller_id,
                        master.master_uri,
                        exc,
                    )
                gone = True

    def _register(self, master: rosgraph.Master) -> None:
        uri = rospy.core.get_node_uri()
        tm, sm = get_topic_manager(), get_service_manager()
        with tm.lock, sm.lock:  # as rospy's own registration: nothing added meanwhile
            publications, subscriptions = tm.get_publications(), tm.get_subscriptions()
            services = sm.get_services()
            try:
                for topic, topic_type in publications:
                    master.registerPublisher(topic, topic_type, uri)
                publishers = {
                    topic: master.registerSubscriber(topic, topic_type, uri)
                    for topic, topic_type in subscriptions
                }
                for service, service_uri in services:
                    master.registerService(service, service_uri, uri)
            except (OSError, xmlrpc.client.Error, rosgraph.MasterError) as exc:
                log.debug('registering again failed (%s); retrying', exc)
                return
        node = xmlrpc.client.ServerProxy(uri)
        for topic, uris in publishers.items():
            if uris:  # connect to the publishers the new master knows, as rospy does at start
                node.publisherUpdate('/master', topic, uris)
        self.registrations += 1
        rospy.logwarn(
            '%s: registered again with the ROS master at %s (it was restarted): %d '
            'topics, %d services. Its parameters are gone: load them again (or '
            'restart the launch) before spawning or loading controllers.',
            rospy.get_name(),
            master.master_uri,
            len(publications) + len(subscriptions),
            len(services),
        )
