"""Draw the certified-performance figures of the docs: the interference-free region
(docs/interference.md) and the error panel (docs/accuracy.md) of the Table-3 3-RRR, as
small PNGs in docs/figures/ (:func:`make_figures.small_png`).

    python docs/figures/make_certified_figures.py
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from make_figures import small_png  # noqa: E402

TABLE3 = """[robot3rrr]
base_side_cm = 120
platform_side_cm = 40
proximal_cm = 30
distal_cm = 30

[workspace]
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
orientation_deg = 0
precision_cm = 0.5
form = "arc-distance"
geometric_reference = false
elbow = [1, -1, 1]
{key}
output = "ws.csv"
"""
FIGURES = {
    "interference-free-region.png": "leg_width_cm = 4",
    "accuracy-error-map.png": "accuracy = { actuator_deg = 0.1, tolerance_cm = 0.01 }",
}


def main() -> None:
    from planar_tui import batch
    from planar_tui.figures import figure_for_result
    from planar_tui.presets import load_preset
    from planar_tui.runtime import configure_process

    configure_process()
    with tempfile.TemporaryDirectory() as folder:
        for name, key in FIGURES.items():
            preset = Path(folder) / "table3.toml"
            preset.write_text(TABLE3.format(key=key), encoding="utf-8")
            (job,) = batch.prepare_jobs(load_preset(preset).jobs)
            result = batch.run_job(job)
            print(result.summary, flush=True)
            size = small_png(figure_for_result(job, result), HERE / name)
            print(f"{name} {size / 1024:.0f} KB", flush=True)


if __name__ == "__main__":
    main()
