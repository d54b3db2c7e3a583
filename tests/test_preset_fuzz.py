"""A mutation fuzz of the preset loader: bundled presets' text with characters deleted,
duplicated or replaced, deep nesting, huge numbers and long names inserted. Whatever the
text, :func:`planar_tui.presets.load_preset` either returns a preset or raises
:class:`~planar_tui.errors.PresetError` (the CLI's one line and exit code 2), never
anything else. Deterministic (``derandomize``), a few hundred examples."""

from __future__ import annotations

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
