"""The refusals that keep a run within the machine, at their thresholds.

:mod:`planar_tui.limits` (half the physical memory, one day of computing), the workspace
estimates of :mod:`planar_tui.workspace.paving.estimate` (3-RPR, 3-PRR, five-bar) and
:mod:`planar_tui.workspace.rrr.compute` (3-RRR) and
:mod:`planar_tui.workspace.paving.levels`, and the box budget: each limit one byte, one
box or a fraction of a second either side, each form, each tolerance mode, each robot.
The expected estimates are the module docstrings' formulas written out with their
constants as numbers (not read from the code under test), in the same order of
operations, so equal to the box; the boundary length, area and
search box they rest on come from the geometry functions, tested against closed forms
elsewhere (``tests/test_workspace_estimate.py``, ``tests/test_workspace_area.py``).
"""

from __future__ import annotations

import dataclasses
import math
import os

import numpy as np
import pytest

from planar_tui import limits
from planar_tui.errors import JobError, PresetError
from planar_tui.presets import load_preset
from planar_tui.progress import Progress
from planar_tui.workspace.paving import levels
from planar_tui.workspace.paving.estimate import (
    _geometry,
    count_text,
    estimate,
    estimate_boxes,
    needs,
    report_box_estimate,
)
from planar_tui.workspace.rrr import compute
from planar_tui.workspace.rrr.geometry import outer_area_and_length
from tests.conftest import PRESETS
from tests.test_workspace_estimate import JOBS

GIB = 2**30


@pytest.fixture
def fresh_limit():
    """:func:`limits.memory_limit_bytes` is cached: recomputed before and after the test."""
    limits.memory_limit_bytes.cache_clear()
    yield
    limits.memory_limit_bytes.cache_clear()


# --- planar_tui.limits ---------------------------------------------------------------------


def test_the_limits_are_half_the_memory_and_one_day():
    """README: a job may plan half the physical memory (8 GiB where the system does not
    say) and one day of computing."""
    assert limits.MEMORY_FRACTION == 0.5
    assert limits.FALLBACK_MEMORY_BYTES == 8 * GIB
    assert limits.MAX_JOB_SECONDS == 24 * 3600


def test_the_memory_limit_is_half_the_physical_memory(fresh_limit):
    physical = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    assert limits.memory_limit_bytes() == physical // 2


@pytest.mark.parametrize(
    "page, pages, expected",
    [(4096, 1000, 2_048_000), (4096, 1, 2048), (4096, 0, 8 * GIB), (-1, 1000, 8 * GIB)],
)
def test_the_memory_limit_from_what_the_system_says(
    monkeypatch, fresh_limit, page, pages, expected
):
    """Half of page size times pages; nothing usable (0, or -1 for an unknown value) gives
    the 8 GiB fallback."""
    values = {"SC_PAGE_SIZE": page, "SC_PHYS_PAGES": pages}
    monkeypatch.setattr(limits.os, "sysconf", values.__getitem__)
    assert limits.memory_limit_bytes() == expected


@pytest.mark.parametrize("error", [OSError, ValueError, AttributeError])
def test_the_memory_limit_falls_back_where_the_system_does_not_say(monkeypatch, fresh_limit, error):
    def unknown(name):
        raise error(name)

    monkeypatch.setattr(limits.os, "sysconf", unknown)
    assert limits.memory_limit_bytes() == 8 * GIB


@pytest.mark.parametrize("limit", [8 * GIB, 12_345_679, 1000])
def test_memory_is_refused_one_byte_over_the_limit(monkeypatch, limit):
    monkeypatch.setattr(limits, "memory_limit_bytes", lambda: limit)
    assert limits.memory_problem(limit) is None
    assert limits.memory_problem(limit - 1) is None
    assert limits.memory_problem(0) is None
    assert limits.memory_problem(limit + 1) is not None
    assert limits.memory_problem(2 * limit) is not None


def test_the_memory_problem_says_the_need_and_the_limit(monkeypatch):
    monkeypatch.setattr(limits, "memory_limit_bytes", lambda: 8 * GIB)
    assert limits.memory_problem(48 * GIB) == "needs about 48 GiB of memory (limit 8 GiB)"


def test_time_is_refused_past_one_day():
    day = 86_400.0
    assert limits.time_problem(day) is None
    assert limits.time_problem(day - 1.0) is None
    assert limits.time_problem(0.0) is None
    assert limits.time_problem(float(np.nextafter(day, math.inf))) is not None
    assert limits.time_problem(day + 1.0) == "needs about 1 days of computing (limit 1 day)"
    assert limits.time_problem(3 * day) == "needs about 3 days of computing (limit 1 day)"


@pytest.mark.parametrize(
    "n_bytes, text",
    [
        (2**40, "1 TiB"),
        (2**40 - 2**30, "1.02e+03 GiB"),
        (3 * 2**40, "3 TiB"),
        (GIB, "1 GiB"),
        (GIB - 2**20, "1.02e+03 MiB"),
        (48 * GIB, "48 GiB"),
        (2**20, "1 MiB"),
        (2**20 - 2**10, "1.02e+03 KiB"),
        (1536, "1.5 KiB"),
        (0, "0 KiB"),
    ],
)
def test_sizes_change_unit_at_each_power_of_1024(n_bytes, text):
    assert limits.size_text(n_bytes) == text


@pytest.mark.parametrize(
    "seconds, text",
    [
        (365.25 * 86_400, "1 years"),
        (365.25 * 86_400 - 86_400, "364 days"),
        (365.25 * 86_400 - 1, "365 days"),
        (86_400, "1 days"),
        (86_399, "24 hours"),
        (3 * 86_400, "3 days"),
        (3_600, "1 hours"),
        (3_599, "3.6e+03 s"),
        (5 * 3_600, "5 hours"),
        (12.5, "12.5 s"),
    ],
)
def test_durations_change_unit_at_each_hour_day_and_year(seconds, text):
    assert limits.duration_text(seconds) == text


# --- the 3-RPR, 3-PRR and five-bar estimates ------------------------------------------------

KINDS = sorted(JOBS)


def load_job(tmp_path, kind, precision=1.0, extra=""):
    path = tmp_path / f"{kind}.toml"
    text = (
        JOBS[kind]
        .format(precision=precision)
        .replace('output = "w.csv"', extra + 'output = "w.csv"')
    )
    path.write_text(text, encoding="utf-8")
    (job,) = load_preset(path).jobs
    return job, path


def with_spec(job, **changes):
    return dataclasses.replace(job, spec=dataclasses.replace(job.spec, **changes))


def docstring_boxes(kind, job, *, refine=None, tolerance=None, band=0.0, singular=None):
    """The module docstring's N: 10 L/ε (+ 10 L/ε_r), with a tolerance 3 times that plus
    c_t L t / ε², plus c_s (w + h) / ε_s with ``singular = (c_s, ε_s, w + h)``, rounded
    up, plus 64."""
    length, _ = _geometry(kind, job.robot, job.spec)
    eps = job.spec.precision_cm
    boxes = 10.0 * length / eps
    if refine is not None:
        boxes += 10.0 * length / refine
    if tolerance is not None:
        boxes = 3.0 * boxes + band * length * tolerance / (eps * eps)
    if singular is not None:
        per_step, precision, width_plus_height = singular
        boxes += per_step * width_plus_height / precision
    return math.ceil(boxes) + 64


@pytest.mark.parametrize("kind", KINDS)
def test_the_estimate_of_a_plain_job_is_the_boundary_term(tmp_path, kind):
    job, _ = load_job(tmp_path, kind, precision=0.5)
    assert estimate_boxes(kind, job.robot, job.spec) == docstring_boxes(kind, job)


@pytest.mark.parametrize("kind", KINDS)
def test_the_estimate_adds_the_boundary_refinement(tmp_path, kind):
    job, _ = load_job(tmp_path, kind, precision=2.0)
    job = with_spec(job, refine_precision_cm=0.25)
    expected = docstring_boxes(kind, job, refine=0.25)
    assert estimate_boxes(kind, job.robot, job.spec) == expected


@pytest.mark.parametrize("kind", ["workspace3rpr", "workspace3prr"])
def test_the_geometric_form_processes_no_boxes(tmp_path, kind):
    """The shortcut: no paving, so no boundary length is even computed."""
    job, _ = load_job(tmp_path, kind)
    job = with_spec(job, form="geometric", refine_precision_cm=0.1, tolerance_cm=0.5)
    assert estimate_boxes(kind, job.robot, job.spec) == 0
    assert needs(kind, job.robot, job.spec) == (0, 0.0, 0.5)


def test_the_five_bar_geometric_form_processes_no_boxes(tmp_path):
    job, _ = load_job(tmp_path, "workspace5r")
    job = with_spec(job, form="geometric")
    assert estimate_boxes("workspace5r", job.robot, job.spec) == 0


#: c_t of the job's mode plus that of the other mode (the job's paving and its figure's),
#: by kind: 3-RPR 5 + 5, 3-PRR 5 ("all") + 16 ("some"), five-bar 1 + 1.
BANDS = {"workspace3rpr": 10.0, "workspace3prr": 21.0, "workspace5r": 2.0}


@pytest.mark.parametrize("mode", ["all", "some"])
@pytest.mark.parametrize("kind", KINDS)
def test_a_tolerance_adds_both_modes_bands_at_the_widest_tolerance(tmp_path, kind, mode):
    """A table of tolerances counts at its widest; a uniform tolerance wider than the
    table's entries wins over them."""
    job, _ = load_job(tmp_path, kind, precision=0.5)
    table = (("a", 0.05), ("b", 0.3), ("c", 0.1))
    tabled = with_spec(job, tolerance_cm=None, tolerances_cm=table, tolerance_mode=mode)
    expected = docstring_boxes(kind, job, tolerance=0.3, band=BANDS[kind])
    assert estimate_boxes(kind, tabled.robot, tabled.spec) == expected
    uniform = with_spec(job, tolerance_cm=0.4, tolerances_cm=table, tolerance_mode=mode)
    expected = docstring_boxes(kind, job, tolerance=0.4, band=BANDS[kind])
    assert estimate_boxes(kind, uniform.robot, uniform.spec) == expected


@pytest.mark.parametrize("kind", KINDS)
def test_a_tolerance_without_a_mode_counts_as_all(tmp_path, kind):
    """Unset, the mode is ``all``: both modes' bands, as when it is set."""
    job, _ = load_job(tmp_path, kind, precision=0.5)
    job = with_spec(job, tolerance_cm=0.2, tolerance_mode=None)
    expected = docstring_boxes(kind, job, tolerance=0.2, band=BANDS[kind])
    assert estimate_boxes(job.kind, job.robot, job.spec) == expected


#: Singularity boxes per ε_s of the search box's width plus height.
SINGULAR = {"workspace3rpr": 10.0, "workspace3prr": 10.0, "workspace5r": 20.0}


@pytest.mark.parametrize("kind", KINDS)
def test_the_singularity_paving_adds_the_search_boxs_term(tmp_path, kind):
    """The search box 320 cm wide and 280 cm high: w + h = 600 cm."""
    job, _ = load_job(tmp_path, kind, precision=1.0)
    job = with_spec(job, search_box_cm=((-150.0, 170.0), (-120.0, 160.0)))
    at_eps = with_spec(job, singularities=True, singularity_precision_cm=None)
    expected = docstring_boxes(kind, job, singular=(SINGULAR[kind], 1.0, 600.0))
    assert estimate_boxes(kind, at_eps.robot, at_eps.spec) == expected
    finer = with_spec(job, singularities=True, singularity_precision_cm=0.25)
    expected = docstring_boxes(kind, job, singular=(SINGULAR[kind], 0.25, 600.0))
    assert estimate_boxes(kind, finer.robot, finer.spec) == expected


@pytest.mark.parametrize("kind", KINDS)
def test_needs_are_112_bytes_and_5_microseconds_a_box_and_half_a_second(tmp_path, kind):
    job, _ = load_job(tmp_path, kind, precision=0.5)
    boxes, memory, seconds = needs(kind, job.robot, job.spec)
    assert boxes == estimate_boxes(kind, job.robot, job.spec)
    assert memory == 112.0 * boxes
    assert seconds == pytest.approx(0.5 + 5e-6 * boxes, rel=1e-12)


@pytest.mark.parametrize("kind", KINDS)
def test_the_kinds_hooks_give_the_needs(tmp_path, kind):
    """``estimate`` (memory and seconds, summed by sweeps) and ``report_box_estimate``
    (the progress figure, warned of over ``box_budget``)."""
    job, _ = load_job(tmp_path, kind, precision=0.5)
    boxes, memory, seconds = needs(kind, job.robot, job.spec)
    assert estimate(job) == (memory, seconds)
    progress = Progress()
    assert report_box_estimate(with_spec(job, box_budget=boxes), progress) == boxes
    assert progress.figures["boxes_estimate"] == boxes and not progress.warning
    report_box_estimate(with_spec(job, box_budget=boxes - 1), progress)
    assert progress.warning.startswith(f"about {boxes:,} boxes expected")


@pytest.mark.parametrize(
    "count, text",
    [(48_475, "48,475"), (10**12 - 1, "999,999,999,999"), (10**12, "1e+12"), (2.62e12, "2.62e+12")],
)
def test_box_counts_switch_to_exponents_from_a_trillion(count, text):
    assert count_text(count) == text


def set_limits(monkeypatch, memory_bytes=None, seconds=None):
    if memory_bytes is not None:
        monkeypatch.setattr(limits, "memory_limit_bytes", lambda: memory_bytes)
    if seconds is not None:
        monkeypatch.setattr(limits, "MAX_JOB_SECONDS", seconds)


@pytest.mark.parametrize("kind", KINDS)
def test_a_job_is_refused_one_box_over_the_memory_limit(tmp_path, monkeypatch, kind):
    """The limit at the job's own estimate: read; one box's bytes lower: refused, naming
    the precision, the box count and the memory."""
    job, path = load_job(tmp_path, kind, precision=0.5)
    boxes, memory, _ = needs(kind, job.robot, job.spec)
    set_limits(monkeypatch, memory_bytes=int(memory), seconds=1e12)
    load_preset(path)
    set_limits(monkeypatch, memory_bytes=int(memory) - 112)
    with pytest.raises(PresetError) as refused:
        load_preset(path)
    message = str(refused.value)
    assert "precision_cm" in message and f"about {boxes:,} boxes" in message
    assert "of memory" in message


@pytest.mark.parametrize("kind", KINDS)
def test_a_job_is_refused_a_moment_over_the_time_limit(tmp_path, monkeypatch, kind):
    """The time limit checked as well as the memory's: the job fits the memory, and is
    refused for time alone, at the job's estimate less one float."""
    job, path = load_job(tmp_path, kind, precision=0.5)
    boxes, memory, seconds = needs(kind, job.robot, job.spec)
    set_limits(monkeypatch, memory_bytes=10 * int(memory), seconds=seconds)
    load_preset(path)
    set_limits(monkeypatch, seconds=float(np.nextafter(seconds, 0.0)))
    with pytest.raises(PresetError) as refused:
        load_preset(path)
    message = str(refused.value)
    assert f"about {boxes:,} boxes" in message and "of computing" in message


@pytest.mark.parametrize("kind", KINDS)
def test_a_job_over_both_limits_names_the_memory(tmp_path, monkeypatch, kind):
    _, path = load_job(tmp_path, kind, precision=0.5)
    set_limits(monkeypatch, memory_bytes=1000, seconds=0.1)
    with pytest.raises(PresetError, match="of memory"):
        load_preset(path)


# --- the 3-RRR's estimate and budget (planar_tui.workspace.rrr.compute) -------------------------


def table3_job(index=0, **changes):
    """Job ``index`` of paper B's Table 3 preset (natural form, ε = 0.1172 cm)."""
    job = load_preset(PRESETS / "paper-b-table3.toml").jobs[index]
    return with_spec(job, **changes) if changes else job


def area_length(job):
    spec = job.spec
    return outer_area_and_length(job.robot, spec.limits_rad, spec.orientation_rad, 64)


#: (form, strategy, expanded, its term): processed boxes per ε² of area (joint bisection
#: of the 5-D forms) or per ε of boundary length (arc-distance, leg-wise).
RRR_FORMS = [
    ("natural", "joint", False, "area", 75.0),
    ("mean-value", "joint", False, "area", 65.0),
    ("slope", "joint", False, "area", 55.0),
    ("natural", "joint", True, "area", 1000.0),
    ("arc-distance", "joint", False, "length", 8.0),
    ("natural", "legwise", False, "length", 400.0),
    ("natural", "legwise", True, "length", 400.0),
    ("mean-value", "legwise", False, "length", 180.0),
    ("slope", "legwise", False, "length", 180.0),
]


@pytest.mark.parametrize("form, strategy, expanded, term, per", RRR_FORMS)
@pytest.mark.parametrize("refine", [None, 0.05])
def test_the_3rrr_estimate_of_each_form(form, strategy, expanded, term, per, refine):
    eps = 0.5
    job = table3_job(
        form=form,
        strategy=strategy,
        expanded=expanded,
        precision_cm=eps,
        refine_precision_cm=refine,
    )
    area, length = area_length(job)
    boxes = per * area / (eps * eps) if term == "area" else per * length / eps
    if refine is not None:
        boxes += 8.0 * length / refine
    expected = math.ceil(boxes) + 1
    assert compute.estimate_boxes(job.robot, job.spec) == expected


def test_the_3rrr_geometric_form_processes_no_boxes():
    job = table3_job(form="geometric", refine_precision_cm=0.05)
    assert compute.estimate_boxes(job.robot, job.spec) == 0


def test_the_estimate_warns_one_box_over_the_box_budget():
    spec = table3_job().spec
    progress = Progress()
    assert levels.report_boxes(spec.box_budget, spec, progress) == spec.box_budget
    assert progress.figures["boxes_estimate"] == spec.box_budget and not progress.warning
    progress = Progress()
    levels.report_boxes(spec.box_budget + 1, spec, progress)
    assert progress.warning.startswith(f"about {spec.box_budget + 1:,} boxes expected, more")


def test_the_run_stops_one_box_over_the_box_budget():
    job = table3_job(box_budget=1000)
    budget = levels.BoxBudget(job, Progress())
    budget.count(600)
    budget.count(400)  # exactly the budget: allowed
    assert budget.processed == 1000
    with pytest.raises(JobError, match="exceeded 1,000 boxes"):
        budget.count(1)


def write_rrr_preset(tmp_path, budget_line):
    text = (PRESETS / "paper-b-table3.toml").read_text(encoding="utf-8")
    head, _, _ = text.partition("[[workspace]]\nform")
    job = (
        '[[workspace]]\nform = "natural"\nprecision_cm = 1.0\n'
        "joint_limits_deg = [[20, 70], [110, 160], [245, 295]]\n"
        f'{budget_line}output = "w.csv"\n'
    )
    path = tmp_path / "rrr.toml"
    path.write_text(head + job, encoding="utf-8")
    return path


def test_a_box_budget_one_box_over_the_memory_limit_is_refused(tmp_path, monkeypatch):
    """``box_budget`` boxes of 112 bytes must fit the memory limit: at the limit it is read,
    one box more refused; the default is lowered to the limit. (6 000 boxes: four times the
    budget admits the job's estimate of about 20 600 boxes, so the budget refusal stays out
    of the way.)"""
    monkeypatch.setattr(limits, "memory_limit_bytes", lambda: 112 * 6000)
    (job,) = load_preset(write_rrr_preset(tmp_path, "box_budget = 6000\n")).jobs
    assert job.spec.box_budget == 6000
    with pytest.raises(PresetError, match="box_budget"):
        load_preset(write_rrr_preset(tmp_path, "box_budget = 6001\n"))
    (job,) = load_preset(write_rrr_preset(tmp_path, "")).jobs
    assert job.spec.box_budget == 6000
