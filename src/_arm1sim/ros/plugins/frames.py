"""Frame ids as gazebo_plugins stamp them: ``tf::resolve(tf_prefix, frameName)``."""

from __future__ import annotations

import logging

import rospy

log = logging.getLogger('rosout')


def tf_resolve(prefix: str, frame: str) -> str:
    """tf::resolve (noetic): an absolute frame loses its '/'; otherwise prefix/frame."""
    if frame.startswith('/'):
        return frame[1:]
    if prefix:
        return '%s/%s' % (prefix.strip('/'), frame)
    return frame


def tf_prefix(search_namespace: str, fallback: str) -> str:
    """tf::getPrefixParam of a node handle in ``search_namespace`` (searchParam upward), else
    ``fallback`` (the plugin's robot namespace) without its trailing '/', as the camera and
    laser plugins do."""
    parts = [s for s in search_namespace.split('/') if s]
    for depth in range(len(parts), -1, -1):
        key = '/' + '/'.join(parts[:depth] + ['tf_prefix'])
        try:
            if rospy.has_param(key):
                return str(rospy.get_param(key))
        except (OSError, rospy.ROSException) as exc:  # master gone: as if unset
            log.warning('could not read %s (%s)', key, exc)
            break
    return fallback.rstrip('/')
