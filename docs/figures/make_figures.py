"""Regenerate the figure gallery: every job and sweep of every bundled preset, run at the
preset's own settings (sweeps in this process), drawn as a small PNG in docs/figures/, and
the gallery part of docs/figures.md.

    python docs/figures/make_figures.py            # every preset (about a minute on 2 cores)
    python docs/figures/make_figures.py paper-b-table3 path-3rrr   # these presets only

Named presets have their figures and their gallery sections written again (the others'
sections kept as they are, every section in the bundled presets' order). A preset's
optimisations are not run here (their jobs are).

The PNGs are drawn at 80 dpi and reduced to a 64-colour palette (Pillow, which matplotlib
installs) so that each stays a few tens of KB; the CLI's figures are full colour.
"""

from __future__ import annotations

import io
import re
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
DOCS = HERE.parent
DPI = 80
COLOURS = 64
#: docs/figures.md is kept up to this line; the gallery below it is written here.
MARKER = "<!-- gallery: written by docs/figures/make_figures.py -->"


def small_png(figure, path: Path) -> int:
    """Write ``figure`` as a palette PNG; returns its size in bytes."""
    from PIL import Image

    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=DPI)
    figure.clear()
    image = (
        Image.open(buffer).convert("RGB").quantize(colors=COLOURS, method=Image.Quantize.MEDIANCUT)
    )
    image.save(path, format="PNG", optimize=True)
    return path.stat().st_size


def file_stem(preset: str, key: str) -> str:
    return f"{preset}-" + re.sub(r"[^a-z0-9]+", "-", key).strip("-")


def main(names: list[str]) -> None:
    from planar_tui import batch
    from planar_tui.figures import figure_for_result, figure_for_table
    from planar_tui.presets import load_preset
    from planar_tui.resources import bundled_presets, preset_description
    from planar_tui.runtime import configure_process
    from planar_tui.sweep.service import run_sweep
    from planar_tui.sweep.spec import parse_sweeps

    configure_process()
    presets = [p for p in bundled_presets() if not names or p.stem in names]
    sections = {}
    for path in presets:
        preset = load_preset(path)
        lines = [f"## `{path.stem}`", "", preset_description(path), ""]
        for job in batch.prepare_jobs(preset.jobs):
            result = batch.run_job(job)
            stem = file_stem(path.stem, job.key)
            size = small_png(figure_for_result(job, result), HERE / f"{stem}.png")
            print(f"{stem}.png {size / 1024:.0f} KB", flush=True)
            lines += [
                f"**{job.key}** (`{job.output}`): {result.summary}",
                "",
                f"![{path.stem} {job.key}](figures/{stem}.png)",
                "",
            ]
        for sweep in parse_sweeps(preset):
            run = run_sweep(sweep, workers=1)
            stem = file_stem(path.stem, sweep.name)
            size = small_png(figure_for_table(run.table, sweep.label), HERE / f"{stem}.png")
            print(f"{stem}.png {size / 1024:.0f} KB", flush=True)
            lines += [
                f"**{sweep.name}** (`{sweep.output}`): {len(run.outcomes)} points of "
                f"{sweep.job.key}, {run.failed} failed",
                "",
                f"![{path.stem} {sweep.name}](figures/{stem}.png)",
                "",
            ]
        sections[path.stem] = "\n".join(lines)
    page = DOCS / "figures.md"
    text = page.read_text(encoding="utf-8")
    order = [path.stem for path in bundled_presets()]
    page.write_text(gallery_page(text, sections, order, keep=bool(names)), encoding="utf-8")


def gallery_page(text: str, sections: dict[str, str], order: list[str], keep: bool) -> str:
    """``text`` (docs/figures.md) with its gallery (below :data:`MARKER`) made of
    ``sections`` by preset name, in ``order``; ``keep``: the page's other sections stay."""
    head, _, gallery = text.partition(MARKER)
    shown = {}
    if keep:
        for chunk in re.split(r"\n(?=## `)", gallery):
            found = re.match(r"## `([^`]+)`", chunk)
            if found:
                shown[found.group(1)] = chunk.strip("\n")
    shown.update({name: section.strip("\n") for name, section in sections.items()})
    names = [name for name in order if name in shown]
    return head + MARKER + "\n\n" + "\n\n".join(shown[name] for name in names) + "\n"


if __name__ == "__main__":
    main(sys.argv[1:])
