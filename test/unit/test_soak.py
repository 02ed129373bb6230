"""make soak's judging and report: the goals' verdicts, per-minute rows, the BENCHMARKS.md
section."""

import pytest

from _arm1sim.bench.soak import judge, report


def samples(minutes=5.0, rtf=1.0, rss0=100.0, rss_growth=0.0, stall=None, step=2.0):
    """Synthetic samples every `step` s: sim time at `rtf`, RSS growing linearly, one stall."""
    out, sim, t = [], 10.0, 0.0
    while t <= 60 * minutes:
        lost = stall[1] if stall and abs(t - stall[0]) < step / 2 else 0.0
        sim += 0.0 if t == 0 else rtf * step - lost
        out.append(
            {
                't': t,
                'clock_wall': 1000.0 + t,
                'sim': sim,
                'joint_states': int(50 * (sim - 10.0)),
                'images': int(30 * (sim - 10.0)),
                'images_late': 0,
                'world_rss_mb': rss0 * (1 + rss_growth * t / (60 * minutes)),
                'render_rss_mb': 160.0,
                'world_threads': 20,
                'world_cpu_s': 0.15 * t,
                'render_cpu_s': 0.6 * t,
                'session_cpu_s': t,
                'machine_busy_s': 1.2 * t,
                'load1': 1.0,
            }
        )
        t += step
    return out


def test_real_time_and_flat_memory_meet_both_goals():
    fig = judge.judge(samples(), 60)
    assert fig['rtf'] == pytest.approx(1.0) and fig['rtf_ok'] and fig['rss_ok']
    assert fig['joint_states_hz'] == pytest.approx(50, rel=0.01)
    assert fig['images_hz'] == pytest.approx(30, rel=0.01)
    assert fig['other_cpu_cores'] == pytest.approx(0.2)


def test_sim_time_two_tenths_of_a_percent_slow_misses_the_rtf_goal():
    fig = judge.judge(samples(rtf=0.998), 60)
    assert not fig['rtf_ok']
    assert fig['drift_pct'] == pytest.approx(-0.2, abs=0.01)


def test_one_stall_is_found_and_counted_in_the_drift():
    fig = judge.judge(samples(stall=(150.0, 0.4)), 60)
    assert fig['worst_loss_s'] == pytest.approx(0.4) and fig['worst_loss_at_s'] == 150.0
    assert fig['losses_over_50ms'] == 1
    assert fig['drift_s'] == pytest.approx(-0.4)


def test_memory_growing_past_five_percent_misses_the_rss_goal_and_below_meets_it():
    assert not judge.judge(samples(minutes=10, rss_growth=0.08), 60)['rss_ok']
    assert judge.judge(samples(minutes=10, rss_growth=0.04), 60)['rss_ok']


def test_warm_up_growth_is_left_out():
    data = samples(minutes=5)
    for s in data:
        if s['t'] < 60:
            s['world_rss_mb'] = 50.0  # memory still filling during the warm-up
    assert judge.judge(data, 60)['rss_ok']


def test_one_row_per_whole_minute():
    rows = judge.minute_rows(samples(minutes=5))
    assert [r['minute'] for r in rows] == [1, 2, 3, 4, 5]
    assert all(r['rtf'] == pytest.approx(1.0) for r in rows)
    assert report.format_row(rows[0]).split()[0] == '1'


def test_section_replaces_the_previous_one_and_keeps_the_rest(tmp_path):
    path = tmp_path / 'BENCHMARKS.md'
    path.write_text('# Benchmarks\n\ntable\n')
    first = report.SECTION_BEGIN + '\n## Soak\nrun 1\n' + report.SECTION_END + '\n'
    report.replace_section(str(path), first)
    report.replace_section(str(path), first.replace('run 1', 'run 2'))
    text = path.read_text()
    assert text.startswith('# Benchmarks\n\ntable\n')
    assert 'run 2' in text and 'run 1' not in text and text.count('## Soak') == 1
    assert report.existing_section(str(path)) == first.replace('run 1', 'run 2')


def test_markdown_names_goals_and_other_load():
    data = samples(minutes=3)
    result = {
        'figures': judge.judge(data, 60),
        'minutes': judge.minute_rows(data),
        'minutes_asked': 3,
        'machine': {'date': 'today', 'cpu': 'cpu', 'cores': 2},
    }
    text = report.markdown(result)
    assert '| real-time factor after the warm-up | 1.00000 | 1 ± 0.001 | met |' in text
    assert 'Other work ran on the machine' in text


def test_markdown_explains_stalls_and_skipped_frames_only_when_there_are_some():
    def text(data):
        return report.markdown(
            {
                'figures': judge.judge(data, 60),
                'minutes': judge.minute_rows(data),
                'minutes_asked': 3,
                'machine': {'date': 'd', 'cpu': 'c', 'cores': 2},
            }
        )

    smooth = samples(minutes=3)
    assert 'falls behind in steps' not in text(smooth) and 'skipped' not in text(smooth)
    stalled = samples(minutes=3, stall=(150.0, 0.3))
    for s in stalled:
        s['images'] = int(s['images'] * 0.8)  # a fifth of the frames skipped
    assert '1 of 2 minutes lost more than 50 ms' in text(stalled)
    assert 'Images arrive at 24.0 Hz of sim time, not 30' in text(stalled)
