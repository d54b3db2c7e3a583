"""The tolerance layers of the 3-RPR, 3-PRR and five-bar as the 3-RRR shows them: the
summary CSV's ``tolerance_mode`` and ``tolerance_<quantity>`` columns (before ``seconds``)
with the mode's bracket, the map's nominal and "some" layers beside the robust boxes, and
the figure overlaying the "some", nominal and robust workspaces (read back from its
collections)."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from planar_tui.jobkind import PreparedJob
from planar_tui.presets import load_preset
from planar_tui.progress import Progress
from planar_tui.workspace.paving.levels import INSIDE

PRESETS = {
    "workspace3rpr": (
        "[robot3rpr]\n[[workspace3rpr]]\nleg_limits_cm = [[30, 80], [25, 85], [35, 75]]\n"
        'orientation_deg = 20\nprecision_cm = 2\n{tolerance}\noutput = "o.csv"\n',
        ("base_joints_cm", "platform_points_cm"),
    ),
    "workspace3prr": (
        "[robot3prr]\n[[workspace3prr]]\norientation_deg = 15\nprecision_cm = 2\n"
        '{tolerance}\noutput = "o.csv"\n',
        ("slider_points_cm", "platform_points_cm", "distal_cm"),
    ),
    "workspace5r": (
        '[robot5r]\nworking_mode = "+-"\n[[workspace5r]]\nprecision_cm = 2\n{tolerance}\n'
        'output = "o.csv"\n',
        ("base_joints_cm", "proximal_cm", "distal_cm"),
    ),
}
KINDS = sorted(PRESETS)
TOLERANCE = 'tolerance_cm = 0.5\ntolerance_mode = "{mode}"'


def preset(tmp_path, kind, mode):
    path = tmp_path / f"{kind}.toml"
    path.write_text(PRESETS[kind][0].format(tolerance=TOLERANCE.format(mode=mode)), "utf-8")
    return path


def run_job(path):
    from planar_tui.registry import JOB_KINDS

    job = load_preset(path).jobs[0]
    kind = JOB_KINDS[job.kind]
    prepared = kind.prepare(job) if kind.prepare is not None else None
    return job, kind.run(PreparedJob(job, prepared), Progress())


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("mode", ["all", "some"])
def test_the_summary_csv_has_the_tolerance_columns_and_the_modes_bracket(cli, tmp_path, kind, mode):
    path = preset(tmp_path, kind, mode)
    result = cli(kind, path, "--out-dir", tmp_path / "out")
    assert result.exit_code == 0, result.output
    with open(tmp_path / "out" / "o.csv", encoding="utf-8") as f:
        header, *rows = list(csv.reader(f))
    columns = ["tolerance_mode", *(f"tolerance_{key}" for key in PRESETS[kind][1])]
    assert header[-1] == "seconds" and header[-1 - len(columns) : -1] == columns
    (row,) = [dict(zip(header, r, strict=True)) for r in rows]
    assert row["tolerance_mode"] == mode
    assert all(float(row[c]) == 0.5 for c in columns[1:])
    _, direct = run_job(path)  # the CSV's bracket is the mode's, the others in the summary
    assert float(row["area_inside_cm2"]) == direct.outcome.area_inside_cm2
    assert float(row["area_kept_cm2"]) == direct.outcome.area_kept_cm2
    other = "some" if mode == "all" else "all"
    assert set(direct.companions) == {"nominal", other}
    for name, outcome in direct.companions.items():
        bracket = f"{name} [{outcome.area_inside_cm2:.5g}, {outcome.area_kept_cm2:.5g}] cm2"
        assert bracket in direct.summary
    # the map: the robust boxes, and the nominal and "some" workspaces as their own layers
    assert "▓ nominal robot only" in result.stdout and "░ some robot only" in result.stdout
    assert "tolerance " + mode + " ±0.5 cm" in result.stdout


@pytest.mark.parametrize("kind", KINDS)
def test_the_brackets_nest_and_the_figure_overlays_them(tmp_path, kind):
    from planar_tui.figures.dispatch import figure_for_result

    job, result = run_job(preset(tmp_path, kind, "all"))
    outcomes = {"all": result.outcome, **result.companions}
    robust, nominal, some = outcomes["all"], outcomes["nominal"], outcomes["some"]
    assert robust.area_kept_cm2 < nominal.area_kept_cm2 < some.area_kept_cm2
    assert robust.area_inside_cm2 < nominal.area_inside_cm2 <= some.area_inside_cm2
    fig = figure_for_result(job, result)
    ax = fig.axes[0]
    layers = {c.get_gid(): c for c in ax.collections}
    expected = {
        "some-kept": len(some.boxes),
        "nominal-kept": len(nominal.boxes),
        "all-kept": len(robust.boxes),
        "all-inside": int(np.count_nonzero(robust.status == INSIDE)),
    }
    assert {gid: len(layers[gid].get_paths()) for gid in expected} == expected
    labels = {c.get_gid(): c.get_label() for c in ax.collections}
    assert f"{some.area_kept_cm2:.5g} cm2" in labels["some-kept"]
    assert f"{robust.area_inside_cm2:.5g} cm2" in labels["all-inside"]
    assert any(line.get_gid() == "exact" for line in ax.lines)
    fig.savefig(tmp_path / "f.png")


@pytest.mark.parametrize("kind", KINDS)
def test_a_some_job_paves_a_search_box_beyond_the_nominal_reach(tmp_path, kind):
    """Every robot within ±t reaches at most √2 Σ t farther than the nominal one (the 3-RPR's
    σ, the 3-PRR's σ + t_l, the five-bar's √2 t_A + t_1 + t_2 are below it): the default
    search box of a "some" job holds the nominal reach box grown by that margin, also at a
    precision whose power-of-two square fits the nominal reach box exactly (no slack).
    Checked to fail, in all three kinds, with `reach_margin_cm` returning 0."""
    import dataclasses
    import math

    from planar_tui.registry import JOB_KINDS

    job = load_preset(preset(tmp_path, kind, "some")).jobs[0]
    reach = (
        job.robot.reach_box_cm()
        if kind == "workspace5r"
        else job.spec.mechanism.reach_box(job.robot, job.spec)
    )
    tight = max(reach[1] - reach[0], reach[3] - reach[2]) / 32
    job = dataclasses.replace(job, spec=dataclasses.replace(job.spec, precision_cm=tight))
    result = JOB_KINDS[kind].run(PreparedJob(job, None), Progress())
    margin = math.sqrt(2.0) * 0.5 * len(PRESETS[kind][1])
    xlo, xhi, ylo, yhi = result.outcome.extent_cm
    assert xlo <= reach[0] - margin and reach[1] + margin <= xhi
    assert ylo <= reach[2] - margin and reach[3] + margin <= yhi


@pytest.mark.parametrize("kind", KINDS)
def test_a_some_jobs_search_box_must_hold_the_grown_reach(cli, tmp_path, kind):
    """The nominal reach box is a valid ``search_box_cm`` for the robust job, and refused
    (one line, exit 2) for the "some" job, whose robots reach farther."""
    from tests.test_workspace_3rpr import refused

    job = load_preset(preset(tmp_path, kind, "all")).jobs[0]
    reach = (
        job.robot.reach_box_cm()
        if kind == "workspace5r"
        else job.spec.mechanism.reach_box(job.robot, job.spec)
    )
    box = f"search_box_cm = [[{reach[0]!r}, {reach[1]!r}], [{reach[2]!r}, {reach[3]!r}]]\n"
    for mode in ("all", "some"):
        text = PRESETS[kind][0].format(tolerance=box + TOLERANCE.format(mode=mode))
        if mode == "all":
            (tmp_path / "ok.toml").write_text(text, "utf-8")
            assert load_preset(tmp_path / "ok.toml").jobs[0].spec.search_box_cm is not None
        else:
            refused(cli, tmp_path, kind, text, "search_box_cm")
