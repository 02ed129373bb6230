"""try_robot's verdict and its readable report, from the report dict (also saved as JSON)."""

from typing import Any, Dict, List

from ..control.joint_trajectory_controller import ERROR_CODE_NAMES

MAX_WARNINGS_SHOWN = 25
CHATTER_WORDS = 'velocity-limit chatter'  # sim/limit_chatter.py's warning


def verdict(rep: Dict[str, Any]) -> Dict[str, Any]:
    """ok, and one line per reason it is not."""
    why: List[str] = []
    build = rep.get('build', {})
    if not build.get('ok'):
        failed = sorted(n for n, v in (build.get('per_package') or {}).items() if not v['built'])
        if build.get('rest_ok') and failed:
            why.append(
                'the workspace did not build with %s (ran from it built without)'
                % ', '.join(failed)
            )
        else:
            why.append('the workspace did not build (ran from the sources)')
    up = rep.get('bringup', {})
    if not up.get('up'):
        why.append('the bringup did not come up: %s' % up.get('error'))
    elif not up.get('alive', True):
        why.append('roslaunch ended before the checks were done')
    elif not up.get('world_alive', True):
        why.append('the world /gazebo died (see the warnings and roslaunch lines)')
    managers = rep.get('controller_managers') or {}
    if up.get('up') and not managers:
        why.append('no controller manager came up')
    for ns, controllers in managers.items():
        for c in controllers:
            if 'error' in c:
                why.append('controller manager %s: %s' % (ns, c['error']))
    motion = rep.get('motion') or []
    for m in motion:
        if not m.get('ok'):
            why.append('%s: %s' % (m.get('controller'), _motion_line(m)))
    if up.get('up') and managers and not motion:
        why.append('no running position or trajectory controller to move a joint with')
    for w in rep.get('warnings') or []:  # the world's diagnosis of the limit trap
        if CHATTER_WORDS in str(w.get('message', '')):
            why.append(str(w['message']))
    return {'ok': not why, 'problems': why}


def work_verdict(rep: Dict[str, Any]) -> Dict[str, Any]:
    """A tool's own verdict (rep['work']['ok'], its 'problems'), after the bringup's."""
    why: List[str] = []
    up = rep.get('bringup', {})
    if not up.get('up'):
        why.append('the bringup did not come up: %s' % up.get('error'))
    elif not up.get('world_alive', True):
        why.append('the world /gazebo died (see the warnings and roslaunch lines)')
    work = rep.get('work') or {}
    why += [str(p) for p in work.get('problems', [])]
    if up.get('up') and not work.get('ok'):
        why.append(str(work.get('summary', 'the tool did not finish')))
    return {'ok': not why, 'problems': why}


def _motion_line(m: Dict[str, Any]) -> str:
    if 'error' in m:
        return 'error: %s' % m['error']
    if 'error_code' in m or 'finished' in m:
        code = m.get('error_code')
        name = ERROR_CODE_NAMES.get(code, str(code)) if code is not None else 'no result'
        text = 'FollowJointTrajectory over %d joints: %s' % (len(m.get('joints', [])), name)
        if m.get('error_string'):
            text += ' (%s)' % m['error_string']
        text += ', %.2f s, largest final error %.4f' % (
            float(m.get('seconds', 0.0)),
            float(m.get('max_abs_error', float('nan'))),
        )
        if not m.get('finished'):
            text += ', no result in time'
        if m.get('remapped_from'):
            text += ', on %s (remapped from %s)' % (m.get('action'), m['remapped_from'])
        vel = [abs(v) for v in (m.get('final_velocity') or {}).values() if v is not None]
        if code == -5 and vel:  # a goal error may be the stopped-velocity check's
            text += ', fastest joint at the end %.3f/s' % max(vel)
        if m.get('restarted_to_hold_the_measured_pose'):
            worst = max((abs(e) for e in (m.get('hold_error_before') or {}).values()), default=0)
            text += ' (restarted first: it held %.3f away from the measured pose)' % worst
        return text
    moved = m.get('moved') or {}
    n = sum(1 for v in moved.values() if v)
    return 'command on %s: %d of %d joints moved' % (m.get('command_topic'), n, len(moved))


def text(rep: Dict[str, Any]) -> str:
    lines: List[str] = []
    add = lines.append
    la = rep['launch']
    add('try_robot  %s %s %s' % (la['package'], la['file'], ' '.join(la['args'])))
    for pkg, launch in la.get('then', []):
        add('then       %s %s' % (pkg, launch))
    add('date       %s' % rep.get('date'))
    for c in rep.get('checkouts', []):
        commit = (c.get('commit') or 'not a git checkout')[:12]
        add(
            'checkout   %s @ %s%s%s%s'
            % (
                c['path'],
                commit,
                ' (%s)' % c['branch'] if c.get('branch') else '',
                ', %s' % c['commit_date'] if c.get('commit_date') else '',
                ', WITH LOCAL CHANGES' if c.get('local_changes') else '',
            )
        )
    b = rep.get('build', {})
    add(
        'build      %s in %.1f s: %s'
        % ('ok' if b.get('ok') else 'FAILED', b.get('seconds', 0), ', '.join(b.get('packages', [])))
    )
    for name, v in sorted((b.get('per_package') or {}).items()):
        if v.get('built'):
            add('  %-28s built unchanged' % name)
        else:
            add('  %-28s NOT BUILT (%s) %s' % (name, v.get('stage', ''), v.get('error', '')))
    if not b.get('ok') and b.get('log_tail'):
        lines.extend('  | ' + t for t in str(b['log_tail']).splitlines()[-15:])
    up = rep.get('bringup', {})
    if up.get('up'):
        add('bringup    up in %.1f s' % up.get('seconds', 0))
        if up.get('unpaused_by_try_robot'):
            add('           (the world stayed paused; try_robot unpaused it)')
    else:
        add('bringup    DID NOT COME UP: %s' % up.get('error'))
    models = rep.get('models')
    if models is not None:
        add('models     %s' % (', '.join(models) or '(none)'))
    for ns, controllers in (rep.get('controller_managers') or {}).items():
        add('controller manager %s' % ns)
        for c in controllers:
            if 'error' in c:
                add('  ERROR %s' % c['error'])
                continue
            add(
                '  %-28s %-48s %-12s %s'
                % (c['name'], c['type'], c['state'], ' '.join(c.get('joints', [])))
            )
    for name, d in (rep.get('descriptions') or {}).items():
        if 'error' in d:
            add('description %s: REFUSED: %s' % (name, d['error']))
            continue
        sensors = ', '.join(
            '%s (%s on %s)' % (s['name'], s['type'], s['link']) for s in d['sensors']
        )
        plugins = ', '.join(sorted({str(p['filename']) for p in d['plugins']}))
        add('description %s: robot %s, %d joints' % (name, d['robot'], len(d['joints'])))
        add('  sensors  %s' % (sensors or '(none)'))
        add('  plugins  %s' % (plugins or '(none)'))
    topics = rep.get('gazebo_topics')
    if topics:
        add('topics of /gazebo  %s' % ', '.join(topics))
    for line in rep.get('unimplemented') or []:
        add('not implemented  %s' % line)
    for m in rep.get('motion') or []:
        add(
            'motion     %s %s: %s'
            % ('ok  ' if m.get('ok') else 'FAIL', m.get('controller'), _motion_line(m))
        )
    for line in (rep.get('work') or {}).get('lines', []):
        add('work       %s' % line)
    warnings = rep.get('warnings') or []
    add('warnings   %d distinct WARN/ERROR/FATAL messages in rosout.log' % len(warnings))
    for w in warnings[:MAX_WARNINGS_SHOWN]:
        count = ' (x%d)' % w['count'] if w['count'] > 1 else ''
        add('  %-5s %s: %s%s' % (w['level'], w['node'], w['message'][:200], count))
    for line in rep.get('launch_problems') or []:
        add('roslaunch  %s' % line[:200])
    v = rep.get('verdict', {})
    add('verdict    %s' % ('PASS' if v.get('ok') else 'FAIL'))
    for why in v.get('problems', []):
        add('  - %s' % why)
    add('report     %s/report.json' % rep.get('out'))
    return '\n'.join(lines) + '\n'
