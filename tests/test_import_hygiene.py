"""`planar-tui --help` imports no heavy module; batch runs never import Textual."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from tests.conftest import REPO

pytestmark = pytest.mark.slow  # real processes (see pyproject.toml's markers)

PROBE = """
import json, sys
from typer.testing import CliRunner
from planar_tui.cli import app

result = CliRunner().invoke(app, sys.argv[1:])
heavy = ("numba", "SALib", "textual", "scipy", "mujoco", "numpy", "matplotlib", "dask",
         "distributed", "shapely", "pydantic", "rich.markdown", "markdown_it", "pygments",
         "rich.traceback", "rich.pretty", "attr")
print(json.dumps({"code": result.exit_code, "loaded": [m for m in heavy if m in sys.modules]}))
"""


def modules_loaded_by(*args: str) -> dict:
    env = dict(os.environ, PYTHONPATH=str(REPO))
    out = subprocess.run(
        [sys.executable, "-c", PROBE, *args],
        capture_output=True,
        text=True,
        env=env,
        check=True,
        cwd=REPO,
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def words_printed_by(code: str) -> list[str]:
    """The words a fresh ``python -c code`` (this checkout importable) prints."""
    env = dict(os.environ, PYTHONPATH=str(REPO))
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True
    )
    return out.stdout.split()


@pytest.mark.parametrize("command", [(), ("run",), ("workspace",), ("sweep",)])
def test_help_loads_no_heavy_module(command):
    """Nor typer's Markdown and traceback renderers (with markdown_it, pygments, attrs),
    nor pydantic (typer's value coercion): help needs none of them."""
    probe = modules_loaded_by(*command, "--help")
    assert probe == {"code": 0, "loaded": []}


def test_help_renders_without_markdown_yet_the_real_modules_import_after_it():
    """The help formatter's stand-ins for ``rich.markdown`` and ``rich.traceback``
    (:func:`planar_tui.cli.output._import_help_formatter`) leave nothing behind: a later
    import gets the real module, and typer's own names for them make the real objects."""
    code = (
        "import sys\n"
        "from typer.testing import CliRunner\n"
        "from planar_tui.cli import app\n"
        "result = CliRunner().invoke(app, ['--help'])\n"
        "assert result.exit_code == 0 and 'Usage: planar-tui' in result.stdout\n"
        "before = 'rich.markdown' in sys.modules or 'rich.traceback' in sys.modules\n"
        "import rich.markdown, rich.traceback, typer.rich_utils as utils\n"
        "made = utils.Markdown('*x*')\n"
        "try:\n"
        "    raise ValueError('x')\n"
        "except ValueError as error:\n"
        "    traced = utils.Traceback.from_exception(type(error), error, error.__traceback__)\n"
        "print(before, type(made) is rich.markdown.Markdown,\n"
        "      type(traced) is rich.traceback.Traceback,\n"
        "      rich.markdown.__file__.endswith('markdown.py'))\n"
    )
    assert words_printed_by(code) == ["False", "True", "True", "True"]


def test_presets_list_loads_no_heavy_module():
    """Nor pydantic: typer's coercion of the option values (``presets --copy``'s ``None``)
    without it (:class:`planar_tui.cli.coercion.CommonValues`)."""
    assert modules_loaded_by("presets")["loaded"] == []


def test_batch_run_never_imports_textual(tmp_path):
    probe = modules_loaded_by("torques", "presets/paper-a-table1.toml", "--out-dir", str(tmp_path))
    assert probe["code"] == 0
    assert "textual" not in probe["loaded"]
    assert "numba" in probe["loaded"]  # the probe can see a heavy import when there is one


def test_a_warm_batch_run_never_imports_matplotlib(tmp_path):
    """Figures cost nothing unless asked for: `run paper-b-table3` (kernels cached by a
    first run) imports no matplotlib; with `--plot` it does (the probe sees it)."""
    probe = modules_loaded_by("run", "paper-b-table3", "--out-dir", str(tmp_path))
    assert probe["code"] == 0 and "numba" in probe["loaded"]
    assert "matplotlib" not in probe["loaded"] and "pydantic" not in probe["loaded"]
    plotted = modules_loaded_by(
        "torques", "paper-a-table1", "--out-dir", str(tmp_path), "--plot", str(tmp_path / "t.svg")
    )
    assert plotted["code"] == 0 and "matplotlib" in plotted["loaded"]


def test_loading_a_cached_kernel_skips_numbas_scipy_blas_probe_but_blas_still_works():
    code = (
        "import sys, numpy as np\n"
        "from planar_tui.runtime import prepare_kernels\n"
        "prepare_kernels()\n"
        "from planar_tui.kernels.dynamics import inverse_dynamics\n"
        "x = np.ones(3)\n"
        "inverse_dynamics(x, x, x, 9.81, x, x, x)\n"
        "before = 'scipy.linalg' in sys.modules\n"
        "from numba import njit\n"
        "dot = njit(lambda a, b: np.dot(a, b))\n"
        "print(before, dot(np.eye(2) * 2.0, np.ones(2)).tolist())\n"
    )
    assert words_printed_by(code) == ["False", "[2.0,", "2.0]"]


def test_prepare_kernels_builds_no_cffi_parser_and_leaves_cffi_importable():
    """numba's cffi typing module is imported with cffi hidden (no pycparser: its C lexer
    took half of numba's first dispatch), kernels run, and cffi (pymoo's moocore needs it)
    imports as usual after."""
    code = (
        "import sys, numpy as np\n"
        "from planar_tui.runtime import prepare_kernels\n"
        "prepare_kernels()\n"
        "from numba.core.typing import cffi_utils\n"
        "from planar_tui.kernels.dynamics import inverse_dynamics\n"
        "x = np.ones(3)\n"
        "inverse_dynamics(x, x, x, 9.81, x, x, x)\n"
        "parser = 'pycparser' in sys.modules\n"
        "import cffi\n"
        "print(cffi_utils.SUPPORTED, parser, type(cffi.FFI()).__name__)\n"
    )
    assert words_printed_by(code) == ["False", "False", "FFI"]


def test_importing_the_package_and_its_kernels_changes_nothing_in_the_process():
    """Process set-up happens where a front end starts (``planar_tui.runtime``), never as
    a side effect of an import: no environment variable, no numba setting, no BLAS patch."""
    code = (
        "import os, sys, json\n"
        "from numba import config\n"
        "before = (dict(os.environ), config.CACHE_DIR)\n"
        "import planar_tui.registry, planar_tui.presets, planar_tui.batch\n"
        "import planar_tui.kernels.dynamics, planar_tui.kernels.workspace3rrr\n"
        "after = (dict(os.environ), config.CACHE_DIR)\n"
        "print(json.dumps([before == after, 'numba.np.arraymath' in sys.modules]))\n"
    )
    env = {k: v for k, v in os.environ.items() if k != "OMP_WAIT_POLICY"}
    env["PYTHONPATH"] = str(REPO)
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True
    )
    assert json.loads(out.stdout) == [True, False]


@pytest.mark.parametrize("user_value", [None, "2"])
def test_a_front_end_runs_blas_on_one_thread_unless_the_user_said(user_value):
    """``configure_process`` sets ``OPENBLAS_NUM_THREADS=1`` before numpy is imported (a
    value the user set wins), and the CLI's ``main`` calls it before any numerical
    import."""
    code = (
        "import os, sys, json\n"
        "from planar_tui.runtime import configure_process\n"
        "import planar_tui.cli\n"
        "loaded = 'numpy' in sys.modules\n"
        "configure_process()\n"
        "print(json.dumps([loaded, os.environ['OPENBLAS_NUM_THREADS']]))\n"
    )
    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    if user_value is not None:
        env["OPENBLAS_NUM_THREADS"] = user_value
    env["PYTHONPATH"] = str(REPO)
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True
    )
    assert json.loads(out.stdout) == [False, user_value or "1"]


def test_prepare_kernels_refuses_to_run_after_a_kernel_was_imported():
    code = (
        "import planar_tui.kernels.rk4\n"
        "from planar_tui.runtime import prepare_kernels\n"
        "prepare_kernels()\n"
    )
    env = dict(os.environ, PYTHONPATH=str(REPO))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert out.returncode == 1
    assert "prepare_kernels() must run before importing planar_tui.kernels." in out.stderr


def test_a_sweep_on_one_worker_imports_no_dask(tmp_path):
    preset = tmp_path / "sweep.toml"
    preset.write_text(
        (REPO / "presets" / "paper-a-table1.toml").read_text()
        + '\n[[sweep]]\njob = "simulate"\nvalues.step_s = [0.01, 0.02]\n'
    )
    probe = modules_loaded_by("sweep", str(preset), "--workers", "1", "--out-dir", str(tmp_path))
    assert probe["code"] == 0
    assert "numba" in probe["loaded"]
    assert "dask" not in probe["loaded"] and "distributed" not in probe["loaded"]
    assert (tmp_path / "sweep-sweep-1.csv").exists()


@pytest.mark.parametrize(("command", "collecting"), [("--help", "False"), ("presets", "True")])
def test_no_garbage_collection_while_the_cli_loads_but_while_a_command_runs(command, collecting):
    """``planar_tui.entry.main`` turns the cyclic collector off while the CLI loads; every
    command turns it back on (``--help`` ends before any command: still off)."""
    code = (
        "import atexit, gc, sys\n"
        "atexit.register(lambda: print('collecting', gc.isenabled()))\n"
        f"sys.argv = ['planar-tui', {command!r}]\n"
        "from planar_tui.entry import main\n"
        "main()\n"
    )
    assert words_printed_by(code)[-2:] == ["collecting", collecting]


@pytest.mark.parametrize("collecting", [True, False])
def test_preparing_the_kernels_leaves_garbage_collection_as_it_was(collecting):
    """numba is imported without cyclic collection (:func:`planar_tui.runtime.
    no_cyclic_collection`), which is then as before: on stays on, off stays off."""
    code = (
        "import gc, sys\n"
        f"gc.enable() if {collecting} else gc.disable()\n"
        "from planar_tui.runtime import no_cyclic_collection, prepare_kernels\n"
        "with no_cyclic_collection():\n"
        "    inside = gc.isenabled()\n"
        "prepare_kernels()\n"
        "print(inside, 'numba' in sys.modules, gc.isenabled())\n"
    )
    assert words_printed_by(code) == ["False", "True", str(collecting)]


KINDS_PROBE = """
import json, sys
from typer.testing import CliRunner
from planar_tui.cli import build_app
from planar_tui.registry import JOB_KINDS

result = CliRunner().invoke(build_app(sys.argv[1]), sys.argv[1:])
print(json.dumps({"code": result.exit_code, "kinds": list(JOB_KINDS.loaded()),
                  "modules": sorted(m for m in sys.modules if m.startswith("planar_tui."))}))
"""

#: Every job kind's module (and the modules only those kinds use).
KIND_MODULES = {
    "planar_tui.dynamics.simulate",
    "planar_tui.dynamics.torques",
    "planar_tui.sensitivity.job",
    "planar_tui.sensitivity.spec",
    "planar_tui.sensitivity.runner",
    "planar_tui.workspace.rrr.job",
    "planar_tui.workspace.fivebar.job",
    "planar_tui.motion.job",
    "planar_tui.motion.spec",
    "planar_tui.motion.runner",
    "planar_tui.workspace.rpr.job",
    "planar_tui.workspace.prr.job",
    "planar_tui.workspace.paving.orientation",
    "planar_tui.workspace.paving.tolerance",
}


def kinds_loaded_by(*args: str) -> dict:
    env = dict(os.environ, PYTHONPATH=str(REPO))
    out = subprocess.run(
        [sys.executable, "-c", KINDS_PROBE, *args],
        capture_output=True,
        text=True,
        env=env,
        check=True,
        cwd=REPO,
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_a_run_imports_only_the_kinds_of_its_jobs(tmp_path):
    """Issue 21: job kinds and their dependencies are imported only when a job of that
    kind runs (:class:`planar_tui.registry.Registry`, ``build_app("run")``)."""
    preset = tmp_path / "torques.toml"
    preset.write_text(
        "[robot]\nlengths_m = [0.3, 0.2]\nmasses_kg = [1.0, 0.8]\n\n"
        "[torques]\ntheta_deg = [[0, 10]]\n"
    )
    probe = kinds_loaded_by("run", str(preset), "--out-dir", str(tmp_path))
    assert probe["code"] == 0 and (tmp_path / "torques-torques-1.csv").exists()
    assert probe["kinds"] == ["torques"]
    assert KIND_MODULES & set(probe["modules"]) == {"planar_tui.dynamics.torques"}
    # the probe sees a kind's module when one is loaded: every kind's command builds them
    everything = kinds_loaded_by("--help")
    assert everything["code"] == 0 and set(everything["modules"]) >= KIND_MODULES


STUDY_PROBE = """
import sys, tempfile
from typer.testing import CliRunner
from planar_tui.cli import app, commands

commands.run_jobs = lambda plan, name: None  # planned and prepared, not run
with tempfile.TemporaryDirectory() as out:
    result = CliRunner().invoke(app, ["run", *sys.argv[1:], "--out-dir", out])
studies = ("planar_tui.sweep.spec", "planar_tui.sweep.service", "planar_tui.optimise.run",
           "planar_tui.optimise.problem", "planar_tui.sweep.execute")
print(result.exit_code, *sorted(m for m in studies if m in sys.modules))
"""


@pytest.mark.parametrize(
    ("arguments", "imported"),
    [
        (("paper-b-table3",), []),
        (("paper-b-table3", "--job", "workspace[4]"), []),
        (
            ("sweep-3rrr-design",),
            ["planar_tui.sweep.execute", "planar_tui.sweep.service", "planar_tui.sweep.spec"],
        ),
    ],
)
def test_a_run_of_jobs_imports_no_sweep_or_optimisation_module(arguments, imported):
    """A preset without ``[[sweep]]`` or ``[[optimise]]`` tables (or a run with
    ``--job``) plans and prepares its jobs without importing the studies' modules (they
    cost the warm single job about a tenth of its CPU); a sweep preset imports them."""
    assert words_printed_by(STUDY_PROBE.replace("sys.argv[1:]", repr(list(arguments)))) == [
        "0",
        *imported,
    ]
