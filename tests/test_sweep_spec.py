"""[[sweep]] tables: the points a table makes, and every bad table refused with one line
(exit code 2, nothing written) before anything runs."""

from __future__ import annotations

import math

import pytest

from planar_tui.errors import PresetError
from planar_tui.presets import load_preset
from planar_tui.sweep.points import design, make_points
from planar_tui.sweep.spec import build_sweep, parse_sweeps
from tests.sweep_presets import TORQUES, TORQUES_BASE, WORKSPACE, WORKSPACE_BASE, write


def sweeps_of(tmp_path, sweep: str, template=WORKSPACE, base=WORKSPACE_BASE):
    return parse_sweeps(load_preset(write(tmp_path, "p.toml", template, sweep, **base)))


def test_grid_runs_like_nested_loops_first_key_slowest(tmp_path):
    (sweep,) = sweeps_of(
        tmp_path,
        """[[sweep]]
job = "workspace"
values."orientation_deg" = [-10, 0, 10]
values."robot3rrr.distal_cm" = { from = 28.0, to = 32.0, count = 3 }
""",
    )
    assert sweep.point_count == 9 and sweep.combine == "grid"
    assert list(design(sweep)) == [(o, d) for o in (-10, 0, 10) for d in (28.0, 30.0, 32.0)]
    points = make_points(sweep)
    assert [p.number for p in points] == list(range(1, 10))
    # the values reached the parsed jobs
    assert [(p.job.spec.orientation_deg, p.job.robot.distal_cm) for p in points] == [
        (float(o), d) for o in (-10, 0, 10) for d in (28.0, 30.0, 32.0)
    ]
    assert sweep.output == "p-sweep-1.csv"


def test_from_to_count_is_evenly_spaced_with_both_ends(tmp_path):
    (sweep,) = sweeps_of(
        tmp_path,
        """[[sweep]]
job = "workspace[1]"
values.orientation_deg = { from = -60, to = 60, count = 7 }
""",
    )
    assert [v for (v,) in design(sweep)] == [-60.0, -40.0, -20.0, 0.0, 20.0, 40.0, 60.0]


def test_zip_takes_the_ith_value_of_every_list_and_list_items_are_1_based(tmp_path):
    (sweep,) = sweeps_of(
        tmp_path,
        """[[sweep]]
job = "torques"
combine = "zip"
values."robot.lengths_m[2]" = [0.3, 0.4]
values."theta_deg[1][2]" = [10, 20]
""",
        TORQUES,
        TORQUES_BASE,
    )
    points = make_points(sweep)
    assert [p.job.robot.lengths_m for p in points] == [(0.25, 0.3), (0.25, 0.4)]
    assert [p.job.spec.theta_deg[0] for p in points] == [(30.0, 10.0), (30.0, 20.0)]
    assert points[0].job.spec.theta_deg[1] == (-45.0, 90.0)  # the other row untouched


def test_a_list_item_of_a_key_left_at_its_default(tmp_path):
    """``theta0_deg`` is not in the table (zeros by default): its item 2 is set."""
    text = TORQUES.replace(
        "[[torques]]",
        '[[simulate]]\nduration_s = 0.01\nstep_s = 0.001\noutput = "s.csv"\n\n[[torques]]',
    )
    (sweep,) = sweeps_of(
        tmp_path,
        """[[sweep]]
job = "simulate"
values."theta0_deg[2]" = [15]
""",
        text,
        TORQUES_BASE,
    )
    (point,) = make_points(sweep)
    assert point.job.spec.theta0_deg == (0.0, 15.0)


def test_sampled_designs_are_seeded_and_inside_their_ranges(tmp_path):
    from scipy.stats import qmc

    ranges = (
        '[[sweep]]\njob = "torques"\nranges."robot.lengths_m[1]" = [0.2, 0.3]\n'
        'ranges."robot.masses_kg[2]" = [1.0, 2.0]\n'
    )
    designs = {}
    for method in ("sobol", "lhs", "uniform"):
        sample = f'sample = {{ method = "{method}", count = 8, seed = 5 }}\n'
        (sweep,) = sweeps_of(tmp_path, ranges + sample, TORQUES, TORQUES_BASE)
        first, again = list(design(sweep)), list(design(sweep))
        assert first == again and len(first) == 8
        assert all(0.2 <= a <= 0.3 and 1.0 <= b <= 2.0 for a, b in first)
        designs[method] = first
    # Latin hypercube: one value in each eighth of each range
    for dim, (low, high) in enumerate(((0.2, 0.3), (1.0, 2.0))):
        cells = sorted(math.floor((p[dim] - low) / (high - low) * 8) for p in designs["lhs"])
        assert cells == list(range(8))
    # Sobol': scipy's scrambled sequence for that seed, scaled
    import numpy as np

    unit = qmc.Sobol(2, scramble=True, rng=np.random.default_rng(5)).random(8)
    scaled = qmc.scale(unit, [0.2, 1.0], [0.3, 2.0])
    assert np.allclose(np.array(designs["sobol"]), scaled, rtol=0, atol=1e-15)
    assert len({tuple(p) for p in designs.values() for p in p}) == 24  # three distinct designs


def test_build_sweep_checks_like_a_table(tmp_path):
    preset = load_preset(write(tmp_path, "p.toml", WORKSPACE, **WORKSPACE_BASE))
    sweep = build_sweep(preset, "workspace", values={"orientation_deg": [0, 5]})
    assert sweep.point_count == 2 and sweep.name == "sweep"
    with pytest.raises(PresetError, match="did you mean orientation_deg"):
        build_sweep(preset, "workspace", values={"orientation": [0, 5]})


def test_the_fingerprint_follows_the_preset(tmp_path):
    sweep = '[[sweep]]\njob = "workspace"\nvalues.orientation_deg = [0, 5]\n'
    (a,) = sweeps_of(tmp_path, sweep)
    (b,) = sweeps_of(tmp_path, sweep)
    (c,) = sweeps_of(tmp_path, sweep, base={**WORKSPACE_BASE, "precision_cm": 2.0})
    assert a.fingerprint() == b.fingerprint() != c.fingerprint()


BAD = [
    (
        'values."orientation_degs" = [1, 2]',
        "sweep[1].values.orientation_degs",
        "unknown key path",
        "did you mean orientation_deg?",
    ),
    (
        'values."robot.lengths_m" = [1, 2]',
        'sweep[1].values."robot.lengths_m"',
        "unknown key path",
        "did you mean robot3rrr.",
    ),
    ("values.orientation_deg = []", "sweep[1].values.orientation_deg", "is empty", None),
    (
        "values.orientation_deg = { from = 0, to = 1, count = 0 }",
        "sweep[1].values.orientation_deg.count",
        "is 0, below 1",
        None,
    ),
    (
        'ranges.orientation_deg = [0, 1]\nsample = { method = "lhs", count = 0 }',
        "sweep[1].sample.count",
        "is 0, below 1",
        None,
    ),
    (
        'values.orientation_deg = [1, 2]\nvalues.precision_cm = [1, 2, 3]\ncombine = "zip"',
        "sweep[1].combine",
        "differ in length (orientation_deg: 2, precision_cm: 3)",
        None,
    ),
    (
        "values.orientation_deg = { from = 0, to = 1, count = 1000 }\n"
        "values.precision_cm = { from = 1, to = 2, count = 1000 }",
        "sweep[1].values",
        "1,000,000 points, more than max_points = 100,000",
        None,
    ),
    (
        "values.orientation_deg = [1, 2, 3]\nmax_points = 2",
        "sweep[1].max_points",
        "3 points, more than max_points = 2",
        None,
    ),
    (
        "values.precision_cm = [1.0, -2.0]",
        "sweep[1]: point 2 (precision_cm = -2.0): workspace[1].precision_cm",
        "must be > 0",
        None,
    ),
    (
        'values."joint_limits_deg[4]" = [1]',
        'sweep[1].values."joint_limits_deg[4]"',
        "index 4 is beyond the 3 items of joint_limits_deg",
        None,
    ),
    (
        "values.orientation_deg = [1]\nranges.precision_cm = [1, 2]",
        "sweep[1].values",
        "both values and ranges",
        None,
    ),
    ('values.orientation_deg = [1]\ncombine = "cross"', "sweep[1].combine", "is 'cross'", None),
]


@pytest.mark.parametrize(("body", "key", "problem", "hint"), BAD)
def test_a_bad_sweep_is_one_line_exit_2_and_nothing_is_written(
    tmp_path, cli, body, key, problem, hint
):
    job = 'job = "workspace"\n' if "job" not in body else ""
    path = write(tmp_path, "p.toml", WORKSPACE, "[[sweep]]\n" + job + body + "\n", **WORKSPACE_BASE)
    out = tmp_path / "out"
    for command in ("sweep", "run"):
        result = cli(command, path, "--out-dir", out, "--workers", "1")
        assert result.exit_code == 2, result.output
        (line,) = result.stderr.splitlines()
        assert line.startswith(f"error: {path}: {key}: "), line
        assert problem in line
        assert hint is None or hint in line
        assert not out.exists()  # nothing written, not even the jobs' CSVs (run)


def test_a_bad_job_key(tmp_path, cli):
    path = write(
        tmp_path,
        "p.toml",
        WORKSPACE,
        '[[sweep]]\njob = "workspace[2]"\nvalues.orientation_deg = [1]\n',
        **WORKSPACE_BASE,
    )
    result = cli("sweep", path, "--out-dir", tmp_path / "out")
    assert result.exit_code == 2
    assert (
        "sweep[1].job: is 'workspace[2]', no such job (expected one of the preset's jobs: "
        "workspace[1]" in result.stderr
    )


def test_a_preset_with_sweeps_loads_edits_and_saves(tmp_path):
    """The loader accepts [[sweep]] tables, the app's workbench finds no problem in them and
    a saved preset keeps them."""
    from planar_tui.app.workbench import Workbench
    from planar_tui.preset_writer import dump_preset
    from planar_tui.presets import parse_toml

    path = write(
        tmp_path,
        "p.toml",
        WORKSPACE,
        '[[sweep]]\njob = "workspace"\n'
        'values."robot3rrr.distal_cm" = { from = 28.0, to = 32.0, count = 3 }\n',
        **WORKSPACE_BASE,
    )
    preset = load_preset(path)
    assert [job.key for job in preset.jobs] == ["workspace[1]"]
    bench = Workbench.open(path)
    assert bench.problems() == []
    saved = tmp_path / "saved.toml"
    saved.write_text(dump_preset(preset, "saved"))
    (again,) = parse_sweeps(load_preset(saved))
    assert list(design(again)) == [(28.0,), (30.0,), (32.0,)]
    assert parse_toml(saved, saved.read_text())["sweep"] == preset.raw["sweep"]


def test_the_docs_document_every_sweep_key():
    from planar_tui.sweep.spec import SWEEP_KEYS
    from tests.conftest import REPO

    page = (REPO / "docs" / "sweeps.md").read_text(encoding="utf-8")
    start = page.index("\n## The `[[sweep]]` table\n")
    section = page[start : page.index("\n## ", start + 1)]
    documented = [line.split("`")[1] for line in section.splitlines() if line.startswith("| `")]
    assert documented == list(SWEEP_KEYS)


@pytest.mark.slow
def test_the_app_edits_and_saves_a_preset_with_sweeps(tmp_path):
    """A [[sweep]] table neither stops the app's validation nor is lost when it saves."""
    import asyncio

    from planar_tui.app.app import WorkbenchApp
    from planar_tui.app.workbench import Workbench
    from tests.test_app import SIZE, validation

    sweep = '[[sweep]]\njob = "workspace"\nvalues.orientation_deg = [-5, 5]\n'
    path = write(tmp_path, "p.toml", WORKSPACE, sweep, **WORKSPACE_BASE)

    async def edit_and_save() -> None:
        app = WorkbenchApp(Workbench.open(path), output_dir=tmp_path)
        async with app.run_test(size=SIZE) as pilot:
            await pilot.pause()
            assert validation(app).startswith("ok: p.toml")
            app.action_show_tab("workspace")
            await pilot.pause()
            app.query_one("#pane-workspace #field-orientation_deg").value = "3"
            await pilot.pause()
            assert app.workbench.modified
            await pilot.press("ctrl+s")
            await pilot.pause()

    asyncio.run(edit_and_save())
    text = path.read_text()
    assert "orientation_deg = 3\n" in text and text.endswith(sweep)
    (again,) = parse_sweeps(load_preset(path))
    assert list(design(again)) == [(-5,), (5,)]
