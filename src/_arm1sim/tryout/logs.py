"""Warnings and errors of a finished bringup, read from its ROS logs (rosout.log holds every
node's WARN, ERROR and FATAL, including the world's) and roslaunch's own output."""

import glob
import os
import re
from typing import Any, Dict, List

# rosout.log: "<time> <LEVEL> <node> [<file>:<line>(<func>)] [topics: ...] <message>"
ROSOUT_LINE = re.compile(
    r'^\S+\s+(WARN|ERROR|FATAL)\s+(\S+)\s+\[[^\]]*\]\s+\[topics:[^\]]*\]\s?(.*)$'
)
# A rospy node's own log (ROS_LOG_DIR/<run>/<node>-<n>.log): what it sent to rosout, even
# before rosout was connected to it (warnings at spawn often are).
NODE_LINE = re.compile(r'^\[rosout\]\[(WARNING|ERROR|CRITICAL)\] \S+ \S+: (.*)$')
NODE_LEVELS = {'WARNING': 'WARN', 'ERROR': 'ERROR', 'CRITICAL': 'FATAL'}
DIED = re.compile(r'process has died|REQUIRED process|ERROR: |RLException|Traceback')
MAX_KEPT = 300


def rosout_problems(log_dir: str) -> List[Dict[str, Any]]:
    """WARN/ERROR/FATAL lines of every rosout.log under log_dir, each once with a count."""
    seen: Dict[tuple, Dict[str, Any]] = {}
    for path in sorted(glob.glob(os.path.join(log_dir, '**', 'rosout.log'), recursive=True)):
        with open(path, encoding='utf-8', errors='replace') as f:
            for line in f:
                m = ROSOUT_LINE.match(line.rstrip('\n'))
                if not m:
                    continue
                level, node, msg = m.groups()
                key = (level, node, msg)
                if key in seen:
                    seen[key]['count'] = int(seen[key]['count']) + 1
                elif len(seen) < MAX_KEPT:
                    seen[key] = {'level': level, 'node': node, 'message': msg, 'count': 1}
    messages = {(str(p['level']), str(p['message'])) for p in seen.values()}
    for path in sorted(glob.glob(os.path.join(log_dir, '**', '*.log'), recursive=True)):
        base = os.path.basename(path)
        if base in ('rosout.log', 'master.log') or base.startswith('roslaunch-'):
            continue
        node = '/' + re.sub(r'-\d+$', '', base[: -len('.log')])
        with open(path, encoding='utf-8', errors='replace') as f:
            for line in f:
                m = NODE_LINE.match(line.rstrip('\n'))
                if not m:
                    continue
                level, msg = NODE_LEVELS[m.group(1)], m.group(2)
                if (level, msg) in messages or len(seen) >= MAX_KEPT:
                    continue
                messages.add((level, msg))
                seen[(level, node, msg)] = {
                    'level': level,
                    'node': node,
                    'message': msg,
                    'count': 1,
                }
    return list(seen.values())


def launch_problems(roslaunch_log: str) -> List[str]:
    """Lines of roslaunch's output saying a process died or the launch failed."""
    try:
        with open(roslaunch_log, encoding='utf-8', errors='replace') as f:
            lines = f.read().splitlines()
    except OSError:
        return []
    strip = re.compile(r'\x1b\[[0-9;]*m|\x1b\][^\x07]*\x07')
    out = []
    for line in lines:
        clean = strip.sub('', line).strip()
        if DIED.search(clean) and 'signal_shutdown' not in clean:
            out.append(clean)
    return out[:50]


def unimplemented(problems: List[Dict[str, Any]]) -> List[str]:
    """The world's messages about plugins (and other parts) the stand-in does not implement."""
    keys = ('not implemented', 'not supported', 'unknown plugin', 'ignored')
    return [
        str(p['message']) for p in problems if any(k in str(p['message']).lower() for k in keys)
    ]
