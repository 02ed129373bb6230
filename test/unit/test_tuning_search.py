"""``tune --search`` on arm1, checked by independent step runs in a fresh simulation.

A small search budget keeps this under ~20 s; the real one (``rosrun arm1 tune
--search``) runs about ten times as many candidates.
"""
import io
import os

import yaml

from arm1.tuning import cli
from arm1.tuning.search import Evaluator, GainSearch, score
from arm1.tuning.steps import StepRig
from conftest import REPO_ROOT


def find(pkg):
    if pkg == 'arm1':
        return REPO_ROOT
    raise LookupError(pkg)


def total(rig, gains, joints, protocol, criteria):
    rig.gains = {j: dict(g) for j, g in gains.items()}
    out = {}
    for j in joints:
        run = rig.run(j, protocol)
        out[j] = score(run.metrics, criteria, protocol.hold, run.others_jitter)
    return out


def test_search_result_holds_up_in_an_independent_run(arm1_urdf, controllers_params):
    setup = cli.Setup(cli.parse_args([]))
    make = lambda: StepRig(arm1_urdf, controllers_params, setup.world, find)  # noqa: E731
    evaluator = Evaluator(make, workers=2)
    try:
        probe = make()
        joints, seed = probe.joints, {j: dict(g) for j, g in probe.gains.items()}
        effort = {j: probe.hw.handles[j].limits.effort for j in joints}
        probe.close()
        search = GainSearch(evaluator, joints, seed, effort, setup.protocol, setup.criteria,
                            rounds=1, runs_per_joint=14, seed=0)
        found = search.run()
    finally:
        evaluator.close()
    # independent: a fresh simulation whose controllers load the found gains from parameters
    params = cli.with_gains(controllers_params, '/arm1',
                            {j: '%s_position_controller' % j for j in joints}, found)
    check = StepRig(arm1_urdf, params, setup.world, find)
    try:
        after = total(check, check.gains, joints, setup.protocol, setup.criteria)
        before = total(check, seed, joints, setup.protocol, setup.criteria)
    finally:
        check.close()
    # never worse than the seed, as the search promises, and the same numbers it saw
    assert sum(a[1] for a in after.values()) <= sum(b[1] for b in before.values()) + 1e-9
    assert sum(a[1] for a in after.values()) == search.set_value
    for joint in joints:  # each joint meets the criteria in the check iff it did in the search
        feasible, value, _, fails = search.set_results[joint]
        assert after[joint][0] == feasible and after[joint][1] == value, (joint, fails)


def test_tune_command_prints_metrics_snippet_and_plots(tmp_path):
    out = io.StringIO()
    save = os.path.join(str(tmp_path), 'tuned.yaml')
    rc = cli.main(['--search', '--rounds', '1', '--runs', '4', '--joints', 'joint1',
                   '--hold', '1.0', '--plot', str(tmp_path), '--save', save], out=out)
    text = out.getvalue()
    assert rc == 0, text
    assert 'current gains' in text and 'found gains' in text
    assert 'joint1   out' in text and 'overshoot' in text
    assert '  joint1_position_controller:\n' in text and '    pid: {p: ' in text
    saved = yaml.safe_load(open(save))
    assert saved['arm1']['joint1_position_controller']['type'] == \
        'effort_controllers/JointPositionController'
    assert saved['arm1']['joint_state_controller']['publish_rate'] == 50
    for name in ('joint1.png', 'overview.png'):
        assert os.path.getsize(os.path.join(str(tmp_path), name)) > 10000
