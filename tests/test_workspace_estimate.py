"""The 3-RPR, 3-PRR and five-bar workspace kinds' estimates (:mod:`planar_tui.workspace.paving.estimate`):
a job over the memory or time limit refused before it runs (one line, exit code 2, nothing
written), the estimated box count against the count of real runs on the bundled designs, the
boundary length it rests on against a closed form, and sweeps and optimisations over these
kinds run end to end, or refused with their estimate."""

from __future__ import annotations

import csv
import dataclasses
import math

import pytest

from planar_tui.errors import ExitCode, PresetError
from planar_tui.presets import load_preset
from planar_tui.progress import Progress
from planar_tui.registry import JOB_KINDS
from planar_tui.workspace.paving.estimate import MIN_BOXES, _geometry, estimate_boxes
from tests.conftest import PRESETS
from tests.sweep_presets import one_line

#: A small job of each kind, its precision a placeholder.
JOBS = {
    "workspace3rpr": """[robot3rpr]
name = "paper B's scale"

[[workspace3rpr]]
leg_limits_cm = [[20, 80], [20, 80], [20, 80]]
orientation_deg = 30
precision_cm = {precision}
geometric_reference = false
output = "w.csv"
""",
    "workspace3prr": """[robot3prr]
name = "paper B's scale"

[[workspace3prr]]
precision_cm = {precision}
geometric_reference = false
output = "w.csv"
""",
    "workspace5r": """[robot5r]
base_separation_cm = 40
proximal_cm = [45, 45]
distal_cm = [55, 55]
joint_limits_deg = [[-60, 180], [0, 240]]
working_mode = "+-"

[[workspace5r]]
precision_cm = {precision}
geometric_reference = false
output = "w.csv"
""",
}
#: A robot value of each kind that a sweep or an optimisation varies, and its range.
VARIED = {
    "workspace3rpr": ("leg_limits_cm[1][2]", 70, 80),
    "workspace3prr": ("robot3prr.distal_cm[1]", 35, 45),
    "workspace5r": ("robot5r.distal_cm[1]", 50, 55),
}


def preset(tmp_path, kind, precision, extra=""):
    path = tmp_path / f"{kind}.toml"
    path.write_text(JOBS[kind].format(precision=precision) + "\n" + extra, encoding="utf-8")
    return path


@pytest.mark.parametrize("kind", sorted(JOBS))
def test_an_over_limit_job_of_each_kind_is_refused_with_its_estimate(tmp_path, cli, kind):
    """At ε = 1e-9 cm a 100 cm robot's boundary takes about 1e12 boxes: hundreds of TiB
    (the limit is half the memory), refused when read, in the preset or on the command line."""
    out = tmp_path / "out"
    result = cli("run", preset(tmp_path, kind, "1e-9"), "--out-dir", out)
    assert result.exit_code == ExitCode.BAD_INPUT
    line = one_line(result)
    assert f"{kind}[1].precision_cm: is 1e-09 cm: about " in line
    assert " boxes, needs about " in line and "TiB of memory (limit " in line
    result = cli(kind, preset(tmp_path, kind, "1"), "--precision", "1e-9", "--out-dir", out)
    assert result.exit_code == ExitCode.BAD_INPUT
    assert one_line(result).startswith("error: command line: --precision: is 1e-09 cm: about ")
    assert not out.exists()


def bundled(name, index, scale, **changes):
    """Job ``index`` of the bundled preset ``name`` with its precisions times ``scale``."""
    job = load_preset(PRESETS / name).jobs[index]
    spec = job.spec
    for key in ("precision_cm", "refine_precision_cm", "singularity_precision_cm"):
        if getattr(spec, key, None) is not None:
            changes.setdefault(key, getattr(spec, key) * scale)
    return dataclasses.replace(job, spec=dataclasses.replace(spec, **changes))


def counted_boxes(job):
    """The boxes a real run processes (paving, refinement, singularities, circle)."""
    kind = JOB_KINDS[job.kind]
    result = kind.run(kind.prepare_job(job), Progress())
    singular = result.singularity
    companions = sum(o.boxes_processed for o in (result.companions or {}).values())
    singular_boxes = 0 if singular is None else singular.boxes_processed
    return result.outcome.boxes_processed + singular_boxes + companions


#: The bundled designs' jobs (preset, job index, changes to the job's own settings).
BUNDLED = [
    ("workspace-3rpr.toml", 0, {}),
    ("workspace-3rpr.toml", 1, {}),
    ("workspace-3rpr.toml", 1, {"tolerance_cm": 0.1, "tolerance_mode": "all"}),
    ("workspace-3prr.toml", 0, {}),
    ("workspace-3prr.toml", 0, {"singularities": True}),
    ("workspace-3prr.toml", 0, {"tolerance_cm": 0.1, "tolerance_mode": "some"}),
    ("fivebar-illustrative.toml", 0, {}),
    ("fivebar-illustrative.toml", 1, {}),
    ("fivebar-illustrative.toml", 0, {"tolerance_cm": 0.1, "tolerance_mode": "all"}),
    ("fivebar-illustrative.toml", 0, {"tolerance_cm": 0.1, "tolerance_mode": "some"}),
    ("workspace-3prr.toml", 0, {"tolerance_cm": 0.1, "tolerance_mode": "all"}),
]
#: The stated factor between the estimated and the counted boxes.
FACTOR = 2.0


def within_factor(job):
    estimated, counted = estimate_boxes(job.kind, job.robot, job.spec), counted_boxes(job)
    assert counted / FACTOR <= estimated <= FACTOR * counted, (estimated, counted)


@pytest.mark.parametrize(("name", "index", "changes"), BUNDLED)
def test_the_estimate_is_within_a_factor_2_of_the_counted_boxes(name, index, changes):
    """At 4x the bundled precisions (a fraction of a second each)."""
    within_factor(bundled(name, index, 4.0, geometric_reference=False, **changes))


@pytest.mark.slow
@pytest.mark.parametrize(("name", "index", "changes"), BUNDLED)
def test_the_estimate_is_within_a_factor_2_at_the_bundled_precisions(name, index, changes):
    within_factor(bundled(name, index, 1.0, geometric_reference=False, **changes))


@pytest.mark.parametrize(("lo", "hi"), [(0.0, 30.0), (20.0, 80.0)])
def test_the_boundary_length_is_the_closed_form_of_concentric_annuli(tmp_path, lo, hi):
    """Legs whose annuli share their centre (the platform's points at the base joints'
    places, φ = 0): the workspace is one annulus, its boundary 2π(lo + hi); the 32-gons
    are within 1 % of the circles."""
    text = f"""[robot3rpr]
base_joints_cm = [[0, 0], [1, 0], [0, 1]]
platform_points_cm = [[0, 0], [1, 0], [0, 1]]

[[workspace3rpr]]
leg_limits_cm = [[{lo}, {hi}], [{lo}, {hi}], [{lo}, {hi}]]
precision_cm = 0.5
output = "w.csv"
"""
    path = tmp_path / "annulus.toml"
    path.write_text(text, encoding="utf-8")
    (job,) = load_preset(path).jobs
    length, _ = _geometry(job.kind, job.robot, job.spec)
    assert length == pytest.approx(2 * math.pi * (lo + hi), rel=0.01)
    expected = 10.0 * 2 * math.pi * (lo + hi) / 0.5 + MIN_BOXES
    assert estimate_boxes(job.kind, job.robot, job.spec) == pytest.approx(expected, rel=0.01)


def rows(path):
    with open(path, newline="", encoding="utf-8") as stream:
        return list(csv.DictReader(stream))


@pytest.mark.parametrize("kind", sorted(JOBS))
def test_a_sweep_of_each_kind_runs_end_to_end(tmp_path, cli, kind):
    key, lo, hi = VARIED[kind]
    sweep = f'[[sweep]]\njob = "{kind}"\nvalues."{key}" = [{lo}, {hi}]\noutput = "s.csv"\n'
    result = cli(
        "sweep", preset(tmp_path, kind, "2", sweep), "--out-dir", tmp_path / "out", "--workers", "1"
    )
    assert result.exit_code == 0, result.output
    found = rows(tmp_path / "out" / "s.csv")
    assert [row["status"] for row in found] == ["ok", "ok"]
    assert [float(row[key]) for row in found] == [lo, hi]
    inside = [float(row["area_inside_cm2"]) for row in found]
    assert all(0 < a <= float(row["area_kept_cm2"]) for a, row in zip(inside, found, strict=True))
    assert inside[0] < inside[1]  # a longer leg or link reaches more


@pytest.mark.parametrize("kind", sorted(JOBS))
def test_a_sweep_of_long_points_of_each_kind_is_refused_with_its_estimate(tmp_path, cli, kind):
    """10 000 points at ε = 0.0005 cm (each a few hundred MiB and tens of seconds, within
    the limits): days of computing on one worker, refused before anything runs."""
    key, lo, hi = VARIED[kind]
    sweep = (
        f'[[sweep]]\njob = "{kind}"\n'
        f'values."{key}" = {{ from = {lo}, to = {hi}, count = 10000 }}\noutput = "s.csv"\n'
    )
    result = cli(
        "sweep",
        preset(tmp_path, kind, "0.0005", sweep),
        "--out-dir",
        tmp_path / "out",
        "--workers",
        "1",
    )
    assert result.exit_code == ExitCode.BAD_INPUT
    line = one_line(result)
    assert "sweep[1]: 10,000 points need about " in line and "days of computing" in line
    assert not (tmp_path / "out").exists()


OPTIMISE = """[[optimise]]
job = "workspace3prr"
variables."robot3prr.distal_cm[1]" = {{ from = 35, to = 45 }}
maximise = "area_inside_cm2"
coarse = {{ precision_cm = 4 }}
budget = {budget}
population = 4
seed = 1
output = "o.csv"
"""


def test_an_optimisation_over_a_3prr_link_runs_end_to_end(tmp_path, cli):
    """The longest distal link reaches most: the optimum is near the upper end, its
    certified re-run at the job's own precision."""
    path = preset(tmp_path, "workspace3prr", "2", OPTIMISE.format(budget=8))
    result = cli("optimise", path, "--out-dir", tmp_path / "out", "--workers", "1")
    assert result.exit_code == 0, result.output
    evaluations = rows(tmp_path / "out" / "o.csv")
    assert len(evaluations) == 8 and all(row["status"] == "ok" for row in evaluations)
    (optimum,) = rows(tmp_path / "out" / "o-optimum.csv")
    assert optimum["status"] == "ok" and float(optimum["precision_cm"]) == 2.0
    best = max(float(row["robot3prr.distal_cm[1]"]) for row in evaluations)
    assert float(optimum["robot3prr.distal_cm[1]"]) == best
    assert 0 < float(optimum["area_inside_cm2"]) <= float(optimum["area_kept_cm2"])


def test_an_optimisation_of_long_evaluations_is_refused_with_its_estimate(tmp_path, cli):
    text = OPTIMISE.format(budget=20000).replace("coarse = { precision_cm = 4 }\n", "")
    result = cli(
        "optimise",
        preset(tmp_path, "workspace3prr", "0.0005", text),
        "--out-dir",
        tmp_path / "out",
        "--workers",
        "1",
    )
    assert result.exit_code == ExitCode.BAD_INPUT
    line = one_line(result)
    assert "optimise[1]: 20,000 evaluations and 1 certified re-run(s) need about" in line
    assert "days of computing" in line
    assert not (tmp_path / "out").exists()


def test_the_five_bar_command_prints_its_map(tmp_path, cli):
    """The map view of a five-bar job (its result has no tolerance companions)."""
    result = cli(
        "workspace5r",
        PRESETS / "fivebar-illustrative.toml",
        "--precision",
        "2",
        "--out-dir",
        tmp_path,
    )
    assert result.exit_code == 0, result.output
    assert "workspace5r[2]: arc-distance, ε = 2 cm" in result.stdout
    assert "singularity-free" in result.stdout


@pytest.mark.parametrize("kind", sorted(JOBS))
def test_a_run_reports_its_estimate_and_warns_over_the_box_budget(tmp_path, kind):
    """The estimate is the progress figure ``boxes_estimate``; over ``box_budget`` the job
    is warned of, then stops at the budget (nothing written)."""
    from planar_tui.errors import JobError

    text = (
        JOBS[kind]
        .format(precision=0.5)
        .replace('output = "w.csv"', 'box_budget = 500\noutput = "w.csv"')
    )
    path = tmp_path / "p.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(PresetError, match=r"boxes, more than 4 × box_budget = 500"):
        load_preset(path)  # estimated past 4 × its budget: refused when read
    path.write_text(text.replace("box_budget = 500\n", ""), encoding="utf-8")
    (job,) = load_preset(path).jobs  # the run's own stop, for an estimate that falls short:
    job = dataclasses.replace(job, spec=dataclasses.replace(job.spec, box_budget=500))
    declared, progress = JOB_KINDS[kind], Progress()
    with pytest.raises(JobError, match="exceeded 500 boxes"):
        declared.run(declared.prepare_job(job), progress)
    expected = estimate_boxes(kind, job.robot, job.spec)
    assert progress.figures["boxes_estimate"] == expected > 500
    assert progress.warning.startswith(f"about {expected:,} boxes expected, more than box_budget")
    within = dataclasses.replace(job, spec=dataclasses.replace(job.spec, box_budget=10**7))
    progress = Progress()
    declared.run(declared.prepare_job(within), progress)
    assert progress.figures["boxes_estimate"] == expected and not progress.warning
