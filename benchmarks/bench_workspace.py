"""Benchmark of the 3-RRR workspace (paper B, Tables 3-5): ``python benchmarks/bench_workspace.py``.

Part 1, in process (kernels compiled and loaded first): every form at the paper's
precision, with seconds, boxes processed, the certified bracket [inside, kept], the
paper's area and the ratio of the paper's MATLAB/INTLAB time to ours; then the
arc-distance form with boundary-only refinement (bracket width in % of the exact area).

Part 2, whole processes through the CLI (median of 3 fresh processes, Numba cache warm):
the issue's targets, beside the floor of any Numba process on this machine (Python +
``import numba`` + loading one cached kernel), measured in the same run.
"""

from __future__ import annotations

import csv
import math
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from planar_tui.runtime import prepare_kernels  # noqa: E402

prepare_kernels()  # before any kernel is imported

from planar_tui.progress import Progress  # noqa: E402
from planar_tui.workspace.compute import BoxBudget, compute_workspace  # noqa: E402
from planar_tui.workspace.geometry import geometric_area  # noqa: E402
from planar_tui.workspace.job import WorkspaceSpec  # noqa: E402
from planar_tui.workspace.robot import Robot3RRR  # noqa: E402

REFERENCE = REPO / "tests" / "data" / "reference" / "paper_workspace_tables.csv"
ROBOT = Robot3RRR()
CASES = {
    3: (((20, 70), (110, 160), (245, 295)), 0.0, ((0, 120), (0, 120)), 0.1171875),
    4: (((-15, 75), (105, 195), (225, 315)), 30.0, ((-40, 120), (-40, 120)), 0.3125),
    5: (((50, 70), (140, 160), (260, 280)), 0.0, ((0, 128), (0, 128)), 0.00390625),
}
PAPER_PRECISION = {0.1171875: "0.1172", 0.3125: "0.3125", 0.00390625: "0.00391"}
REFINE = {3: 0.1171875 / 128, 4: 0.3125 / 128, 5: 0.03125 / 256}


class _Job:
    def __init__(self, spec):
        self.spec, self.preset_path, self.label = spec, "bench", "bench:workspace"
        self.key = "workspace"


def paper_row(table, form, precision):
    with open(REFERENCE, encoding="utf-8") as f:
        for row in csv.DictReader(f):
            same_case = row["table"] == str(table) and row["form"] == form
            if same_case and (form == "geometric" or row["precision_cm"] == precision):
                return row
    return None


def spec(table, form, precision=None, **extra):
    limits, phi, box, eps = CASES[table]
    return WorkspaceSpec(
        joint_limits_deg=limits,
        orientation_deg=phi,
        precision_cm=precision or eps,
        form=form,
        search_box_cm=box,
        geometric_reference=False,
        **extra,
    )


def timed(s):
    started = time.perf_counter()
    out = compute_workspace(ROBOT, s, BoxBudget(_Job(s), Progress()))
    return time.perf_counter() - started, out


def in_process() -> None:
    for t in CASES:  # compile / load every kernel once
        timed(spec(t, "mean-value", 1.0))
        timed(spec(t, "arc-distance", 1.0, refine_precision_cm=0.5))
    print("## In process (kernels loaded)\n")
    print(
        "| table | form | eps (cm) | seconds | boxes | [inside, kept] cm² | exact cm² "
        "| paper cm² | paper s | paper s / ours |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    for table in CASES:
        _, phi, _, eps = CASES[table]
        g = geometric_area(ROBOT, spec(table, "geometric").limits_rad, math.radians(phi))
        forms = [
            ("natural", {}),
            ("natural", {"expanded": True}),
            ("slope", {}),
            ("mean-value", {}),
            ("arc-distance", {}),
        ]
        if table == 5:
            forms = [("mean-value", {}), ("arc-distance", {})]
        for form, extra in forms:
            seconds, out = timed(spec(table, form, **extra))
            name = form + (" (expanded)" if extra else "")
            row = paper_row(table, form, PAPER_PRECISION[eps])
            paper_area = row["area_cm2"] if row and not extra and form != "arc-distance" else "–"
            if extra and row:
                paper_area = row["area_cm2"] + " (printed natural)"
            paper_s = int(row["time_s"]) if row and row["time_s"] and not extra else None
            if form == "arc-distance":
                paper_s = None
            ratio = f"{paper_s / seconds:,.0f}" if paper_s else "–"
            print(
                f"| {table} | {name} | {eps:g} | {seconds:.3f} | {out.boxes_processed:,} "
                f"| [{out.area_inside_cm2:.5g}, {out.area_kept_cm2:.5g}] | {g.area_cm2:.5g} "
                f"| {paper_area} | {paper_s or '–'} | {ratio} |"
            )
    print(
        "\n## Boundary-only refinement with the exact leg test (target: bracket < 0.1 % in <= 1 s)\n"
    )
    print(
        "| table | form | eps → refine (cm) | seconds | boxes | [inside, kept] cm² | width % of exact |"
    )
    print("|---|---|---|---|---|---|---|")
    for table in CASES:
        _, phi, _, eps = CASES[table]
        eps = 0.03125 if table == 5 else eps
        g = geometric_area(ROBOT, spec(table, "geometric").limits_rad, math.radians(phi))
        seconds, out = timed(spec(table, "arc-distance", eps, refine_precision_cm=REFINE[table]))
        width = 100 * (out.area_kept_cm2 - out.area_inside_cm2) / g.area_cm2
        print(
            f"| {table} | arc-distance | {eps:g} → {REFINE[table]:.3g} | {seconds:.3f} "
            f"| {out.boxes_processed:,} | [{out.area_inside_cm2:.6g}, {out.area_kept_cm2:.6g}] "
            f"| {width:.3f} |"
        )
    print("\n## arc-distance vs mean-value at equal eps (target: >= 10x)\n")
    print("| table | eps | mean-value s | arc-distance s | speed-up |")
    print("|---|---|---|---|---|")
    for table in CASES:
        mv, _ = timed(spec(table, "mean-value"))
        arc, _ = timed(spec(table, "arc-distance"))
        print(f"| {table} | {CASES[table][3]:g} | {mv:.4f} | {arc:.4f} | {mv / arc:,.0f}x |")


PRESET = """
[robot3rrr]
[workspace]
joint_limits_deg = {limits}
orientation_deg = {phi}
precision_cm = {eps}
search_box_cm = {box}
form = "{form}"
geometric_reference = false
{extra}output = "out.csv"
"""


def wall(command, runs=3):
    times = []
    for _ in range(runs):
        started = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True, cwd=REPO)
        times.append(time.perf_counter() - started)
    return statistics.median(times)


def whole_process() -> None:
    print("\n## Whole process through the CLI (median of 3, Numba cache warm)\n")
    print("| run | seconds | target |")
    print("|---|---|---|")
    floor = (
        "import numba, numpy as np\n"
        "from planar_tui.kernels.workspace_union import union_area\n"
        "union_area(np.array([[0.0, 1.0, 0.0, 1.0]]))\n"
    )
    subprocess.run([sys.executable, "-c", floor], check=True, cwd=REPO)
    print(
        f"| floor: python + import numba + one cached kernel | "
        f"{wall([sys.executable, '-c', floor]):.2f} | – |"
    )
    print(f"| planar-tui --help | {wall([sys.executable, '-m', 'planar_tui', '--help']):.2f} | – |")
    runs = [
        ("Table 3 mean-value eps=0.1172", 3, "mean-value", None, "", "0.5"),
        ("Table 5 mean-value eps=0.00391", 5, "mean-value", None, "", "3"),
        ("Table 3 arc-distance eps=0.1172", 3, "arc-distance", None, "", "–"),
    ] + [
        (f"Table {t} arc-distance + refinement", t, "arc-distance",
         0.03125 if t == 5 else None, f"refine_precision_cm = {REFINE[t]}\n", "1")
        for t in CASES
    ]  # fmt: skip
    with tempfile.TemporaryDirectory() as folder:
        for label, table, form, eps, extra, target in runs:
            limits, phi, box, default_eps = CASES[table]
            path = Path(folder) / f"bench-{table}-{form}.toml"
            path.write_text(
                PRESET.format(
                    limits=[list(r) for r in limits], phi=phi, eps=eps or default_eps,
                    box=[list(r) for r in box], form=form, extra=extra,
                ),
                encoding="utf-8",
            )  # fmt: skip
            command = [sys.executable, "-m", "planar_tui", "workspace", str(path),
                       "--no-map", "--out-dir", folder]  # fmt: skip
            subprocess.run(command, check=True, capture_output=True, cwd=REPO)  # warm cache
            print(f"| {label} | {wall(command):.2f} | {target} |")


if __name__ == "__main__":
    in_process()
    whole_process()
