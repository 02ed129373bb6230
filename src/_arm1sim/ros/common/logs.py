"""The core's Python log records (logger ``arm1``) routed to rosout."""

import logging

import rospy


class RospyLogHandler(logging.Handler):
    """Sends the core's Python log records to rosout."""

    def emit(self, record: logging.LogRecord) -> None:
        level = record.levelno
        log = (
            rospy.logerr
            if level >= logging.ERROR
            else rospy.logwarn
            if level >= logging.WARNING
            else rospy.loginfo
            if level >= logging.INFO
            else rospy.logdebug
        )
        log(self.format(record))


def route_core_logs() -> None:
    logger = logging.getLogger('_arm1sim')
    if not any(isinstance(h, RospyLogHandler) for h in logger.handlers):
        logger.addHandler(RospyLogHandler())
        logger.setLevel(logging.INFO)
        logger.propagate = False
