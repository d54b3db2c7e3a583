"""Mutation testing of one module against its own fast tests (a development tool, not CI).

Usage (from the repository root, with the project's virtual environment)::

    nice .venv/bin/python tests/mutation.py kernels/interval.py            # every mutant
    nice .venv/bin/python tests/mutation.py planar_tui/limits.py --max 40  # a sample of 40
    .venv/bin/python tests/mutation.py kernels/interval.py --list          # list, run nothing
    .venv/bin/python tests/mutation.py kernels/interval.py --only 12,40    # those mutants
    .venv/bin/python tests/mutation.py planar_tui/csvio.py --tests tests/test_csvio.py

A mutant is one small change to the module's source: a comparison moved by one
(``<`` and ``<=``) or flipped (``<`` and ``>``), an arithmetic operator swapped (``+`` and
``-``, ``*`` and ``/``), a constant nudged (an integer by one either way, a float times
1.2, ``True`` and ``False``), ``min``/``max``, ``floor``/``ceil``, ``down``/``up`` swapped,
``and``/``or`` swapped or one operand of it dropped, a ``not`` or a unary minus dropped, a
condition negated, or a statement replaced by ``pass``. Each mutant is written into a
temporary copy of the repository (the working tree is never written: nothing mutated can be
left behind), and the module's tests from :data:`MODULES` run there
(``pytest -x -n 0 -m "not slow"``) under a timeout, niced. A mutant whose tests fail (or
time out) is *killed*; one whose tests pass *survived*: a change to the code that no test
noticed, either a gap in the tests or an *equivalent* mutant (a change that does not change
what the code computes); the equivalent survivors of each module are listed with a reason
in ``docs/mutation-testing.md``. The score is (killed + timeout) / (run mutants).

Numba: every mutant of a module in ``kernels/`` runs with a fresh, empty ``NUMBA_CACHE_DIR``,
so a kernel is compiled from the mutated source, never loaded from a cache (the mutants of
other modules share one cache, warmed by the unmutated run: planar-tui's kernel cache is
keyed by the kernels' sources, which they leave alone); a kernel module may also ask for
``NUMBA_DISABLE_JIT=1`` (its ``env`` in :data:`MODULES`) where the interpreted code behaves
as the compiled one for its tests, to spare the compilations.

The module -> tests mapping is :data:`MODULES`, the one place to edit. Exit code 0 when
every run mutant was killed, 1 when some survived, 2 on bad usage or when the unmutated
module's tests fail.
"""

from __future__ import annotations

import argparse
import ast
import copy
import glob
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent

#: Each module (a path from the repository root) with its own fast tests (paths or globs
#: from the root, or pytest node ids) and extra environment variables for its test runs.
MODULES: dict[str, dict] = {
    # the deterministic oracle first: with -x most mutants die in its first seconds
    "kernels/interval.py": {"tests": ["tests/test_interval_oracle.py", "tests/test_interval.py"]},
    "planar_tui/workspace/paving/estimate.py": {
        "tests": ["tests/test_limits_thresholds.py", "tests/test_workspace_estimate.py"]
    },
    "planar_tui/workspace/rrr/compute.py": {"tests": ["tests/test_limits_thresholds.py"]},
    "planar_tui/workspace/paving/levels.py": {"tests": ["tests/test_limits_thresholds.py"]},
    "planar_tui/limits.py": {"tests": ["tests/test_limits_thresholds.py"]},
    "kernels/sensitivity_estimators.py": {"tests": ["tests/test_sensitivity_estimators*.py"]},
    "planar_tui/sensitivity/pce.py": {"tests": ["tests/test_sensitivity_pce*.py"]},
    "kernels/aba_planar.py": {"tests": ["tests/test_aba_planar*.py"]},
    "planar_tui/sweep/checkpoint.py": {"tests": ["tests/test_sweep_checkpoint*.py"]},
    "planar_tui/csvio.py": {"tests": ["tests/test_csvio*.py"]},
    "planar_tui/provenance.py": {
        "tests": ["tests/test_provenance*.py", "tests/test_bounded_reads.py"]
    },
}

#: Names swapped in a call (``min(a, b)`` -> ``max(a, b)``, ``math.floor`` -> ``math.ceil``).
SWAPPED_CALLS = {
    "min": "max",
    "max": "min",
    "floor": "ceil",
    "ceil": "floor",
    "down": "up",
    "up": "down",
    "any": "all",
    "all": "any",
}
COMPARE_SHIFT = {
    ast.Lt: ast.LtE,
    ast.LtE: ast.Lt,
    ast.Gt: ast.GtE,
    ast.GtE: ast.Gt,
    ast.Eq: ast.NotEq,
    ast.NotEq: ast.Eq,
    ast.In: ast.NotIn,
    ast.NotIn: ast.In,
    ast.Is: ast.IsNot,
    ast.IsNot: ast.Is,
}
COMPARE_FLIP = {ast.Lt: ast.Gt, ast.LtE: ast.GtE, ast.Gt: ast.Lt, ast.GtE: ast.LtE}
BINOP_SWAP = {
    ast.Add: ast.Sub,
    ast.Sub: ast.Add,
    ast.Mult: ast.Div,
    ast.Div: ast.Mult,
    ast.FloorDiv: ast.Div,
    ast.Mod: ast.FloorDiv,
    ast.Pow: ast.Mult,
}
REMOVABLE = (
    ast.Assign,
    ast.AugAssign,
    ast.AnnAssign,
    ast.Expr,
    ast.Return,
    ast.Raise,
    ast.Continue,
    ast.Break,
)


@dataclass
class Mutant:
    """One change: the byte span ``[start, stop)`` of the source replaced by ``text``."""

    number: int
    line: int
    start: int
    stop: int
    text: str
    description: str


class _Finder(ast.NodeVisitor):
    """Collects the mutation sites of a module (see the module docstring)."""

    def __init__(self, source: bytes):
        self.source = source
        lines = source.splitlines(keepends=True)
        self.offsets = [0]
        for line in lines:
            self.offsets.append(self.offsets[-1] + len(line))
        self.found: list[tuple[ast.AST, str, str]] = []  # (node, replacement, label)

    # -- helpers -----------------------------------------------------------------------------
    def span(self, node: ast.AST) -> tuple[int, int]:
        start = self.offsets[node.lineno - 1] + node.col_offset  # type: ignore[attr-defined]
        stop = self.offsets[node.end_lineno - 1] + node.end_col_offset  # type: ignore[attr-defined]
        return start, stop

    def add(self, node: ast.AST, new: ast.AST | str, label: str) -> None:
        text = new if isinstance(new, str) else f"({ast.unparse(new)})"
        self.found.append((node, text, label))

    # -- what is not mutated: docstrings, annotations, decorators, TYPE_CHECKING blocks --------
    def visit_FunctionDef(self, node: ast.FunctionDef | ast.AsyncFunctionDef) -> None:
        for default in (*node.args.defaults, *node.args.kw_defaults):
            if default is not None:
                self.visit(default)
        body = node.body
        if body and _is_docstring(body[0]):
            body = body[1:]
        last = body[-1] if body else None
        for statement in body:
            if statement is last and isinstance(statement, ast.Return):
                self.generic_visit_statement(statement, removable=False)
            else:
                self.visit_statement(statement, in_function=True)

    visit_AsyncFunctionDef = visit_FunctionDef

    def visit_ClassDef(self, node: ast.ClassDef) -> None:
        body = node.body[1:] if node.body and _is_docstring(node.body[0]) else node.body
        for statement in body:
            self.visit_statement(statement, in_function=False)

    def visit_Module(self, node: ast.Module) -> None:
        body = node.body[1:] if node.body and _is_docstring(node.body[0]) else node.body
        for statement in body:
            self.visit_statement(statement, in_function=False)

    def visit_statement(self, node: ast.stmt, in_function: bool) -> None:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            self.visit(node)
            return
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            return
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            return
        if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant):
            return  # a string standing alone: documentation
        if in_function and isinstance(node, REMOVABLE):
            self.add(node, "pass", "statement removed")
        self.generic_visit_statement(node, removable=in_function)

    def generic_visit_statement(self, node: ast.stmt, removable: bool) -> None:
        if isinstance(node, ast.AugAssign) and type(node.op) in BINOP_SWAP:
            new = copy.deepcopy(node)
            new.op = BINOP_SWAP[type(node.op)]()
            self.add(node, ast.unparse(new), "augmented operator swapped")
        if isinstance(node, (ast.If, ast.While)):
            self.add(node.test, ast.UnaryOp(ast.Not(), node.test), "condition negated")
        for field, value in ast.iter_fields(node):
            if field in ("annotation", "returns", "decorator_list", "type_comment"):
                continue
            children = value if isinstance(value, list) else [value]
            for child in children:
                if isinstance(child, ast.stmt):
                    self.visit_statement(child, in_function=removable)
                elif isinstance(child, ast.AST):
                    self.visit(child)

    # -- expressions -------------------------------------------------------------------------
    def visit_JoinedStr(self, node: ast.JoinedStr) -> None:
        return  # message text

    def visit_arguments(self, node: ast.arguments) -> None:
        return  # annotations; defaults are visited by visit_FunctionDef

    def visit_Compare(self, node: ast.Compare) -> None:
        for index, op in enumerate(node.ops):
            for table, label in ((COMPARE_SHIFT, "comparison moved"), (COMPARE_FLIP, "flipped")):
                if type(op) in table:
                    new = copy.deepcopy(node)
                    new.ops[index] = table[type(op)]()
                    self.add(node, new, label)
        self.generic_visit(node)

    def visit_BinOp(self, node: ast.BinOp) -> None:
        if type(node.op) in BINOP_SWAP:
            new = copy.deepcopy(node)
            new.op = BINOP_SWAP[type(node.op)]()
            self.add(node, new, "operator swapped")
        self.generic_visit(node)

    def visit_BoolOp(self, node: ast.BoolOp) -> None:
        new = copy.deepcopy(node)
        new.op = ast.Or() if isinstance(node.op, ast.And) else ast.And()
        self.add(node, new, "and/or swapped")
        for index in range(len(node.values)):
            rest = [v for i, v in enumerate(node.values) if i != index]
            kept = rest[0] if len(rest) == 1 else ast.BoolOp(node.op, rest)
            self.add(node, kept, "operand dropped")
        self.generic_visit(node)

    def visit_UnaryOp(self, node: ast.UnaryOp) -> None:
        if isinstance(node.op, (ast.Not, ast.USub)):
            self.add(node, node.operand, "unary operator dropped")
        if isinstance(node.op, ast.USub) and isinstance(node.operand, ast.Constant):
            return  # -1.0: the literal's own nudge is enough
        self.generic_visit(node)

    def visit_IfExp(self, node: ast.IfExp) -> None:
        self.add(node.test, ast.UnaryOp(ast.Not(), node.test), "condition negated")
        self.generic_visit(node)

    def visit_Call(self, node: ast.Call) -> None:
        func = node.func
        name = func.id if isinstance(func, ast.Name) else getattr(func, "attr", None)
        if name in SWAPPED_CALLS:
            new_func = copy.deepcopy(func)
            if isinstance(new_func, ast.Name):
                new_func.id = SWAPPED_CALLS[name]
            else:
                new_func.attr = SWAPPED_CALLS[name]  # type: ignore[attr-defined]
            self.add(func, new_func, "call swapped")
        self.generic_visit(node)

    def visit_Constant(self, node: ast.Constant) -> None:
        value = node.value
        if isinstance(value, bool):
            self.add(node, ast.Constant(not value), "constant negated")
        elif isinstance(value, int):
            self.add(node, ast.Constant(value + 1), "constant nudged")
            self.add(node, ast.Constant(value - 1), "constant nudged")
        elif isinstance(value, float):
            self.add(node, ast.Constant(value * 1.2 if value else 0.1), "constant nudged")


def _is_docstring(statement: ast.stmt) -> bool:
    return isinstance(statement, ast.Expr) and isinstance(statement.value, ast.Constant)


def find_mutants(source: bytes) -> list[Mutant]:
    """Every mutant of ``source`` that compiles and changes its syntax tree, in source order."""
    tree = ast.parse(source)
    finder = _Finder(source)
    finder.visit(tree)
    original = ast.dump(tree)
    mutants: list[Mutant] = []
    sites = sorted(finder.found, key=lambda f: (finder.span(f[0]), f[2], f[1]))
    for node, text, label in sites:
        start, stop = finder.span(node)
        mutated = source[:start] + text.encode() + source[stop:]
        try:
            if ast.dump(ast.parse(mutated)) == original:
                continue
            compile(mutated, "<mutant>", "exec")
        except SyntaxError:
            continue
        before = source[start:stop].decode().splitlines()[0]
        before = before if len(before) <= 50 else before[:47] + "..."
        after = text if len(text) <= 50 else text[:47] + "..."
        description = f"{label}: {before} -> {after}"
        mutants.append(Mutant(len(mutants) + 1, node.lineno, start, stop, text, description))  # type: ignore[attr-defined]
    return mutants


def copy_repository(target: Path) -> None:
    """Copy the tracked and untracked, not ignored, files of the working tree to ``target``,
    and link ``planar_tui/kernels`` and ``planar_tui/bundled_presets`` there as the installed
    package maps them, so that the copy's modules are imported, not the working tree's."""
    listed = subprocess.run(
        ["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
        cwd=REPO,
        capture_output=True,
        check=True,
    ).stdout.split(b"\0")
    for name in filter(None, listed):
        source = REPO / os.fsdecode(name)
        if source.is_file():
            (target / os.fsdecode(name)).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, target / os.fsdecode(name))
    (target / "planar_tui" / "kernels").symlink_to("../kernels")
    (target / "planar_tui" / "bundled_presets").symlink_to("../presets")


def resolve_tests(patterns: list[str]) -> list[str]:
    """The tests named by ``patterns`` (globs from the root, or node ids); exit 2 on a
    pattern that names nothing."""
    found = []
    for pattern in patterns:
        path = pattern.split("::")[0]
        matches = sorted(glob.glob(path, root_dir=REPO))
        if not matches:
            sys.exit(f"error: no test file matches {pattern!r} (edit MODULES or pass --tests)")
        found += [pattern] if "::" in pattern else matches
    return found


def run_tests(
    copy_root: Path, tests: list[str], env: dict, timeout_s: float, numba_cache: Path | None
) -> tuple[str, float]:
    """``("passed" | "failed" | "timeout" | "error rc", seconds)`` of the tests in the copy,
    with kernels cached in ``numba_cache`` (``None``: a fresh, empty folder)."""
    command = [sys.executable, "-m", "pytest", "-x", "-q", "-n", "0", "-m", "not slow"]
    command += ["-p", "no:cacheprovider", *tests]
    started = time.monotonic()
    log_path = copy_root / ".mutation-pytest.log"
    with tempfile.TemporaryDirectory(prefix="mutation-numba-") as fresh, log_path.open("wb") as log:
        run_env = {**os.environ, **env, "NUMBA_CACHE_DIR": str(numba_cache or fresh)}
        run_env["PYTHONPATH"] = str(copy_root)
        process = subprocess.Popen(
            command,
            cwd=copy_root,
            env=run_env,
            stdout=log,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
        try:
            rc = process.wait(timeout=timeout_s)
        except subprocess.TimeoutExpired:
            rc = None
        finally:
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()
    seconds = time.monotonic() - started
    if rc is None:
        return "timeout", seconds
    if rc == 0:
        return "passed", seconds
    if rc in (1, 2):  # tests failed, or the mutated module failed to import
        return "failed", seconds
    return f"error {rc}", seconds


def check_copy_is_imported(copy_root: Path, module: str, env: dict) -> None:
    """Exit 2 unless the copy's module (not the working tree's) is what the tests import."""
    name = "planar_tui." + module.removesuffix(".py").replace("/", ".").removeprefix("planar_tui.")
    probe = f"import {name} as m; print(m.__file__)"
    run_env = {**os.environ, **env, "PYTHONPATH": str(copy_root)}
    out = subprocess.run(
        [sys.executable, "-c", probe], cwd=copy_root, env=run_env, capture_output=True, text=True
    )
    imported = Path(out.stdout.strip()).resolve()
    if not imported.is_relative_to(copy_root.resolve()):
        sys.exit(f"error: the tests would import {imported or out.stderr}, not the copy's")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("module", help="path from the repository root, e.g. kernels/interval.py")
    parser.add_argument("--tests", nargs="+", help="tests to run instead of MODULES' entry")
    parser.add_argument("--max", type=int, default=0, help="run a sample of this many mutants")
    parser.add_argument("--seed", type=int, default=0, help="seed of the sample (default 0)")
    parser.add_argument("--only", help="comma-separated mutant numbers to run")
    parser.add_argument("--timeout", type=float, help="seconds per mutant (default 5x baseline)")
    parser.add_argument("--list", action="store_true", help="list the mutants and stop")
    parser.add_argument("--markdown", type=Path, help="also write the table to this file")
    args = parser.parse_args(argv)
    # a `kill` ends the run as Ctrl-C does: the tests' process group killed, the copy removed
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))

    module = args.module
    if module not in MODULES and not args.tests:
        parser.error(f"{module} is not in MODULES ({', '.join(MODULES)}); pass --tests")
    config = MODULES.get(module, {})
    env = dict(config.get("env", {}))
    source = (REPO / module).read_bytes()
    mutants = find_mutants(source)
    chosen = mutants
    if args.only:
        wanted = {int(n) for n in args.only.split(",")}
        chosen = [m for m in mutants if m.number in wanted]
    elif args.max and args.max < len(mutants):
        chosen = sorted(random.Random(args.seed).sample(mutants, args.max), key=lambda m: m.number)
    if args.list:
        for m in chosen:
            print(f"{m.number:4d}  L{m.line:<4d} {m.description}")
        print(f"{len(chosen)} of {len(mutants)} mutants of {module}")
        return 0
    tests = resolve_tests(args.tests or config["tests"])

    results = []
    with tempfile.TemporaryDirectory(prefix="mutation-repo-") as folder:
        copy_root = Path(folder)
        copy_repository(copy_root)
        check_copy_is_imported(copy_root, module, env)
        target = copy_root / module
        shared_cache = None if module.startswith("kernels/") else copy_root / ".numba-cache"
        outcome, baseline_s = run_tests(copy_root, tests, env, 1800.0, shared_cache)
        if outcome != "passed":
            tail = (copy_root / ".mutation-pytest.log").read_text(errors="replace")[-3000:]
            print(f"{tail}\nerror: the unmutated module's tests did not pass ({outcome})")
            return 2
        timeout_s = args.timeout or max(60.0, 5.0 * baseline_s)
        sample = f" (a sample, seed {args.seed})" if len(chosen) < len(mutants) else ""
        print(
            f"{module}: {len(chosen)} of {len(mutants)} mutants{sample}; tests: {' '.join(tests)}"
        )
        print(f"baseline {baseline_s:.1f} s, timeout {timeout_s:.0f} s a mutant")
        try:
            for m in chosen:
                target.write_bytes(source[: m.start] + m.text.encode() + source[m.stop :])
                try:
                    outcome, seconds = run_tests(copy_root, tests, env, timeout_s, shared_cache)
                finally:
                    target.write_bytes(source)
                verdict = {"failed": "killed", "passed": "SURVIVED"}.get(outcome, outcome)
                results.append((m, verdict))
                print(
                    f"{m.number:4d}  L{m.line:<4d} {verdict:9s} {seconds:6.1f} s  {m.description}"
                )
                sys.stdout.flush()
        finally:
            target.write_bytes(source)
    return report(module, results, len(mutants), args.markdown)


def report(module: str, results: list, total: int, markdown: Path | None) -> int:
    """Print the summary (and write the markdown table); 0 when nothing survived."""
    killed = sum(v == "killed" for _, v in results)
    timeouts = sum(v == "timeout" for _, v in results)
    survived = [m for m, v in results if v == "SURVIVED"]
    errors = [m for m, v in results if v.startswith("error")]
    run = len(results)
    score = 100.0 * (killed + timeouts) / run if run else 0.0
    print(
        f"\n{module}: {run} run of {total}; killed {killed}, timeout {timeouts}, "
        f"survived {len(survived)}, error {len(errors)}; score {score:.1f} %"
    )
    for m in survived:
        print(f"  survived {m.number:4d}  L{m.line:<4d} {m.description}")
    if markdown:
        rows = ["| # | line | result | mutant |", "|---|---|---|---|"]
        rows += [f"| {m.number} | {m.line} | {v} | `{m.description}` |" for m, v in results]
        markdown.write_text("\n".join(rows) + "\n", encoding="utf-8")
    return 0 if not survived and not errors else 1


if __name__ == "__main__":
    sys.exit(main())
