"""The type checker guards the core: mypy (configured in pyproject.toml, run by .ci/run
over the package) refuses a wrong field of a job, a prepared job's payload or a result."""

from __future__ import annotations

import subprocess
import sys

import pytest

from tests.conftest import REPO

SNIPPET = """
from planar_tui.jobkind import Job, PreparedJob
from planar_tui.motion.runner import MotionPrepared
from planar_tui.motion.spec import MotionSpec
from planar_tui.dynamics.robot import SerialRobot

def runs(job: PreparedJob[MotionSpec, SerialRobot, MotionPrepared]) -> None:
    print(job.spec.samples, job.prepared.device, job.robot.n_links, job.label)
    print({wrong})
"""


def check(expression: str, folder) -> tuple[str, int]:
    """mypy's verdict on :data:`SNIPPET` using ``expression`` (the project's settings)."""
    snippet = folder / "snippet.py"
    snippet.write_text(SNIPPET.format(wrong=expression), encoding="utf-8")
    # In a child process: mypy's main raises the recursion limit (to 2**14) of the process
    # it runs in, which would let other tests of this worker parse what they must refuse.
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "mypy",
            "--config-file",
            str(REPO / "pyproject.toml"),
            "--cache-dir",
            str(folder / "cache"),
            "--no-error-summary",
            str(snippet),
        ],
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )
    return done.stdout + done.stderr, done.returncode


@pytest.mark.slow
def test_mypy_refuses_a_field_the_core_types_do_not_have(tmp_path_factory):
    cache = tmp_path_factory.mktemp("mypy")
    text, status = check("job.spec.sample_count", cache)
    assert status == 1 and '"MotionSpec" has no attribute "sample_count"' in text, text
    text, status = check("job.prepared.posture", cache)
    assert status == 1 and '"MotionPrepared" has no attribute "posture"' in text, text
    text, status = check("job.job.device", cache)
    assert status == 1 and '"MotionSpec" has no attribute' not in text, text
    assert 'has no attribute "device"' in text, text
    text, status = check("job.spec.seed + job.prepared.device_note.count('x')", cache)
    assert status == 0, text  # the same checker accepts the right fields
