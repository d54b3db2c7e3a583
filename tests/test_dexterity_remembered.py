"""The dexterity paving's κ enclosures, remembered from the labelling
(:mod:`planar_tui.workspace.paving.remembered`), are what a fresh evaluation of the kept
boxes returns, bit for bit; a box the evaluator never saw is evaluated."""

from __future__ import annotations

import numpy as np

from planar_tui.workspace.paving.remembered import RememberingEvaluator
from tests.test_dexterity import TABLE3, run


def test_the_remembered_kappa_is_a_fresh_evaluation_of_the_kept_boxes(tmp_path):
    ready, result = run(tmp_path, TABLE3.format(precision=0.5, kappa=4, extra=""))
    out = result.dexterity
    fresh = ready.job.spec.mechanism.dexterity(ready.job, ready.prepared)
    _, kappa = fresh(np.ascontiguousarray(out.boxes))
    assert len(out.boxes) > 100
    np.testing.assert_array_equal(out.kappa, kappa)


def test_an_unseen_box_is_evaluated_and_a_seen_one_is_not():
    calls = []

    def evaluate(boxes):
        calls.append(len(boxes))
        verdict = (boxes[:, 0] >= 0).astype(np.int64) * 2  # x_lo < 0: OUT
        return verdict, np.column_stack([boxes[:, 0], boxes[:, 1] + 1.0])

    remembered = RememberingEvaluator(evaluate)
    seen = np.array([[0.0, 1.0, 0.0, 1.0], [2.0, 3.0, 0.0, 1.0], [-1.0, 0.0, 0.0, 1.0]])
    remembered(seen)
    asked = np.array([[2.0, 3.0, 0.0, 1.0], [5.0, 6.0, 0.0, 1.0], [-1.0, 0.0, 0.0, 1.0]])
    got = remembered.enclosures(asked)
    np.testing.assert_array_equal(got, [[2.0, 4.0], [5.0, 7.0], [-1.0, 1.0]])
    assert calls == [3, 2]  # the OUT box is not remembered: evaluated with the unseen one
