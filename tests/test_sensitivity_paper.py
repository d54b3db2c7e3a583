"""Paper A Tables 4-5: our percentages next to every printed cell (full N, a few seconds).

Bounds asserted are the ones docs/sensitivity.md explains; they are not tuned to the
paper: where the paper is inconsistent the test says so and checks the inconsistency.
"""

from pathlib import Path

import pytest

from planar_tui.batch import run_job
from planar_tui.presets import load_preset
from tests.sensitivity_paper import compare, read_paper_cells, report

pytestmark = pytest.mark.slow  # end to end (see pyproject.toml's markers)

ROOT = Path(__file__).resolve().parent.parent
REFERENCE = ROOT / "tests" / "data" / "reference" / "paper_sensitivity_tables.csv"


def run_tables():
    results = []
    for table in ("4", "5"):
        for job in load_preset(ROOT / "presets" / f"paper-a-table{table}.toml").jobs:
            result = run_job(job)
            robot = f"{job.robot.n_links}R"
            results.append((table, robot, result.analyses))
    return results


def swap_3r_tau3(table, robot, torque, posture):
    if (table, robot, torque) == ("4", "3R", 3):
        return {"singular": "isotropic", "isotropic": "singular"}[posture]
    return posture


def test_paper_tables_4_and_5_report():
    cells = read_paper_cells(REFERENCE)
    results = run_tables()
    rows = compare(results, cells)
    print("\n" + report(rows))
    worst = {}
    for row in rows:
        key = (row.table, row.robot, row.method)
        worst[key] = max(worst.get(key, 0.0), row.max_difference_pp)
    print({k: round(v, 2) for k, v in worst.items()})
    # plain physics reproduces the 2R eFAST column and Table 5's 6R Sobol' column
    assert worst["4", "2R", "efast"] < 2.5 and worst["5", "2R", "efast"] < 2.5
    assert worst["5", "6R", "sobol"] < 2.0
    # Table 4's 3R τ3 rows are swapped: in the singular posture τ3 = g m3 l3 / 2 cannot
    # depend on l1, l2, yet the paper's "singular" row gives them 55 %; swapped, they fit
    unswapped = [r for r in rows if (r.table, r.robot, r.torque) == ("4", "3R", 3)]
    swapped = [
        r
        for r in compare(results, cells, swap_3r_tau3)
        if (r.table, r.robot, r.torque) == ("4", "3R", 3)
    ]
    print("\nTable 4 3R τ3 compared with the other posture's row:\n" + report(swapped))
    assert min(r.max_difference_pp for r in unswapped) > 40
    assert max(r.max_difference_pp for r in swapped if r.method == "sobol") < 10
