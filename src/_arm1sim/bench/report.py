"""The benchmark's table and notes (BENCHMARKS.md) from results.json's data."""

from __future__ import annotations

from typing import Any, Dict, Iterator, Optional, Tuple

# (label, figure, field, goal text, check(median) -> bool or None, format)
ROWS = [
    (
        'real-time factor over the run, at factor 1',
        'realtime',
        'rtf',
        '1.00 ± 0.01',
        lambda v: abs(v - 1.0) <= 0.01,
        '%.4f',
    ),
    (
        'joint_states rate in sim time (Hz)',
        'realtime',
        'joint_states_hz',
        '50 ± 0.5 %',
        lambda v: abs(v - 50.0) <= 0.25,
        '%.3f',
    ),
    (
        'world CPU at real time (fraction of a core)',
        'realtime',
        'cpu_core_fraction',
        '≤ 0.10',
        lambda v: v <= 0.10,
        '%.3f',
    ),
    (
        '  world CPU per simulated second at real time (core-seconds)',
        'realtime',
        'cpu_per_sim_s',
        '',
        None,
        '%.3f',
    ),
    (
        '  the same launch, arm1 commanded upright, off the ground (fraction of a core)',
        'realtime',
        'cpu_core_fraction_upright',
        '',
        None,
        '%.3f',
    ),
    (
        '  the same launch, arm1 upright (core-seconds per simulated second)',
        'realtime',
        'cpu_per_sim_s_upright',
        '',
        None,
        '%.3f',
    ),
    (
        '  the floor: empty world, no robot (fraction of a core)',
        'idle_world',
        'cpu_core_fraction',
        '',
        None,
        '%.3f',
    ),
    (
        '  CPU of one 1 ms sleep and wake-up (µs)',
        'idle_world',
        'sleep_wakeup_cpu_us',
        '',
        None,
        '%.1f',
    ),
    (
        'world peak resident memory (MB)',
        'realtime',
        'peak_rss_mb',
        '≤ 200',
        lambda v: v <= 200,
        '%.0f',
    ),
    ('bare pybullet loop (steps/s)', 'bare', 'steps_per_s', 'the ceiling', None, '%.0f'),
    ('stand-in top speed, 1 arm (steps/s)', 'standin_1', 'steps_per_s', '', None, '%.0f'),
    ('stand-in / bare speed ratio', 'speed_ratio', None, '≥ 0.6', lambda v: v >= 0.6, '%.2f'),
    (
        '  the same ratio in CPU time per step (bare over stand-in)',
        'speed_ratio_cpu',
        None,
        '',
        None,
        '%.2f',
    ),
    (
        'stand-in top speed, 1 arm, one JointTrajectoryController (steps/s)',
        'standin_trajectory',
        'steps_per_s',
        'next to the position controllers',
        None,
        '%.0f',
    ),
    ('stand-in top speed, 2 arms (steps/s)', 'standin_2', 'steps_per_s', '', None, '%.0f'),
    ('stand-in top speed, 4 arms (steps/s)', 'standin_4', 'steps_per_s', '', None, '%.0f'),
    ('stand-in top speed, 8 arms (steps/s)', 'standin_8', 'steps_per_s', '', None, '%.0f'),
    ('stand-in top speed, 16 arms (steps/s)', 'standin_16', 'steps_per_s', '', None, '%.0f'),
    (
        'stand-in top speed, 1 arm, camera streaming 30 Hz in lockstep (steps/s)',
        'standin_camera',
        'steps_per_s',
        '',
        None,
        '%.0f',
    ),
    ('  wall time each camera frame adds (ms)', 'camera_frame_ms', None, '', None, '%.1f'),
    (
        'stand-in top speed, 1 arm, /gazebo/model_states subscribed (steps/s)',
        'standin_model_states',
        'steps_per_s',
        '',
        None,
        '%.0f',
    ),
    (
        '  its cost per step on the physics thread (µs)',
        'model_states_us',
        None,
        '',
        None,
        '%.2f',
    ),
    (
        'start-up: roslaunch to first joint_states (s)',
        'startup',
        'startup_s',
        '≤ 3',
        lambda v: v <= 3.0,
        '%.2f',
    ),
    (
        'robot_spawn.launch at real time, every process (cores)',
        'seed_goal',
        'cpu_core_fraction',
        '≤ 0.5',
        lambda v: v <= 0.5,
        '%.3f',
    ),
    ('  of which the world (cores)', 'seed_goal', 'cpu_world', '', None, '%.3f'),
    ('  of which the render processes (cores)', 'seed_goal', 'cpu_render', '', None, '%.3f'),
    ('  of which look_away (cores)', 'seed_goal', 'cpu_look_away', '', None, '%.3f'),
    (
        '  of which the rest: master, rosout, arm_mover, ... (cores)',
        'seed_goal',
        'cpu_rest',
        '',
        None,
        '%.3f',
    ),
    ('command latency p50 (ms)', 'latency', 'p50_ms', '', None, '%.3f'),
    ('command latency p99 (ms)', 'latency', 'p99_ms', '≤ 2', lambda v: v <= 2.0, '%.3f'),
]
# scaling: N arms in one world, N × their steps/s ÷ one arm's (1 = linear)
ROWS += [
    (
        '%sscaling, %d arms: %d × their steps/s ÷ 1 arm\'s' % ('' if n == 8 else '  ', n, n),
        'scaling_%d' % n,
        None,
        '≥ 0.8' if n == 8 else '',
        (lambda v: v >= 0.8) if n == 8 else None,
        '%.2f',
    )
    for n in (2, 4, 8, 16)
]
# camera frame cost per renderer backend (bench/render.py): 'gl' is the default
ROWS += [
    (
        '%scamera frame %s, renderer %s (%s)'
        % ('  ' if size != '640x480' or kind != 'ms' else '', size, name, unit),
        'render',
        '%s_%s_%s' % (name, size, kind),
        '≤ 8' if (name, size, kind) == ('gl', '640x480', 'ms') else '',
        (lambda v: v <= 8.0) if (name, size, kind) == ('gl', '640x480', 'ms') else None,
        '%.1f',
    )
    for name in ('gl', 'egl', 'tiny')
    for size, kind, unit in (
        ('640x480', 'ms', 'ms'),
        ('640x480', 'cpu_ms', 'CPU ms, all threads'),
        ('320x240', 'ms', 'ms'),
        ('800x800', 'ms', 'ms'),
    )
]
# a subscribed laser's cost on the physics thread (bench/sensors.py)
ROWS += [
    ('laser scan cost (ms per scan, 720 rays)', 'laser', 'scan_ms', '', None, '%.2f'),
    ('  of which the ray cast, masking and noise (ms)', 'laser', 'cast_ms', '', None, '%.2f'),
]
# a concave collision mesh made into convex pieces (bench/meshes.py): arm1's link2, 592 triangles
ROWS += [
    ('concave mesh: convex pieces (of 592 triangles)', 'concave_mesh', 'pieces', '', None, '%d'),
    ('concave mesh spawn, empty cache (ms)', 'concave_mesh', 'spawn_first_ms', '', None, '%.0f'),
    ('  the same mesh, from the cache (ms)', 'concave_mesh', 'spawn_cached_ms', '', None, '%.0f'),
    ('  the same mesh as its convex hull (ms)', 'concave_mesh', 'spawn_hull_ms', '', None, '%.0f'),
    ('concave mesh, a box resting on it: step (ms)', 'concave_mesh', 'step_ms', '', None, '%.2f'),
    ('  the same on its convex hull: step (ms)', 'concave_mesh', 'step_hull_ms', '', None, '%.2f'),
]
# the mesh cache's first fill (bench/meshes.py cache_fill): a bumpy U of 20 k triangles
ROWS += [
    (
        'mesh cache fill, cold: CPU s per 10 k triangles (.%s)' % ext,
        'mesh_cache_fill',
        'cold_s_per_10k_' + ext,
        '',
        None,
        '%.2f',
    )
    for ext in ('stl', 'obj', 'dae')
]
ROWS += [
    (
        '  warm, from the cache (.%s)' % ext,
        'mesh_cache_fill',
        'warm_s_per_10k_' + ext,
        '',
        None,
        '%.4f',
    )
    for ext in ('stl', 'obj', 'dae')
]
ROWS += [
    (
        'spawn of 10 links of 20 k triangles, cache empty (s)',
        'mesh_cache_fill',
        'spawn_10_links_cold_s',
        '',
        None,
        '%.2f',
    ),
    (
        '  its caller thread: CPU s',
        'mesh_cache_fill',
        'spawn_10_links_caller_cpu_s',
        '',
        None,
        '%.2f',
    ),
    (
        '  its physics thread: CPU s',
        'mesh_cache_fill',
        'spawn_10_links_physics_cpu_s',
        '',
        None,
        '%.2f',
    ),
]
# the browser view (bench/web.py): gazebo.launch web:=true at real time, page closed and open in
# headless Chromium; then arm1's camera subscribed: images per sim second against its update_rate
ROWS += [
    ('browser view: world CPU, no page open (cores)', 'web_view', 'cpu_closed', '', None, '%.3f'),
    (
        '  with the page open in headless Chromium (cores)',
        'web_view',
        'cpu_added',
        'added ≤ 0.05',
        lambda v: v <= 0.05,
        '%+.3f',
    ),
    ('  real-time factor, no page open', 'web_view', 'rtf_closed', '', None, '%.3f'),
    (
        '  real-time factor, page open',
        'web_view',
        'rtf_open',
        '1.00 ± 0.01',
        lambda v: abs(v - 1.0) <= 0.01,
        '%.3f',
    ),
    (
        'camera 640x480 asked rate (images per sim s)',
        'web_view',
        'camera_asked_hz',
        '',
        None,
        '%.1f',
    ),
    (
        '  delivered at real time (images per sim s)',
        'web_view',
        'camera_hz',
        '≥ 29.7',
        lambda v: v >= 29.7,
        '%.2f',
    ),
]
# a 100 000-point FollowJointTrajectory goal sent to gazebo.launch controllers:=trajectory at real
# time (bench/big_goal.py): the world's pace while it receives the goal (issue 22's bounds)
ROWS += [
    (
        '100 000-point trajectory goal: longest /clock gap (ms)',
        'big_goal',
        'gap_ms',
        '≤ 100',
        lambda v: v <= 100,
        '%.0f',
    ),
    ('  the same window before the goal (ms)', 'big_goal', 'gap_before_ms', '', None, '%.0f'),
    (
        '  real-time factor while it is received',
        'big_goal',
        'rtf',
        '≥ 0.97',
        lambda v: v >= 0.97,
        '%.3f',
    ),
]
# a 50 MB description spawned into gazebo.launch at real time (bench/big_description.py): the
# world's pace while it receives, parses and loads it (issue 22, case 7)
ROWS += [
    (
        '50 MB description spawned: longest /clock gap (ms)',
        'big_description',
        'gap_ms',
        '≤ 100',
        lambda v: v <= 100,
        '%.0f',
    ),
    (
        '  the same window before the spawn (ms)',
        'big_description',
        'gap_before_ms',
        '',
        None,
        '%.0f',
    ),
    (
        '  real-time factor while it is spawned',
        'big_description',
        'rtf',
        '≥ 0.97',
        lambda v: v >= 0.97,
        '%.3f',
    ),
    ('  spawn answered after (s)', 'big_description', 'answer_s', '', None, '%.2f'),
]
# a subscribed depth camera's frame, 640x480, all of it off the physics thread (bench/depth.py)
ROWS += [
    ('depth camera frame cost (ms)', 'depth_camera', 'frame_ms', '', None, '%.1f'),
    ('  of which rendering, depth in metres (ms)', 'depth_camera', 'render_ms', '', None, '%.1f'),
    (
        '  of which the point cloud, built, serialized (ms)',
        'depth_camera',
        'point_cloud_ms',
        '',
        None,
        '%.1f',
    ),
    (
        '  of which the 32FC1 image, built, serialized (ms)',
        'depth_camera',
        'depth_image_ms',
        '',
        None,
        '%.1f',
    ),
]


# the move_group stand-in (bench/moveit.py): the MoveIt tutorial's goals planned on the ROS-free
# core (toy Panda), CPU seconds of the planning process (load does not inflate them), median and
# p95 over 20 plans; and the CPU of an idle move_group node receiving joint_states at 100 Hz
MOVEIT_PLANS = [
    ('tutorial joint goal', 'joint_goal'),
    ('pose goal (IK + plan)', 'pose_goal'),
    ('Cartesian path (3 waypoints, 1 cm steps)', 'cartesian'),
    ('joint goal among 20 boxes', 'cluttered_joint_goal'),
]
ROWS += [
    row
    for i, (label, key) in enumerate(MOVEIT_PLANS)
    for row in (
        (
            ('move_group: ' if i == 0 else '  ') + label + ', CPU median (s)',
            'moveit_planning',
            key + '_cpu_median_s',
            '',
            None,
            '%.3f',
        ),
        ('    p95 (s)', 'moveit_planning', key + '_cpu_p95_s', '', None, '%.3f'),
    )
]
ROWS += [
    ('  plans that failed', 'moveit_planning', 'failures', '0', lambda v: v == 0, '%d'),
    (
        'move_group idle, joint_states at 100 Hz (fraction of a core)',
        'moveit_idle',
        'cpu_core_fraction',
        '≤ 0.05',
        lambda v: v <= 0.05,
        '%.3f',
    ),
]


Results = Dict[str, Any]  # results.json: machine, quick, figures, raw


def rows(results: Results) -> Iterator[Tuple[str, str, str, str, str]]:
    fig = results['figures']
    for label, key, field, goal, check, fmt in ROWS:
        if key not in fig:
            continue
        value = fig[key] if field is None else fig[key].get(field)
        if value is None:
            continue
        median = value['median']
        spread = (
            '%s – %s (%d runs)' % (fmt % value['min'], fmt % value['max'], value['runs'])
            if 'min' in value
            else ''
        )
        verdict = '' if check is None else ('met' if check(median) else 'NOT met')
        yield label, fmt % median, spread, goal, verdict


def table(results: Results) -> str:
    lines = ['| figure | median | spread | goal | |', '|---|---|---|---|---|']
    lines += ['| %s | %s | %s | %s | %s |' % r for r in rows(results)]
    return '\n'.join(lines)


def write_markdown(results: Results, path: str) -> str:
    m = results['machine']
    text = table(results)
    from .render import render_section
    from .soak.report import existing_section

    soak = existing_section(path)  # make soak's section outlives a new make bench
    with open(path, 'w') as f:
        f.write(
            '# Benchmarks\n\n'
            'Made by `make bench` (`python -m _arm1sim.bench`); the raw numbers are in '
            '`bench/results.json`, the plot in `bench/bench.png`. Every figure below comes '
            'from one run of that command, the stand-in and the bare pybullet loop measured '
            'side by side.\n\n'
            'Machine: %s, %s cores, Linux %s, Python %s, pybullet %s; %s.%s%s\n\n'
            % (
                m['cpu'] or 'unknown CPU',
                m['cores'],
                m['kernel'],
                m['python'],
                m['pybullet'],
                m['date'],
                ' Load average as the run ended (1, 5, 15 min): %.1f, %.1f, %.1f: other work '
                'shared the machine.' % tuple(m['load_average'])
                if m.get('load_average')
                else '',
                ' **Quick run (smoke): one short run each.**' if results['quick'] else '',
            )
        )
        f.write(text + '\n')
        f.write(unmet_section(results))
        f.write(profile_section(results))
        f.write(render_section(results))
        f.write(METHOD)
        if soak:
            f.write('\n' + soak)
    return text


def unmet_section(results: Results) -> str:
    """Why a goal is not met, with this run's own figures and what was tried (facts measured
    with the code as it is; see BENCHMARKS.md's notes)."""
    fig = results['figures']

    def med(key: str, field: str) -> Optional[float]:
        return fig[key][field]['median'] if key in fig and field in fig[key] else None

    out = []
    ratio = fig.get('speed_ratio', {}).get('median')
    bare, standin = med('bare', 'steps_per_s'), med('standin_1', 'steps_per_s')
    if ratio is not None and ratio < 0.6 and bare and standin:
        out.append(
            '- **Speed ratio %.2f (goal 0.6).** A bare step takes %.1f µs, a stand-in step '
            '%.1f µs; the goal needs %.1f µs. Both share pybullet\'s step and its joint read '
            'and torque write; the rest of the stand-in\'s step is what ros_control and '
            'gazebo_ros add around them (profile below): the controllers\' update (now one '
            'pass per controller type, the PID inline: 0.3 µs a joint), the hardware '
            'interface\'s read and saturation, joint_states and /clock written to their '
            'subscribers (a loopback write costs about 25 µs, one every few steps at top '
            'speed), and per-step checks of the state topics and the camera. Timed apart at '
            'top speed (2026-11-23, perf_counter around each part, each timing adding about '
            '0.3 µs): pybullet\'s step 6.5 µs; controller manager and hardware interface 7.4 '
            'µs, of which joint_states 1.9 (a 38 µs publish every 20 steps), the read 2.4 and '
            'write 1.8 (with pybullet\'s calls, 2.1 µs), the four position controllers about '
            '1.3; /clock 1.0; gazebo_ros\'s per-step state-topic checks 0.7; the camera\'s due '
            'check 0.4. Tried: numpy for '
            'the four joints\' PID and saturation costs 9 µs a step against 1.3 µs for the '
            'inline Python, so the per-joint path stays in plain Python.'
            % (ratio, 1e6 / bare, 1e6 / standin, 1e6 / bare / 0.6)
        )
    cpu, floor = med('realtime', 'cpu_core_fraction'), med('idle_world', 'cpu_core_fraction')
    upright = med('realtime', 'cpu_core_fraction_upright')
    wake = med('idle_world', 'sleep_wakeup_cpu_us')
    if cpu is not None and cpu > 0.10 and floor is not None:
        out.append(
            '- **CPU at real time %.3f of a core (goal 0.10).** As launched, arm1 lies where '
            'it fell in the half second before the spawner started its controllers (as in '
            'Gazebo: efforts are zero until then), link4 resting on the ground, and pybullet '
            'solves that resting contact every step: arm1 lying so, pybullet\'s step alone '
            'costs 73-85 µs back to back with link4\'s convex pieces, 40 µs with its one hull '
            'and 8-9 µs with nothing touching (measured apart, ROS-free, 2026-11-27). The same '
            'launch with arm1 commanded upright: %s. An empty world costs %.3f: a '
            '1 kHz world sleeps and wakes 500 times a second at two steps a wake-up (one '
            'wake-up: %.0f µs of CPU on this virtual machine). Tried: more steps per wake-up '
            '(world_loop.STEPS_PER_WAKE 10 and 20 against 2, launched world, interleaved: '
            'medians 0.191 and 0.180 against 0.203 core-seconds per simulated second; '
            '2026-11-28, a /clock period\'s ten steps a wake-up: 0.179-0.186 against '
            '0.186-0.198, but command latency p99 1.9-2.1 ms against 1.2-1.3, so not kept). '
            'The first step after a gap of wall time costs more the longer the gap, slept or '
            'spun (ROS-free, arm1 upright, 2026-11-28: 25-58 µs after 0.1 ms, 245-285 µs '
            'after 10 ms, 10-18 back to back): the machine evicts the world\'s working set '
            'per wall second, not per wake-up. '
            'Contacts with static scenery are solved only within 0.5 mm (2026-11-27: 0.188 '
            'before, 0.13-0.16 after). Measured apart (ROS-free, back to back, 2026-11-28, '
            'a loaded machine), the whole simulation step, not pybullet\'s alone: lying 57 µs '
            'against 17 upright; each link as '
            'its hull 35-38; the pieces against everything but the ground and a hull on a '
            'fixed child link against the ground only (pybullet\'s collision filter in its '
            'AND mode) 49, 42 with solverResidualThreshold 1e-5: the extra links take back '
            'half of what the hull saves, short of the goal. Left: a cheaper resting '
            'contact of a compound on the ground (putting the resting arm to sleep changed '
            'nothing: it never slept).'
            % (
                cpu,
                'not measured in this run' if upright is None else '%.3f of a core' % upright,
                floor,
                float('nan') if wake is None else wake,
            )
        )
    p99, p50 = med('latency', 'p99_ms'), med('latency', 'p50_ms')
    if p99 is not None and p99 > 2.0:
        out.append(
            '- **Command latency p99 %.2f ms (goal 2), p50 %.2f ms.** A command waits for the '
            'next step (at most 1 ms at one step per wake-up) and for its delivery from the '
            'publisher\'s process; the tail is scheduling: with other work on the 2 cores the '
            'world or the publisher waits for a core. In the same conditions (500 commands, '
            'load average about 4) the code before this round gave p99 2.2-3.6 ms; the quiet '
            'run of 2026-11-23 13:07 gave 1.30 ms.'
            % (p99, p50 if p50 is not None else float('nan'))
        )
    scaling = fig.get('scaling_8', {}).get('median')
    if scaling is not None and scaling < 0.8:
        out.append(
            '- **8 arms scale at %.2f of linear (goal 0.8).** Each arm brings its own '
            'controller manager, joint_states publisher and pybullet body; a run this far from '
            'linear on a shared 2-core machine usually means other work took the cores (see '
            'the spread).' % scaling
        )
    if not out:
        return ''
    return '\n## Goals not met, and why\n\n' + '\n'.join(out) + '\n'


# The split of the profiled run before the one-pass control path (make bench of
# 2026-11-23 13:07 UTC, code at 8ec20fc), next to this run's.
PROFILE_BEFORE = {
    'controllers, PID, controller manager (Python)': 0.30,
    'hardware interface, robot, simulation step (Python)': 0.18,
    'pybullet stepSimulation': 0.18,
    'Python built-ins (min, max, isfinite, ...) and the rest': 0.12,
    'ROS publishing (messages, rospy, sockets)': 0.11,
    'pybullet joint read / torque write': 0.07,
    'world loop, clock, pacing': 0.05,
}


def profile_section(results: Results) -> str:
    """Where the stand-in's step goes, from the profiled top-speed run, next to before."""
    runs = results['raw'].get('profile')
    if not runs:
        return ''
    shares = runs[0]['profile_share']
    lines = [
        '',
        '## Where a stand-in step goes',
        '',
        'cProfile of the physics thread at top speed (1 arm). Profiling slows Python code '
        'more than pybullet\'s C++, so Python\'s real share is somewhat smaller. "Before": '
        'the same measurement before the one-pass control path (2026-11-23 13:07 UTC, 8ec20fc).',
        '',
        '| part | share of the physics thread | before |',
        '|---|---|---|',
    ]
    lines += [
        '| %s | %.0f %% | %s |'
        % (k, 100 * v, '%.0f %%' % (100 * PROFILE_BEFORE[k]) if k in PROFILE_BEFORE else '')
        for k, v in sorted(shares.items(), key=lambda kv: -kv[1])
    ]
    steps = runs[0].get('profiled_steps_per_s')
    if steps:
        lines += [
            '',
            'Steps per second while profiled: %.0f (before: about 15 000, the same '
            'measurement at 8ec20fc).' % steps,
        ]
    return '\n'.join(lines) + '\n'


METHOD = '''
## How each figure is measured

- **bare pybullet loop**: arm1 (same URDF and meshes) in pybullet DIRECT, a ground plane; each
  step reads the four joints, computes a PD in plain Python, applies the torques and steps.
  No ROS, none of our classes: the ceiling for anything built on pybullet in Python.
  Also its CPU time (process) per step, and the stand-in's: their ratio is what a loaded
  machine leaves alone (steps per wall second count the waits for a core).
- **stand-in top speed**: the world node's own code (`start_world`, `WorldNode.run`) with
  `real_time_update_rate` 0, all five controllers running, `/clock` at 100 Hz sim time and
  joint_states at 50 Hz sim time with a subscriber in another process (`rostopic hz`, as
  robot_state_publisher would be). N arms: N copies of arm1, each in its own namespace
  (`/arm1` … `/armN`) with its own controller manager and five controllers.
- **real time**: `roslaunch arm1 gazebo.launch gui:=false`, watched from another process:
  real-time factor = sim time advanced (from `/clock`) over wall time, joint_states rate =
  messages over their sim-time span; CPU = user+system time of the world process (`/gazebo`)
  over wall time; peak memory = its VmHWM. Then arm1 commanded upright (its four position
  controllers to 0; as launched it lies where it fell before its controllers started) and,
  3 s later, the world's CPU again over up to 20 s ("upright").
- **start-up**: from starting `roslaunch arm1 gazebo.launch gui:=false` (master included,
  nothing running before) to the first `/arm1/joint_states` message.
- **command latency**: a separate process publishes 1 000 distinct joint1 targets at 100 Hz;
  the world records the wall time of the first control update that uses each one.
- **the floor**: the world node with no robot at real time (CPU over 20 s), and the CPU of
  one 0.9 ms `time.sleep` (2 000 of them).
- **robot_spawn.launch**: `roslaunch arm1 robot_spawn.launch gui:=false` (the world, arm1
  with its camera at 30 Hz, arm_mover, look_away watching the camera), 5 s after the first
  joint_states: user + system CPU of the roslaunch process and everything it started (the
  master included) over 20 s of wall time, split by process.
- **/gazebo/model_states subscribed**: stand-in top speed, 1 arm, with `rostopic hz
  /gazebo/model_states` in another process; its cost per step is the difference of the two
  step times.
- **depth camera frame cost**: a 640 × 480 gazebo_ros_openni_kinect camera 2.4 m from a wall,
  in one process: the render process's work (default renderer: RGB and depth buffer, depth
  to metres) plus the plugin's (the 32FC1 depth image and the x y z rgb PointCloud2, each
  built and serialized), median of 60 frames each. None of it runs on the physics thread.
'''
