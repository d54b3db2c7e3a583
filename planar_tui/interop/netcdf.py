"""The motion job's band and indices as one xarray Dataset in a NetCDF file
(``--format netcdf``, the ``netcdf`` extra: xarray, h5netcdf, h5py; imported only here).

Layout (what ``xarray.open_dataset(FILE, engine="h5netcdf")`` gives back):

* ``band`` (time × output × statistic): mean, std (``ddof = 1``), p5, p50, p95 of every
  output over the independent uniform robots, at every recorded time (the band CSV);
* ``S1``, ``S1_conf``, ``ST``, ``ST_conf``, ``percent`` (method × index_time × output ×
  input): the Sobol'/eFAST indices of every output at the times of ``at_s`` (the indices
  CSV's rows at those times; the CSV also holds the other recorded times; ``*_conf`` are 95 % half-widths, NaN for eFAST's first order where planar-tui
  writes none); absent when the job ran Monte Carlo only;
* coordinates ``time`` and ``index_time`` (s), ``output`` (``theta1_rad`` … ``tip_y_m``),
  ``statistic``, ``method``, ``input`` (``l1`` … ``mn``, ``I1`` …); units in each
  variable's ``units`` attribute;
* attributes: ``preset``, ``job``, ``planar_tui_version``, ``seed``, ``samples``,
  ``methods``, ``robots``, ``device`` and ``notes``.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from planar_tui import __version__
from planar_tui.errors import PresetError
from planar_tui.interop.files import write_new
from planar_tui.motion.results import BAND_STATISTICS

#: The option that asks for it (named in messages), and the extra that installs it.
OPTION = "--format"
EXTRA = "pip install 'planar-tui[netcdf]'"
INDEX_VARIABLES = ("S1", "S1_conf", "ST", "ST_conf")


def require_netcdf() -> None:
    """Refuse in one line (:class:`PresetError`) when xarray, h5netcdf or h5py is missing."""
    for module in ("xarray", "h5netcdf", "h5py"):
        try:
            __import__(module)
        except ImportError:
            raise PresetError(
                "command line", OPTION, f"netcdf needs {module}, which is not installed", EXTRA
            ) from None


def _unit(name: str) -> str:
    return "rad" if name.endswith("_rad") else "m"


def motion_dataset(result: Any, attributes: Mapping[str, Any]):
    """The Dataset of a :class:`~planar_tui.motion.runner.MotionResult`; ``attributes``
    (preset, job, version, seed ...) become the Dataset's attributes."""
    import xarray as xr

    names = list(result.names)
    coords: dict[str, Any] = {
        "time": ("time", np.asarray(result.t_s, dtype=np.float64), {"units": "s"}),
        "output": ("output", names, {"units": ", ".join(map(_unit, names))}),
        "statistic": ("statistic", list(BAND_STATISTICS)),
    }
    band = np.asarray(result.band).transpose(0, 2, 1)  # (R, 5, n_out) -> (R, n_out, 5)
    variables: dict[str, Any] = {
        "band": (
            ("time", "output", "statistic"),
            band,
            {"long_name": "band of each output over the robots (rad or m, see output)"},
        ),
    }
    if result.analyses:
        methods = list(dict.fromkeys(a.method for a in result.analyses))
        times = sorted({float(a.speed_rad_s) for a in result.analyses})  # the time slot
        inputs = list(result.analyses[0].names)
        shape = (len(methods), len(times), len(names), len(inputs))
        indices = np.full((4, *shape), np.nan)
        percent = np.full(shape, np.nan)
        for analysis in result.analyses:
            at = (methods.index(analysis.method), times.index(float(analysis.speed_rad_s)))
            indices[(slice(None), *at)] = analysis.indices
            percent[at] = analysis.percent
        dims = ("method", "index_time", "output", "input")
        coords.update(
            method=("method", methods),
            input=("input", inputs),
            index_time=("index_time", times, {"units": "s"}),
        )
        for k, name in enumerate(INDEX_VARIABLES):
            variables[name] = (dims, indices[k], {"units": "1"})
        variables["percent"] = (dims, percent, {"units": "%", "long_name": "percent of ST"})
    attrs = {key: _attribute(value) for key, value in attributes.items()}
    attrs.update(
        robots=int(result.robots), device=str(result.device), notes="; ".join(result.notes)
    )
    return xr.Dataset(variables, coords=coords, attrs=attrs)


def _attribute(value: Any) -> Any:
    """A NetCDF attribute: text, an integer or a float (lists become comma-separated text)."""
    if isinstance(value, bool) or value is None:
        return str(value)
    if isinstance(value, int | float | str):
        return value
    if isinstance(value, list | tuple):
        return ", ".join(map(str, value))
    return str(value)


def write_motion_netcdf(path: Path, result: Any, attributes: Mapping[str, Any]) -> Path:
    """Write the Dataset (h5netcdf engine) to a new file ``path`` (never replaced)."""
    require_netcdf()
    dataset = motion_dataset(result, attributes)
    return write_new(path, lambda temp: dataset.to_netcdf(temp, engine="h5netcdf"), OPTION)


def netcdf_path(band_csv: Path) -> Path:
    """The NetCDF file of a motion job: its band CSV's name with ``.nc``."""
    return Path(band_csv).with_suffix(".nc")


def export_job(job: Any, result: Any, path: Path) -> Path:
    """Write a finished motion job's Dataset to ``path``, with the preset, the job, the
    version, the seed, N and the methods in its attributes."""
    attributes = {
        "preset": str(job.preset_path),
        "job": job.label,
        "planar_tui_version": __version__,
        "seed": job.spec.seed,
        "samples": job.spec.samples,
        "methods": list(job.spec.methods),
    }
    return write_motion_netcdf(path, result, attributes)
