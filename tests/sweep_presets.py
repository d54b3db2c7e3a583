"""Small presets for the sweep tests: a 3-RRR workspace job and a 2R torques job, each
with text placeholders a test fills in (the separate runs' presets are made by text
substitution, not by the sweep's own key-path code)."""

from __future__ import annotations

from pathlib import Path

WORKSPACE = """# sweep test: 3-RRR workspace
[robot3rrr]
base_side_cm = 120
platform_side_cm = 40
proximal_cm = 30
distal_cm = {distal_cm}

[[workspace]]
form = "mean-value"
precision_cm = {precision_cm}
joint_limits_deg = [[20, 70], [110, 160], [245, 295]]
orientation_deg = {orientation_deg}
geometric_reference = false
box_budget = {box_budget}
output = "ws.csv"
"""
WORKSPACE_BASE = {
    "distal_cm": 30,
    "precision_cm": 1.0,
    "orientation_deg": 0,
    "box_budget": 10_000_000,
}

TORQUES = """# sweep test: 2R torques
[robot]
lengths_m = [{l1}, {l2}]
masses_kg = [2.0, {m2}]

[[torques]]
theta_deg = [[30, {theta12}], [-45, 90]]
omega_deg_s = [[10, -20], [5, 5]]
alpha_deg_s2 = [[1, 2], [0, -3]]
output = "tq.csv"
"""
TORQUES_BASE = {"l1": 0.25, "l2": 0.2, "m2": 1.5, "theta12": 60}

SENSITIVITY = """# sweep test: 2R sensitivity
[robot]
lengths_m = [0.3, 0.25]
masses_kg = [2.0, 1.5]

[sensitivity]
posture = [20, 40]
methods = ["sobol"]
samples = 64
tolerance_length_mm = 1
tolerance_mass_g = {mass_g}
output = "sens.csv"
"""


def write(folder: Path, name: str, template: str, sweep: str = "", **values) -> Path:
    """A preset file from ``template`` filled with ``values``, ``sweep`` appended."""
    path = folder / name
    path.write_text(template.format(**values) + "\n" + sweep, encoding="utf-8")
    return path


def one_line(result) -> str:
    """The one line a refused CLI run printed on stderr (no traceback anywhere)."""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert "Traceback" not in result.output
    return lines[0]
