"""A job's ``prepare`` runs exactly once, through the batch service and through a sweep
point, and what it resolves lives in the prepared job, never in the settings."""

from __future__ import annotations

import dataclasses

import pytest

from planar_tui import batch
from planar_tui.jobkind import PreparedJob
from planar_tui.presets import load_preset
from planar_tui.registry import JOB_KINDS
from planar_tui.sweep.service import run_sweep
from planar_tui.sweep.spec import parse_sweeps
from planar_tui.workspace.rrr.job import WorkspacePrepared
from tests.sweep_presets import WORKSPACE, WORKSPACE_BASE, write

SENSITIVITY = """[robot]
lengths_m = [0.303, 0.214]
masses_kg = [1.0, 1.0]

[[sensitivity]]
posture = "isotropic"
methods = ["sobol"]
samples = 8
output = "a.csv"

[[sensitivity]]
posture = "singular"
methods = ["sobol"]
samples = 8
output = "b.csv"
"""


@pytest.fixture
def counted(monkeypatch):
    """Replace a kind's ``prepare`` by one counting its calls (job labels)."""
    calls: list[str] = []

    def count(name):
        kind = JOB_KINDS[name]
        original = kind.prepare
        assert original is not None

        def prepare(job):
            if not job.label.startswith("warmup-"):  # the kernels' warm-up example
                calls.append(job.label)
            return original(job)

        monkeypatch.setitem(JOB_KINDS, name, dataclasses.replace(kind, prepare=prepare))
        return calls

    return count


def test_the_batch_service_prepares_each_job_once(tmp_path, cli, counted):
    calls = counted("sensitivity")
    preset = tmp_path / "s.toml"
    preset.write_text(SENSITIVITY)
    result = cli("run", preset, "--out-dir", tmp_path)
    assert result.exit_code == 0, result.output
    assert calls == ["s:sensitivity[1]", "s:sensitivity[2]"]
    assert (tmp_path / "a.csv").exists() and (tmp_path / "b.csv").exists()


def test_run_job_prepares_a_job_once_and_a_prepared_job_never(tmp_path, counted):
    calls = counted("sensitivity")
    preset = tmp_path / "s.toml"
    preset.write_text(SENSITIVITY)
    first, second = load_preset(preset).jobs
    batch.run_job(first)
    (ready,) = batch.prepare_jobs([second])
    assert isinstance(ready, PreparedJob) and ready.job is second
    batch.run_job(ready)
    assert calls == ["s:sensitivity[1]", "s:sensitivity[2]"]


def test_a_sweep_point_is_prepared_once(tmp_path, counted):
    calls = counted("workspace")
    body = '[[sweep]]\njob = "workspace"\nvalues.orientation_deg = [-10, 10]\noutput = "g.csv"\n'
    path = write(tmp_path, "p.toml", WORKSPACE, body, **WORKSPACE_BASE)
    (sweep,) = parse_sweeps(load_preset(path))
    run_sweep(sweep, out_dir=tmp_path / "out")
    assert calls == ["p:workspace[1]", "p:workspace[1]"]  # one per point


def test_the_prepared_payload_is_typed_and_apart_from_the_settings(tmp_path):
    path = write(tmp_path, "p.toml", WORKSPACE, "", **WORKSPACE_BASE)
    (job,) = load_preset(path).jobs
    (ready,) = batch.prepare_jobs([job])
    assert ready.prepared == WorkspacePrepared(circle=None)
    assert ready.spec is job.spec and not hasattr(job.spec, "circle")
