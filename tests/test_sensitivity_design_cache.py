"""Persistent design cache: byte-identical to SALib, self-healing, invisible in the results."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest

from planar_tui.sensitivity import design_cache, engine
from planar_tui.sensitivity.engine import unit_design
from tests.conftest import REPO
from tests.salib_reference import salib_unit_design

CASES = [("sobol", 3, 64, 5), ("efast", 4, 100, 5)]
ROBOT_2R = """[robot]
lengths_m = [0.303, 0.214]
masses_kg = [1.126, 0.796]
inertias_kgm2 = [0.129, 0.045]

[sensitivity]
"""


def fresh_unit_design(*key):
    """The design via the cache layer, with the per-process memo cleared first."""
    engine.unit_design.cache_clear()
    return unit_design(*key)


def entries(folder):
    return sorted(folder.glob("*.npy"))


@pytest.mark.slow
@pytest.mark.parametrize("key", CASES)
def test_cold_and_warm_designs_are_byte_identical_to_salib(key):
    folder = design_cache.cache_dir()  # the per-test folder of the autouse fixture
    drawn = salib_unit_design(*key)  # SALib itself, no cache involved
    cold = fresh_unit_design(*key)
    (entry,) = entries(folder)
    assert entry.name.startswith(f"v1_{key[0]}_D{key[1]}_N{key[2]}_seed{key[3]}_")
    warm = fresh_unit_design(*key)
    assert cold.tobytes() == drawn.tobytes() == warm.tobytes()
    assert cold.shape == drawn.shape == warm.shape and warm.dtype == np.float64
    assert entries(folder) == [entry]  # read back, not drawn again


PROBE = """
import json, sys
from typer.testing import CliRunner
from planar_tui.cli import app
result = CliRunner().invoke(app, sys.argv[1:])
heavy = ("SALib", "pandas", "scipy.stats", "scipy.optimize")
print(json.dumps({"code": result.exit_code, "loaded": [m for m in heavy if m in sys.modules]}))
"""


@pytest.mark.slow
def test_warm_run_imports_neither_salib_nor_scipy_optimize(tmp_path):
    """Whole CLI runs in fresh processes: the cold one draws the designs with
    ``scipy.stats.qmc`` (so the probe can see it), the warm one reads both designs back
    and imports none of the heavy modules."""
    preset = tmp_path / "job.toml"
    body = 'posture = "isotropic"\nsamples = 64\nefast_samples = 80\n'
    preset.write_text(ROBOT_2R + body, encoding="utf-8")
    env = dict(os.environ, PYTHONPATH=str(REPO))
    probes = []
    for name in ("cold", "warm"):
        command = [sys.executable, "-c", PROBE, "sensitivity", str(preset)]
        command += ["-o", str(tmp_path / f"{name}.csv")]
        out = subprocess.run(command, capture_output=True, text=True, env=env, cwd=REPO)
        probes.append(json.loads(out.stdout.strip().splitlines()[-1]))
    assert probes[0]["code"] == probes[1]["code"] == 0
    assert "scipy.stats" in probes[0]["loaded"]
    assert probes[1]["loaded"] == []
    assert len(entries(design_cache.cache_dir())) == 2


@pytest.mark.parametrize(
    "damage",
    [
        lambda path: path.write_bytes(b"not a numpy file"),
        lambda path: path.write_bytes(path.read_bytes()[:-7]),  # truncated
        lambda path: path.write_bytes(path.read_bytes()[:-1] + b"\x01"),  # one bit: CRC
        lambda path: np.save(path, np.zeros((3, 3))),  # valid .npy, wrong shape
        lambda path: path.unlink(),  # missing
    ],
    ids=["garbage", "truncated", "flipped-bit", "wrong-shape", "missing"],
)
def test_damaged_entries_are_drawn_again(damage):
    folder = design_cache.cache_dir()
    key = CASES[0]
    good = fresh_unit_design(*key).tobytes()
    (entry,) = entries(folder)
    damage(entry)
    assert fresh_unit_design(*key).tobytes() == good
    (healed,) = entries(folder)
    assert healed.name == entry.name and np.load(healed).tobytes() == good


@pytest.mark.slow
def test_unwritable_or_disabled_cache_still_gives_the_design(tmp_path, monkeypatch):
    key = CASES[1]
    expected = salib_unit_design(*key).tobytes()
    blocker = tmp_path / "a-file"
    blocker.write_text("x", encoding="utf-8")
    monkeypatch.setenv(design_cache.ENV_VAR, str(blocker / "cache"))  # cannot be created
    assert fresh_unit_design(*key).tobytes() == expected
    monkeypatch.setenv(design_cache.ENV_VAR, "")
    assert design_cache.cache_dir() is None
    assert fresh_unit_design(*key).tobytes() == expected


def test_cache_folder_resolution(monkeypatch, tmp_path):
    monkeypatch.setenv(design_cache.ENV_VAR, str(tmp_path / "here"))
    assert design_cache.cache_dir() == tmp_path / "here"
    monkeypatch.delenv(design_cache.ENV_VAR)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    if sys.platform.startswith("linux"):
        assert design_cache.cache_dir() == tmp_path / "xdg" / "planar-tui"


def test_key_names_everything_the_design_depends_on():
    keys = {
        design_cache.design_key(*args)
        for args in [
            ("sobol", 4, 64, 1, 4),
            ("efast", 4, 64, 1, 4),
            ("sobol", 5, 64, 1, 4),
            ("sobol", 4, 128, 1, 4),
            ("sobol", 4, 64, 2, 4),
            ("efast", 4, 64, 1, 6),
        ]
    }
    assert len(keys) == 6
    assert all("SALib-" in k and "scipy-" in k and "numpy-" in k for k in keys)


def test_csv_is_byte_identical_cold_warm_and_without_cache(tmp_path, cli, monkeypatch):
    preset = tmp_path / "job.toml"
    body = 'posture = "isotropic"\nsamples = 128\nefast_samples = 100\nseed = 9\n'
    preset.write_text(ROBOT_2R + body, encoding="utf-8")
    outputs = []
    for name, folder in (("cold", "c"), ("warm", "c"), ("none", None)):
        monkeypatch.setenv(design_cache.ENV_VAR, str(tmp_path / folder) if folder else "")
        engine.unit_design.cache_clear()  # so the disk cache, not the memo, is exercised
        result = cli("sensitivity", preset, "-o", tmp_path / f"{name}.csv")
        assert result.exit_code == 0, result.output
        outputs.append((tmp_path / f"{name}.csv").read_bytes())
    assert len(entries(tmp_path / "c")) == 2  # sobol and efast, written cold, read warm
    assert outputs[0] == outputs[1] == outputs[2]
