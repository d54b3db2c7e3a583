"""Benchmark of a certified path: ``python benchmarks/bench_certified_path.py``.

The bundled ``path-3rrr`` robot (paper B's 3-RRR, Table-3 joint limits, working mode
``elbow = [1, -1, -1]``) on a 1-s quintic path from ``[36, 5, -2]`` to ``[44, 9, 2]`` (cm, cm,
deg), κ ≤ 60 with L the platform's circumradius (25 cm); goal: certified in ≤ 1 s.

* in process (kernels compiled and loaded first): the certificate's seconds (best of 5),
  its verdict, the pose boxes tested and the largest κ's bracket;
* a failing path (elbow ``[1, -1, 1]``, ``[34, 5, 0]`` to ``[46, 9, 0]``, leaving a joint
  limit): its seconds and its first failure's bracket;
* the whole ``planar-tui path3rrr`` process with ``kappa_max`` and 1 000 steps, and without
  it (median of 3 fresh processes each, Numba cache warm): the certificate's share.

The 1, 5 and 15 minute load averages are printed with the figures (the machine is shared).
"""

from __future__ import annotations

import math
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from benchmarks.timing import load, wall  # noqa: E402
from planar_tui.runtime import prepare_kernels  # noqa: E402

prepare_kernels()  # before any kernel is imported

LIMITS = ((20.0, 70.0), (110.0, 160.0), (245.0, 295.0))
PATHS = {
    "certified": ((36.0, 5.0, -2.0), (44.0, 9.0, 2.0), (1, -1, -1)),
    "failing": ((34.0, 5.0, 0.0), (46.0, 9.0, 0.0), (1, -1, 1)),
}
KAPPA_MAX = 60.0
PRESET = """[robot3rrr]
proximal_mass_kg = 0.6
distal_mass_kg = 0.4
platform_mass_kg = 1.5

[[path3rrr]]
from_pose = [36, 5, -2]
to_pose = [44, 9, 2]
duration_s = 1.0
steps = 1000
elbow = [1, -1, -1]
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
kappa_max = 60
output = "path.csv"
"""


class Quiet:
    def start(self, *args):
        pass

    def advance(self, *args):
        pass


def in_process(name: str):
    """``(seconds, certificate)``, best of 5 (the first call compiles or loads)."""
    from planar_tui.workspace.path.certify import certify
    from planar_tui.workspace.rrr.mechanism import MECHANISM
    from planar_tui.workspace.rrr.path import Path3RRRSpec
    from planar_tui.workspace.rrr.robot import Robot3RRR

    start, stop, elbow = PATHS[name]
    robot = Robot3RRR()
    spec = Path3RRRSpec(
        from_pose=start, to_pose=stop, elbow=elbow, joint_limits_deg=LIMITS, kappa_max=KAPPA_MAX
    )
    test = MECHANISM.path_box_test(robot, spec)
    s = (start[0], start[1], math.radians(start[2]))
    e = (stop[0], stop[1], math.radians(stop[2]))
    certify(test, s, e, 1.0, KAPPA_MAX, Quiet())
    best, certificate = math.inf, None
    for _ in range(5):
        started = time.perf_counter()
        certificate = certify(test, s, e, 1.0, KAPPA_MAX, Quiet())
        best = min(best, time.perf_counter() - started)
    return best, certificate


def main() -> None:
    print(f"load before: {load()}")
    print("| figure | value | goal |")
    print("|---|---|---|")
    seconds, c = in_process("certified")
    print(f"| 1-s path certified in process (s, best of 5) | {seconds:.3f} | ≤ 1 |")
    print(f"| verdict, pose boxes tested | {c.certified}, {c.boxes_tested:,} | yes |")
    print(f"| largest κ along the path | [{c.kappa_peak_lo:.5g}, {c.kappa_peak_hi:.5g}] | |")
    seconds, c = in_process("failing")
    print(f"| failing 1-s path in process (s, best of 5) | {seconds:.3f} | |")
    bracket = f"[{c.failure_lo_s:.7g}, {c.failure_hi_s:.7g}] s ({c.reason})"
    print(f"| its verdict, first failure | {c.certified}, {bracket} | width ≤ 1e-3 s |")
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        (folder / "path.toml").write_text(PRESET, encoding="utf-8")
        command = [
            sys.executable,
            "-m",
            "planar_tui",
            "path3rrr",
            str(folder / "path.toml"),
            "--out-dir",
            str(folder),
        ]
        wall(command, runs=1)  # the Numba cache warm
        print(f"| whole process with kappa_max, warm (s, median of 3) | {wall(command):.2f} | |")
        plain = PRESET.replace("kappa_max = 60\n", "")
        (folder / "path.toml").write_text(plain, encoding="utf-8")
        wall(command, runs=1)
        print(f"| the same without kappa_max (s, median of 3) | {wall(command):.2f} | |")
    print(f"load after: {load()}")


if __name__ == "__main__":
    main()
