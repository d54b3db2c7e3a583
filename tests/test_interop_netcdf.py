"""The motion job's results as NetCDF: written with h5netcdf, read back by xarray, every
value the job's CSVs hold; an existing file is refused; a missing extra is one line."""

from __future__ import annotations

import csv
import io
import sys

import numpy as np
import pytest
import xarray as xr

from planar_tui import __version__
from planar_tui.batch import run_job
from planar_tui.errors import PresetError
from planar_tui.interop.netcdf import require_netcdf, write_motion_netcdf
from planar_tui.presets import parse_preset


@pytest.fixture(scope="module")
def motion():
    """A 2-link motion job, Monte Carlo, Sobol' and eFAST at two times, run."""
    document = {
        "robot": {"lengths_m": [0.4, 0.3], "masses_kg": [1.0, 0.8]},
        "motion_uncertainty": {
            "duration_s": 0.2,
            "step_s": 0.02,
            "torques_Nm": [2.0, 0.5],
            "samples": 128,
            "methods": ["montecarlo", "sobol", "efast"],
            "at_s": [0.1, 0.2],
            "seed": 5,
            "tolerance_length_mm": 5.0,
            "tolerance_mass_g": 50.0,
        },
    }
    (job,) = parse_preset("motion.toml", document).jobs
    return job, run_job(job)


def csv_rows(table) -> list[dict]:
    buffer = io.StringIO()
    table.write(buffer)
    return list(csv.DictReader(io.StringIO(buffer.getvalue())))


def test_the_dataset_reads_back_with_the_csvs_values(motion, tmp_path):
    job, result = motion
    attributes = {
        "preset": "motion.toml",
        "job": job.label,
        "planar_tui_version": __version__,
        "seed": 5,
        "samples": 128,
        "methods": ["montecarlo", "sobol", "efast"],
    }
    path = write_motion_netcdf(tmp_path / "motion.nc", result, attributes)
    with xr.open_dataset(path, engine="h5netcdf") as data:
        data.load()
    assert data.attrs["preset"] == "motion.toml" and data.attrs["seed"] == 5
    assert data.attrs["planar_tui_version"] == __version__
    assert data.attrs["methods"] == "montecarlo, sobol, efast"
    assert data.attrs["robots"] == 128 + 128 * 6 + 128 * 4
    assert data["band"].dims == ("time", "output", "statistic")
    assert list(data["output"].values) == ["theta1_rad", "theta2_rad", "tip_x_m", "tip_y_m"]
    # the band CSV, cell for cell
    for row in csv_rows(result.table):
        at = data["band"].sel(time=float(row["t_s"]))
        for name in data["output"].values:
            for statistic in data["statistic"].values:
                assert at.sel(output=name, statistic=statistic).item() == float(
                    row[f"{name}_{statistic}"]
                )
    # the indices CSV, cell for cell
    assert data["ST"].dims == ("method", "index_time", "output", "input")
    assert list(data["method"].values) == ["sobol", "efast"]
    np.testing.assert_array_equal(data["index_time"].values, [0.1, 0.2])
    rows = [r for r in csv_rows(result.extra_tables["indices"]) if r["t_s"] in ("0.1", "0.2")]
    assert len(rows) == 2 * 2 * 4 * 4  # methods × times of at_s × outputs × inputs
    for row in rows:
        cell = {
            "method": row["method"],
            "index_time": float(row["t_s"]),
            "output": row["output"],
            "input": row["parameter"],
        }
        for name in ("S1", "ST", "percent"):
            assert data[name].sel(cell).item() == pytest.approx(float(row[name]), abs=0, rel=0)


def test_an_existing_file_is_never_replaced(motion, tmp_path):
    _, result = motion
    path = tmp_path / "motion.nc"
    path.write_text("mine")
    with pytest.raises(PresetError) as caught:
        write_motion_netcdf(path, result, {})
    assert "exists: nothing is overwritten" in str(caught.value)
    assert path.read_text() == "mine"
    assert [p.name for p in tmp_path.iterdir()] == ["motion.nc"]  # no temporary file left


def test_a_missing_extra_is_one_line_naming_it(monkeypatch):
    monkeypatch.setitem(sys.modules, "h5netcdf", None)
    with pytest.raises(PresetError) as caught:
        require_netcdf()
    message = str(caught.value)
    assert message == (
        "error: command line: --format: netcdf needs h5netcdf, which is not installed "
        "(expected pip install 'planar-tui[netcdf]')"
    )
