"""The 3-RPR, 3-PRR and five-bar kinds name their sweep columns without running
(``figure_names``, :mod:`planar_tui.workspace.paving.columns`): the names are the columns a run
reports (nominal, with singularities, with a tolerance, the geometric form), an
optimisation naming another column is refused before it runs, and a cancelled sweep of a
new kind resumes its finished points."""

from __future__ import annotations

import dataclasses

import pytest

from planar_tui.errors import Cancelled, ExitCode
from planar_tui.presets import load_preset
from planar_tui.progress import Progress
from planar_tui.registry import JOB_KINDS
from tests.sweep_presets import one_line
from tests.test_workspace_estimate import JOBS, VARIED, preset

#: Changes of each kind's small job (``JOBS``) a run's columns may depend on.
VARIANTS = {
    "workspace3rpr": [
        {},
        {"singularities": True},
        {"form": "geometric"},
        {"tolerance_cm": 0.05, "tolerance_mode": "all"},
        {"tolerance_cm": 0.05, "tolerance_mode": "some"},
        {"kappa_max": 4.0},
    ],
    "workspace3prr": [
        {},
        {"singularities": True},
        {"form": "geometric"},
        {"tolerance_cm": 0.05, "tolerance_mode": "some"},
    ],
    "workspace5r": [
        {},
        {"singularities": True},
        {"form": "geometric"},
        {"singularities": True, "singularity_free_circle": (0.0, 60.0)},
        {"tolerance_cm": 0.05, "tolerance_mode": "all"},
    ],
}
CASES = [(kind, changes) for kind, variants in VARIANTS.items() for changes in variants]


@pytest.mark.parametrize(("kind", "changes"), CASES)
def test_the_named_columns_are_the_runs(tmp_path, kind, changes):
    (job,) = load_preset(preset(tmp_path, kind, "4")).jobs
    job = dataclasses.replace(job, spec=dataclasses.replace(job.spec, **changes))
    declared = JOB_KINDS[kind]
    result = declared.run(declared.prepare_job(job), Progress())
    assert declared.figure_names(job) == tuple(declared.point_figures(job, result))


@pytest.mark.parametrize("kind", sorted(JOBS))
def test_an_optimisation_naming_no_column_is_refused_before_it_runs(tmp_path, cli, kind):
    key, lo, hi = VARIED[kind]
    text = (
        f'[[optimise]]\njob = "{kind}"\nvariables."{key}" = {{ from = {lo}, to = {hi} }}\n'
        'maximise = "area_insde_cm2"\nbudget = 4\npopulation = 4\noutput = "o.csv"\n'
    )
    result = cli("optimise", preset(tmp_path, kind, "2", text), "--out-dir", tmp_path / "out")
    assert result.exit_code == ExitCode.BAD_INPUT
    line = one_line(result)
    assert "optimise[1]: names the column 'area_insde_cm2', not one of the job's" in line
    assert "area_inside_cm2" in line
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("kind", sorted(JOBS))
def test_a_cancelled_sweep_resumes_its_finished_points(tmp_path, kind, monkeypatch):
    from planar_tui.sweep import execute
    from planar_tui.sweep.service import run_sweep
    from planar_tui.sweep.spec import parse_sweeps

    key, lo, hi = VARIED[kind]
    text = f'[[sweep]]\njob = "{kind}"\nvalues."{key}" = [{lo}, {hi}]\noutput = "s.csv"\n'
    (sweep,) = parse_sweeps(load_preset(preset(tmp_path, kind, "4", text)))
    out, progress = tmp_path / "out", Progress()
    with pytest.raises(Cancelled):
        run_sweep(sweep, progress, out_dir=out, on_outcome=lambda o: progress.request_cancel())
    computed = []
    real = execute.run_point
    monkeypatch.setattr(
        execute, "run_point", lambda task, p=None: computed.append(task.number) or real(task, p)
    )
    run = run_sweep(sweep, out_dir=out, resume=True)
    assert run.resumed == 1 and computed == [2]
    assert len(run.table.rows) == 2
