"""Mutation testing of the core modules with mutmut, one module at a time on the unit tests that cover it.

Usage (from the repository root; dev extra: ``pip install -e .[dev]``)::

    nice python3 tools/mutation.py                      # every module below (about an hour on 2 cores)
    nice python3 tools/mutation.py regions strategies   # some of them
    nice python3 tools/mutation.py --survivors regions  # again, only the survivors, with the tests added since
    nice -n 19 python3 tools/mutation.py spheres --sample 120 --seed 0   # a seeded sample of a module's mutants
    python3 tools/mutation.py --list                    # the modules and their tests

Each module runs in a scratch copy of the working tree (``--work``, default /tmp/lazyground-mutation/<module>),
whose pyproject.toml gets a ``[tool.mutmut]`` section naming that module's files and tests; mutmut then runs,
for each mutant, the tests that reach the mutated function. The score printed is killed / (killed + survived),
mutants that time out counted as killed; the surviving mutants are listed (``mutmut show NAME`` in the scratch
copy shows one). Equivalent mutants are listed in docs/reliability.md. With ``--sample N``, mutmut first makes
every mutant (and maps tests to functions), then only N of them drawn with ``--seed`` are run and counted.
"""

from __future__ import annotations

import argparse
import json
import os
import random
import re
import shutil
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]

# module -> (files mutated, the unit tests that cover them: the fast subset, no Drake unless the module is Drake's)
MODULES: dict[str, tuple[list[str], list[str]]] = {
    "regions": (["lazyground/regions/*"], ["tests/unit/test_regions.py"]),
    "strategies": (["lazyground/planning/strategies.py"],
                   ["tests/unit/test_strategies.py", "tests/contract/test_strategy_contract.py"]),
    "tree-nn": (["lazyground/planning/tree.py", "lazyground/planning/nn.py"],
                ["tests/unit/test_tree.py", "tests/unit/test_nn.py"]),
    "search": (["lazyground/planning/search.py", "lazyground/planning/rrt.py", "lazyground/planning/birrt.py"],
               ["tests/unit/test_planner_toy.py", "tests/unit/test_birrt_toy.py", "tests/unit/test_fine_recheck.py",
                "tests/contract/test_planner_contract.py"]),
    "cover-rule": (["lazyground/planning/cover.py"],
              ["tests/unit/test_cover.py", "tests/contract/test_strategy_contract.py", "tests/unit/test_strategies.py"]),
    "validate": (["lazyground/motion/validate.py", "lazyground/motion/limits.py"],
                 ["tests/unit/test_validate.py", "tests/unit/test_motion_checks.py"]),
    "spatial": (["grounding/spatial.py"], ["tests/unit/test_spatial.py", "tests/unit/test_grounding.py",
                                          "tests/unit/test_grounding_base_pose.py", "tests/unit/test_grounding_language.py"]),
    "resolve": (["grounding/resolve.py"], ["tests/unit/test_resolve.py", "tests/unit/test_grounding.py", "tests/unit/test_grounding_base_pose.py",
                                          "tests/unit/test_grounding_errors.py", "tests/unit/test_grounding_language.py",
                                          "tests/unit/test_grounding_several.py"]),
    "parse": (["grounding/parse.py"], ["tests/unit/test_parse_edges.py", "tests/unit/test_grounding.py", "tests/unit/test_grounding_errors.py",
                                      "tests/unit/test_grounding_language.py", "tests/unit/test_grounding_several.py"]),
    # Drake modules: tests that compare with Drake's own checker, seconds per mutant (test_spheres.py's
    # 7-scene soundness sweep, 85 s, is left out: test_compiled_certifier.py compares every scene with Drake)
    "spheres": (["lazyground/drake/spheres.py"], ["tests/drake/test_compiled_certifier.py", "tests/drake/test_spheres.py",
                                                   "-k", "not test_never_certifies"]),
    "checker": (["lazyground/drake/checker.py"], ["tests/drake/test_fast_checks.py", "tests/contract/test_checker_contract.py",
                                                   "tests/drake/test_compiled_certifier.py"]),
}

# *.pyc, not __pycache__: numba keeps its compiled kernels there (.nbi/.nbc), 50 s to compile again per copy
IGNORE = shutil.ignore_patterns(".git", "mutants", "*.pyc", ".pytest_cache", ".hypothesis", "lazyground_output",
                                "bench_output", "*.egg-info")


def _mutmut_section(files: list[str], tests: list[str]) -> str:
    return "\n[tool.mutmut]\n" + "\n".join([
        'source_paths = ["lazyground", "grounding"]',
        f"only_mutate = {json.dumps(files)}",
        'also_copy = ["yaml_scenes", "models", "docs", "README.md"]',
        f'pytest_add_cli_args_test_selection = {json.dumps(tests + ["-x", "-q", "-p", "no:cacheprovider"])}',
        "mutate_only_covered_lines = true",
    ]) + "\n"


# mutmut runs every selected test under coverage at each start (mutate_only_covered_lines), minutes per module;
# once the mutants exist (and are not regenerated: the sources are older) that pass decides nothing: skipped
# (the map of tests to functions, mutmut-stats.json, is still made when missing)
_MUTMUT_AGAIN = ("import sys, mutmut.__main__ as m; m.store_lines_covered_by_tests = lambda: None; "
                 "sys.argv[0] = 'mutmut'; m.cli()")


def _mutmut_run(scratch: Path, children: int, names: list[str]) -> None:
    again = (scratch / "mutants" / "grounding").exists() or (scratch / "mutants" / "lazyground").exists()
    head = [sys.executable, "-c", _MUTMUT_AGAIN] if again else ["mutmut"]
    subprocess.run([*head, "run", "--max-children", str(children), *names], cwd=scratch, check=False)


def _results(scratch: Path) -> str:
    return subprocess.run(["mutmut", "results", "--all", "true"], cwd=scratch, capture_output=True, text=True).stdout


def _statuses(scratch: Path) -> dict[str, str]:
    out = {}
    for line in _results(scratch).splitlines():
        key, _, status = line.strip().rpartition(": ")
        if key:
            out[key] = status
    return out


def _file_of(name: str) -> str:
    """The dotted module of a mutant's name (``lazyground.planning.rrt.x_extend__mutmut_3`` -> ``lazyground.planning.rrt``)."""
    return re.split(r"\.x[_\u01c1]", name, maxsplit=1)[0]


def _sample_names(scratch: Path, children: int, size: int, seed: int, per_file: bool = False) -> list[str]:
    """Make every mutant and the test map (a run filtered to no mutant: mutmut stops before running any), then
    draw ``size`` mutant names with ``random.Random(seed)`` from the sorted list (with ``per_file``, ``size``
    from each mutated file's sorted list, files in sorted order, one generator)."""
    if not (scratch / "mutants" / "mutmut-stats.json").exists():
        subprocess.run(["mutmut", "run", "--max-children", str(children), "no-such-mutant-*"], cwd=scratch,
                       check=False, capture_output=True)
    names = sorted(_statuses(scratch))
    rng = random.Random(seed)
    if not per_file:
        return sorted(rng.sample(names, min(size, len(names))))
    groups: dict[str, list[str]] = {}
    for n in names:
        groups.setdefault(_file_of(n), []).append(n)
    return sorted(n for f in sorted(groups) for n in rng.sample(groups[f], min(size, len(groups[f]))))


def run_module(name: str, work: Path, children: int, survivors_only: bool = False,
               sample: int | None = None, seed: int = 0, keep: bool = False, per_file: bool = False) -> dict:
    """Copy the tree, configure mutmut for ``name``, run it; returns the counts by status and the survivors.

    With ``survivors_only``, keep the scratch copy of an earlier run, copy the current tests into it and run
    only the mutants that survived there (after tests were added to kill them). With ``sample``, run and count
    only that many mutants drawn with ``seed``. With ``keep``, an earlier run's scratch copy is used as it is
    and mutants it has already judged are not run again."""
    files, tests = MODULES[name]
    scratch = work / name
    names = []
    if survivors_only:
        names = [line.strip().rpartition(": ")[0] for line in _results(scratch).splitlines() if line.endswith(": survived")]
        for dest in (scratch / "tests", scratch / "mutants" / "tests"):
            shutil.copytree(REPO / "tests", dest, ignore=IGNORE, dirs_exist_ok=True)
        for pyproject in (scratch / "pyproject.toml", scratch / "mutants" / "pyproject.toml"):  # the current selection
            pyproject.write_text(pyproject.read_text().partition("\n[tool.mutmut]\n")[0] + _mutmut_section(files, tests))
        (scratch / "mutants" / "mutmut-stats.json").unlink(missing_ok=True)  # re-map tests to functions: new tests count
    else:
        if not (keep and scratch.exists()):
            if scratch.exists():
                shutil.rmtree(scratch)
            shutil.copytree(REPO, scratch, ignore=IGNORE, symlinks=True)
            pyproject = scratch / "pyproject.toml"
            pyproject.write_text(pyproject.read_text() + _mutmut_section(files, tests))
        if sample is not None:
            names = _sample_names(scratch, children, sample, seed, per_file)
    todo = names
    if keep and names:
        judged = _statuses(scratch)
        todo = [n for n in names if judged.get(n) == "not checked"]
    if todo or not (survivors_only or keep and names):
        _mutmut_run(scratch, children, todo)
    statuses = _statuses(scratch)
    counted = names if sample is not None and not survivors_only else [k for k, v in statuses.items() if v != "not checked"]
    counts: dict[str, int] = {}
    survivors = []
    for key in counted:
        status = statuses[key]
        counts[status] = counts.get(status, 0) + 1
        if status == "survived":
            survivors.append(key)
    killed = counts.get("killed", 0) + counts.get("timeout", 0)
    survived = counts.get("survived", 0)
    score = killed / (killed + survived) if killed + survived else float("nan")
    result = {"module": name, "counts": counts, "score": score, "survivors": survivors, "scratch": str(scratch),
              "sample": None if sample is None else {"size": len(counted), "seed": seed}}
    (scratch / "mutation-result.json").write_text(json.dumps(result, indent=1))
    return result


def recheck(name: str, work: Path, tests: list[str] | None = None) -> dict:
    """Run an earlier run's survivors again against the current tests, without mutmut's bookkeeping: the current
    tests are copied into the scratch copy and, per survivor, pytest runs there with ``MUTANT_UNDER_TEST`` set
    (mutmut's switch for the mutant). Returns {mutant: "killed" | "survived"}; mutmut's own results stay as
    they were (``--survivors`` updates them, at the cost of mapping tests to functions again)."""
    scratch = work / name
    result = json.loads((scratch / "mutation-result.json").read_text())
    shutil.copytree(REPO / "tests", scratch / "mutants" / "tests", ignore=IGNORE, dirs_exist_ok=True)
    selection = tests or [t for t in MODULES[name][1] if t.startswith("tests/")]
    out = {}
    for mutant in result["survivors"]:
        env = {**os.environ, "MUTANT_UNDER_TEST": mutant}
        run = subprocess.run([sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider", *selection],
                             cwd=scratch / "mutants", env=env, capture_output=True, text=True)
        out[mutant] = "survived" if run.returncode == 0 else "killed"
    (scratch / "recheck-result.json").write_text(json.dumps(out, indent=1))
    return out


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("modules", nargs="*", help=f"of {', '.join(MODULES)} (default: all)")
    p.add_argument("--work", type=Path, default=Path("/tmp/lazyground-mutation"), help="scratch copies go here")
    p.add_argument("--children", type=int, default=1, help="mutmut worker processes (default 1: a shared machine)")
    p.add_argument("--list", action="store_true", help="print the modules and their tests, run nothing")
    p.add_argument("--sample", type=int, help="run only this many of each module's mutants, drawn with --seed")
    p.add_argument("--per-file", action="store_true", help="with --sample: that many from each mutated file")
    p.add_argument("--seed", type=int, default=0, help="seed of the --sample draw (default 0)")
    p.add_argument("--recheck", action="store_true",
                   help="run the survivors of an earlier run against the current tests (no mutmut bookkeeping)")
    p.add_argument("--tests", nargs="+", help="with --recheck: these test files instead of the module's selection")
    p.add_argument("--keep", action="store_true",
                   help="use an earlier run's scratch copy as it is; do not run again the mutants it judged")
    p.add_argument("--survivors", action="store_true",
                   help="re-run only an earlier run's surviving mutants, with the current tests")
    args = p.parse_args(argv)
    unknown = [m for m in args.modules if m not in MODULES]
    if unknown:
        print(f"unknown module(s) {', '.join(unknown)} (known: {', '.join(MODULES)})", file=sys.stderr)
        return 2
    if args.list:
        for name, (files, tests) in MODULES.items():
            print(f"{name}: {' '.join(files)}  <-  {' '.join(tests)}")
        return 0
    args.work.mkdir(parents=True, exist_ok=True)
    if args.recheck:
        for m in args.modules:
            out = recheck(m, args.work, args.tests)
            killed = sum(v == "killed" for v in out.values())
            print(f"{m}: {killed} of {len(out)} survivors killed by the current tests")
            print("\n".join(f"  {k}: {v}" for k, v in out.items()))
        return 0
    results = [run_module(m, args.work, args.children, args.survivors, args.sample, args.seed, args.keep,
                          args.per_file)
               for m in args.modules or MODULES]
    print("\n| module | killed | survived | other | score |\n| --- | --- | --- | --- | --- |")
    for r in results:
        c = r["counts"]
        killed, survived = c.get("killed", 0) + c.get("timeout", 0), c.get("survived", 0)
        other = {k: v for k, v in c.items() if k not in ("killed", "timeout", "survived")}
        print(f"| {r['module']} | {killed} | {survived} | {other or ''} | {r['score']:.0%} |")
    for r in results:
        if r["survivors"]:
            print(f"\n{r['module']} survivors (mutmut show NAME in {r['scratch']}):")
            print("\n".join(f"  {s}" for s in r["survivors"]))
    (args.work / "results.json").write_text(json.dumps(results, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
