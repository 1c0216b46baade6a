"""Plant the bugs of docs/reliability.md's "Planted bugs" table again, one at a time, and run the tests that catch them.

Usage (from the repository root)::

    nice python3 tools/planted.py            # every bug (a few minutes: two need Drake and the compiled kernels)
    nice python3 tools/planted.py 1 5 6      # some of them
    python3 tools/planted.py --list          # the bugs, their patches and tests

Each bug is a textual patch (an exact piece of code and what replaces it) applied to a scratch copy of the
working tree (``--work``, default /tmp/lazyground-planted); the named tests then run there and the bug is
"caught" when pytest reports a failing test (exit 1). First the named tests run on the unpatched copy: they
must pass, or a failure would prove nothing. A patch whose code is no longer in the tree is reported as such
(the code moved or was removed: the table needs updating), never as caught.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
IGNORE = shutil.ignore_patterns(".git", "mutants", "*.pyc", ".pytest_cache", ".hypothesis", "lazyground_output",
                                "bench_output", "*.egg-info")


@dataclass(frozen=True)
class Bug:
    key: str
    what: str
    file: str
    old: str  # must occur in the file (every occurrence is replaced)
    new: str
    tests: tuple[str, ...]


BUGS = (
    Bug("1", "RewardPenalty.reward writes the weight without updating the heap",
        "lazyground/planning/strategies.py", "self._update(index, reward_weight(w))", "self._w[index] = reward_weight(w)",
        ("tests/contract/test_strategy_contract.py::test_selections_match_the_written_out_rule_under_any_outcomes",)),
    Bug("2", "the certifier's growth bound 1 + s made 1 + s/2 (spheres._growth, the bound levers() promise)",
        "lazyground/drake/spheres.py", "return np.where(s <= 1.0, 1.0 + s, np.inf)",
        "return np.where(s <= 1.0, 1.0 + s / 2, np.inf)",
        ("tests/drake/test_spheres.py::test_the_growth_factor_bounds_the_distance_moved_from_the_lever_at_q",)),
    Bug("2k", "the same growth bound made 1 + s/2 in the compiled kernels (moved_bound: sweep_rows' rows proven "
        "from an anchor)",
        "lazyground/drake/sphere_kernels.py", "a * (1.0 + s) * (1.0 + SAFETY)", "a * (1.0 + s / 2) * (1.0 + SAFETY)",
        ("tests/drake/test_sweep_kernel.py::test_the_moved_bound_is_at_least_the_true_one",)),
    Bug("3", "no tolerance on wrapped axes in GoalRegion.contains",
        "lazyground/regions/base.py", "> s / 2 + tol:", "> s / 2:",
        ("tests/unit/test_regions.py::test_contains_allows_tol_beyond_either_bound_and_no_more",)),
    Bug("4", "left/right ignore the robot base's yaw and offset (lateral reads the world y)",
        "grounding/spatial.py", "return robot_frame(obj.pose.xyz, scene)[1]", "return float(obj.pose.xyz[1])",
        ("tests/unit/test_grounding_base_pose.py",)),
    Bug("5", "the trajectory validator drops abs() from its limit ratio",
        "lazyground/motion/validate.py", "ratio = float(np.max(np.abs(values) / limit))",
        "ratio = float(np.max(values / limit))",
        ("tests/unit/test_validate.py::test_a_velocity_overshoot_is_found_on_either_sign",)),
    Bug("6", "the trajectory validator drops its acceleration check",
        "lazyground/motion/validate.py",
        '(("velocity", traj.qd, traj.limits.velocity), ("acceleration", traj.qdd, traj.limits.acceleration))',
        '(("velocity", traj.qd, traj.limits.velocity),)',
        ("tests/unit/test_validate.py::test_an_acceleration_overshoot_is_found_on_either_sign",)),
    Bug("7", "the far-pair rule removed (half-gap columns proven from one anchor only; SphereCertifier.certify's "
        "anchor path, removed in #32)",
        "lazyground/drake/spheres.py", "ok[:, :, G:2 * G] = np.where((a.sum(axis=2) >= b.sum(axis=2))[:, :, None], a, b)",
        "", ("tests/drake/test_spheres.py",)),
    Bug("7k", "the compiled kernels' far-pair rule: pairs skipped while the largest move is under ROOM, not half "
        "of it (a pair's two geometries can close by twice the largest move)",
        "lazyground/drake/sphere_kernels.py", "count = P if 2.0 * most >= ROOM else tight",
        "count = P if most >= ROOM else tight",
        ("tests/drake/test_sweep_kernel.py::test_a_pair_closing_from_both_sides_is_not_proven_free_from_the_anchor",)),
)


def _pytest(cwd: Path, tests: tuple[str, ...]) -> int:
    return subprocess.run([sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider", *tests], cwd=cwd,
                          capture_output=True, text=True).returncode


def plant(bug: Bug, scratch: Path) -> str:
    """'caught', 'not caught', 'no such code' or 'error (pytest exit N)' for one bug, in the scratch copy."""
    path = scratch / bug.file
    original = path.read_text()
    if bug.old not in original:
        return "no such code"
    path.write_text(original.replace(bug.old, bug.new))
    try:
        code = _pytest(scratch, bug.tests)
    finally:
        path.write_text(original)
    return {0: "not caught", 1: "caught"}.get(code, f"error (pytest exit {code})")


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("bugs", nargs="*", help=f"of {', '.join(b.key for b in BUGS)} (default: all)")
    p.add_argument("--work", type=Path, default=Path("/tmp/lazyground-planted"), help="the scratch copy goes here")
    p.add_argument("--list", action="store_true", help="print the bugs, run nothing")
    args = p.parse_args(argv)
    known = {b.key: b for b in BUGS}
    unknown = [k for k in args.bugs if k not in known]
    if unknown:
        print(f"unknown bug(s) {', '.join(unknown)} (known: {', '.join(known)})", file=sys.stderr)
        return 2
    bugs = [known[k] for k in args.bugs] if args.bugs else list(BUGS)
    if args.list:
        for b in bugs:
            print(f"{b.key}: {b.what}\n   {b.file}: {b.old!r} -> {b.new!r}\n   tests: {' '.join(b.tests)}")
        return 0
    if args.work.exists():
        shutil.rmtree(args.work)
    shutil.copytree(REPO, args.work, ignore=IGNORE, symlinks=True)  # numba's cache (__pycache__/*.nb*) comes along
    clean_runs: dict[tuple[str, ...], int] = {}
    for b in bugs:
        clean = None
        if b.old in (args.work / b.file).read_text():
            if b.tests not in clean_runs:
                clean_runs[b.tests] = _pytest(args.work, b.tests)
            clean = clean_runs[b.tests]
        if clean not in (None, 0):
            verdict = f"tests fail unpatched (pytest exit {clean}): proves nothing"
        else:
            verdict = plant(b, args.work)
        print(f"{b.key}: {verdict} -- {b.what} [{' '.join(b.tests)}]", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
