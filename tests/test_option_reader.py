"""Every kind's command-line options go through one reader (``overrides.override_job``): a bad
value is one line ``error: command line: --OPTION: ...`` naming the option, never the
preset's key, and nothing is written."""

from __future__ import annotations

import pytest


@pytest.mark.parametrize(
    ("args", "line"),
    [
        (
            ("workspace", "paper-b-table3", "--form", "exact"),
            "error: command line: --form: is 'exact' (expected one of natural, mean-value, slope, "
            "arc-distance, geometric)\n",
        ),
        (
            ("workspace", "paper-b-table3", "--precision", "0"),
            "error: command line: --precision: is 0.0, must be > 0 (expected a positive number)\n",
        ),
        (
            ("sensitivity", "paper-a-table4", "--samples", str(2**30)),
            "error: command line: --samples: ",
        ),
        (("sensitivity", "paper-a-table4", "--seed", "0"), "error: command line: --seed: "),
        (("motion", "paper-a-table1-motion", "--device", "gpu"), "error: command line: --device: "),
    ],
)
def test_a_bad_option_is_one_line_naming_the_option(cli, tmp_path, args, line):
    result = cli(*args, "--out-dir", tmp_path)
    assert result.exit_code == 2
    assert result.stderr.startswith(line) and result.stderr.count("\n") == 1, result.stderr
    assert list(tmp_path.iterdir()) == []


def test_an_option_equal_to_the_presets_value_changes_no_file_name(cli, tmp_path):
    """The variant suffix names only what an option changed (the preset says natural)."""
    from planar_tui.overrides import override_job
    from planar_tui.presets import load_preset
    from planar_tui.resources import resolve_preset

    (job, *_) = load_preset(resolve_preset("paper-b-table3")).jobs
    assert override_job(job, {"--form": job.spec.form}).variant == ""
    changed = override_job(job, {"--form": "slope", "--precision": 0.5})
    assert changed.variant == "--form-slope--precision-0.5"
    assert changed.overridden == {"form": "--form", "precision_cm": "--precision"}
