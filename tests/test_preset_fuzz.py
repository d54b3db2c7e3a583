"""A mutation fuzz of the preset loader: bundled presets' text with characters deleted,
duplicated or replaced, deep nesting, huge numbers and long names inserted. Whatever the
text, :func:`planar_tui.presets.load_preset` either returns a preset or raises
:class:`~planar_tui.errors.PresetError` (the CLI's one line and exit code 2), never
anything else. Deterministic (``derandomize``), a few hundred examples."""

from __future__ import annotations

import re
import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from planar_tui.errors import PresetError
from planar_tui.presets import load_preset
from tests.conftest import PRESETS

pytestmark = pytest.mark.slow  # hypothesis-driven fuzz (see pyproject.toml's markers)

SOURCES = [path.read_text(encoding="utf-8") for path in sorted(PRESETS.glob("*.toml"))]
#: Characters that matter to TOML and to the loader's readers.
ALPHABET = "[]{}=\"'.,:0123456789eE+-_#\n \tinfa\\\0xyz"


@st.composite
def insertions(draw) -> str:
    """Something to insert: a character, deep nesting, a huge number, a long name."""
    depth = draw(st.integers(1, 1500))
    digits = draw(st.integers(300, 6000))
    return draw(
        st.sampled_from(
            [
                draw(st.text(ALPHABET, min_size=1, max_size=4)),
                "[" * depth,
                "[" * depth + "]" * depth,
                "x = " + "[" * depth + "1" + "]" * depth + "\n",
                "{a = " * depth + "1" + "}" * depth,
                "1" + "0" * digits,
                "-1" + "0" * digits,
                "1e" + "9" * draw(st.integers(3, 400)),
                "9" * 310 + ".0",
                '"' + "n" * draw(st.integers(200, 5000)) + '.csv"',
                '"a\\u0000b.csv"',
                "2**40",
                "18446744073709551616",
                "1e-300",
                "1e200",
            ]
        )
    )


@st.composite
def mutated_presets(draw) -> str:
    """A bundled preset's text after one to three mutations."""
    text = draw(st.sampled_from(SOURCES))
    for _ in range(draw(st.integers(1, 3))):
        at = draw(st.integers(0, len(text)))
        width = draw(st.integers(1, 12))
        operation = draw(st.sampled_from(["delete", "duplicate", "replace", "insert", "value"]))
        if operation == "value":  # a value (after "=", "[" or ",") replaced by an insertion
            starts = [i + 1 for i, c in enumerate(text) if c in "=[,"]
            at = draw(st.sampled_from(starts)) if starts else at
            end = min((i for i in map(text.find, ",]\n", [at] * 3) if i >= 0), default=at)
            text = text[:at] + " " + draw(insertions()) + text[end:]
        elif operation == "delete":
            text = text[:at] + text[at + width :]
        elif operation == "duplicate":
            text = text[: at + width] + text[at : at + width] + text[at + width :]
        elif operation == "replace":
            text = text[:at] + draw(st.text(ALPHABET, min_size=1, max_size=3)) + text[at + 1 :]
        else:
            text = text[:at] + draw(insertions()) + text[at:]
    return text


FOLDER = Path(tempfile.mkdtemp(prefix="planar-tui-fuzz-"))


@settings(
    max_examples=300,
    derandomize=True,
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
@given(mutated_presets())
def test_the_loader_raises_only_preset_errors(text):
    path = FOLDER / "mutated.toml"
    path.write_text(text, encoding="utf-8", errors="surrogatepass")
    try:
        load_preset(path)
    except PresetError as error:
        assert "\n" not in str(error)  # the CLI prints one line


# -- the sweep tables --------------------------------------------------------------------
SWEEP_SOURCES = [text for text in SOURCES if "[[sweep]]" in text] + [
    (PRESETS / "paper-a-table1.toml").read_text(encoding="utf-8")
    + '\n[[sweep]]\njob = "simulate[2]"\nvalues."robot.lengths_m[3]" = [0.1, 0.2]\n'
    "values.duration_s = { from = 0.1, to = 0.2, count = 3 }\nmax_points = 10\n"
    'point_outputs = "pts"\nplot = "s.png"\n'
    '\n[[sweep]]\njob = "torques"\nranges."robot.masses_kg[1]" = [0.5, 2.0]\n'
    'sample = { method = "sobol", count = 8, seed = 3 }\n',
]
#: What a sweep table's keys and key paths become.
SWEEP_WORDS = [
    "job",
    "values",
    "ranges",
    "sample",
    "combine",
    "output",
    "point_outputs",
    "plot",
    "max_points",
    "method",
    "count",
    "seed",
    "from",
    "to",
    "grid",
    "zip",
    "robot",
    "robot3rrr",
    "lengths_m",
    "masses_kg",
    "orientation_deg",
    "nope",
    "sobol",
    "lhs",
    "uniform",
    "workspace",
    "simulate",
    "torques",
    "sensitivity",
]
INDICES = [
    "[0]",
    "[1]",
    "[99]",
    "[-1]",
    "[²]",
    "[1" + "0" * 5000 + "]",
    "[1][1]",
    "[",
    "]",
    "[x]",
    "[18446744073709551616]",
    ".",
    "..",
]


@st.composite
def mutated_sweeps(draw) -> str:
    """A preset with sweeps after one to three mutations of its sweep tables: a word (a
    key, a key path's table or key, a value) replaced, an index changed, a value
    replaced by an insertion, characters deleted or duplicated."""
    text = draw(st.sampled_from(SWEEP_SOURCES))
    start = text.index("[[sweep]]")
    head, sweeps = text[:start], text[start:]
    for _ in range(draw(st.integers(1, 3))):
        operation = draw(st.sampled_from(["word", "index", "value", "delete", "duplicate"]))
        if operation == "word":
            words = [m.span() for m in re.finditer(r"[A-Za-z_][A-Za-z0-9_]*", sweeps)]
            begin, end = draw(st.sampled_from(words))
            sweeps = sweeps[:begin] + draw(st.sampled_from(SWEEP_WORDS)) + sweeps[end:]
        elif operation == "index":
            spots = [m.span() for m in re.finditer(r"\[\d+\]", sweeps)] or [(0, 0)]
            begin, end = draw(st.sampled_from(spots))
            sweeps = sweeps[:begin] + draw(st.sampled_from(INDICES)) + sweeps[end:]
        elif operation == "value":
            starts = [i + 1 for i, c in enumerate(sweeps) if c in "=[,"]
            at = draw(st.sampled_from(starts))
            end = min((i for i in map(sweeps.find, ",]}\n", [at] * 4) if i >= 0), default=at)
            sweeps = sweeps[:at] + " " + draw(insertions()) + sweeps[end:]
        else:
            at = draw(st.integers(0, len(sweeps)))
            width = draw(st.integers(1, 12))
            if operation == "delete":
                sweeps = sweeps[:at] + sweeps[at + width :]
            else:
                sweeps = sweeps[: at + width] + sweeps[at : at + width] + sweeps[at + width :]
    return head + sweeps


@settings(
    max_examples=150,
    derandomize=True,
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
@given(mutated_sweeps())
def test_the_sweep_checks_raise_only_preset_errors(text):
    """Whatever a sweep table holds, reading it, making a sample of its points and
    checking its limits (all the CLI does before running it) either passes or raises a
    one-line :class:`PresetError`."""
    from planar_tui.sweep.budget import check_sweep_budget
    from planar_tui.sweep.points import make_points
    from planar_tui.sweep.service import check_figure
    from planar_tui.sweep.spec import parse_sweeps

    path = FOLDER / "mutated-sweep.toml"
    path.write_text(text, encoding="utf-8", errors="surrogatepass")
    try:
        preset = load_preset(path)
        prepared = [(sweep, make_points(sweep)) for sweep in parse_sweeps(preset)]
        for sweep, points in prepared:
            check_figure(sweep, points)
        check_sweep_budget(prepared, None, None)
    except PresetError as error:
        assert "\n" not in str(error)  # the CLI prints one line
