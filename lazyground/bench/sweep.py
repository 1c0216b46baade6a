"""Time to the first solution against the number of interpretations (issue #33): presets, table, plot.

``lazyground bench --family-sweep lot`` runs generated lots of 8-512 free spots with 2 reachable
(the lot grows with N); ``lot-fixed`` one 576-spot layout of which N are free (the others hold parked
cars), so that only the number of interpretations changes;
``rack-panda`` / ``rack-fetch`` cubby racks of 4-256 cans with 1 reachable; ``lot-fraction``
64-spot lots with 1-32 reachable. Each method (our strategies on the chosen planners, the
``--baselines``) gets one curve: the median time (unsolved runs counted at the time limit) and
the success rate at each size.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from lazyground.settings import Strategy

FIXED_SLOTS = 576  # lot-fixed: one layout of this many spots for every N (512 free ones fit)
SWEEPS = {
    "lot": ("lot:{n}:2", (8, 32, 128, 512)),
    "lot-fixed": ("lot:{n}:2:0:" + str(FIXED_SLOTS), (8, 64, 256, 512)),
    "rack-panda": ("rack:panda:{n}:1", (4, 16, 64, 256)),
    "rack-fetch": ("rack:fetch:{n}:1", (4, 16, 64, 256)),
    "lot-fraction": ("lot:64:{n}", (1, 4, 16, 32)),
}


def sweep_keys(name: str, sizes: list[int] | None = None) -> list[str]:
    """The family keys of a sweep (its own sizes unless given).

    Raises:
        ValueError: an unknown sweep name.
    """
    if name not in SWEEPS:
        raise ValueError(f"unknown sweep {name!r} (known: {', '.join(SWEEPS)})")
    pattern, default = SWEEPS[name]
    return [pattern.format(n=n) for n in (sizes or default)]


def size_of(scene: str) -> tuple[str, int, int] | None:
    """(family, interpretations N, reachable k) of a bench scene name such as lot_256_2, lot_256_2_0_576
    (a fixed layout: family lot-fixed) or rack_panda_64_1."""
    parts = scene.split("_")
    try:
        if parts[0] == "lot":
            fixed = len(parts) == 5 or parts[-1].startswith("of")  # lot:N:k:seed:slots, or its scene name
            return "lot-fixed" if fixed else "lot", int(parts[1]), int(parts[2])
        if parts[0] == "rack":
            return f"rack-{parts[1]}", int(parts[2]), int(parts[3])
    except (IndexError, ValueError):
        return None
    return None


def _method(row: dict) -> str:
    from lazyground.bench.tables import config_label

    return config_label(row)


def curves(rows: list[dict]) -> dict:
    """{(family, k or 'N'): {method: [(x, median s, success rate, runs)]}}: x is N at fixed k, or k at fixed N."""
    from lazyground.bench.tables import counted_time

    cells: dict = {}
    for r in rows:
        size = size_of(r["scene"])
        if size is None or r["status"] in ("interrupted", "error"):
            continue
        cells.setdefault((size[0], size[1], size[2]), {}).setdefault(_method(r), []).append(r)
    out: dict = {}
    ns = {}
    for fam, n, k in cells:
        ns.setdefault((fam, k), set()).add(n)
    for (fam, n, k), by in sorted(cells.items()):
        fixed_k = len(ns[(fam, k)]) > 1  # several N at this k: a curve against N; else against k
        key = (fam, f"k={k}") if fixed_k else (fam, f"N={n}")
        for method, rs in by.items():
            times = [counted_time(r) for r in rs]
            solved = sum(r["status"] == "solved" for r in rs) / len(rs)
            out.setdefault(key, {}).setdefault(method, []).append((n if fixed_k else k, float(np.median(times)), solved, len(rs)))
    return out


def sweep_table(rows: list[dict]) -> str:
    """Markdown: per family and method, median seconds (success) at each size."""
    lines = []
    limits: dict = {}
    for r in rows:
        limits.setdefault(_method(r), set()).add(float(r["time_limit"]))
    mixed = len(set().union(*limits.values())) > 1 if limits else False  # e.g. --baseline-time-limit: say each limit
    for (fam, fixed), by in sorted(curves(rows).items()):
        xs = sorted({x for pts in by.values() for x, *_ in pts})
        axis = "N" if fixed.startswith("k") else "k"
        lines += [f"**{fam}, {fixed}** (median s to the first solution, unsolved at the limit; success rate)\n",
                  "| method | " + " | ".join(f"{axis}={x}" for x in xs) + " |", "|---|" + "---|" * len(xs)]
        for method, pts in sorted(by.items()):
            at = {x: (m, s, n) for x, m, s, n in pts}
            cells = [f"{at[x][0]:.2f} ({at[x][1]:.0%} of {at[x][2]})" if x in at else "" for x in xs]
            label = f"{method}, {max(limits[method]):g} s limit" if mixed else method
            lines.append(f"| {label} | " + " | ".join(cells) + " |")
        lines.append("")
    return "\n".join(lines)


def _cells(rows: list[dict]) -> dict:
    """{(family, N, k): {method: rows}} of the finished family rows."""
    cells: dict = {}
    for r in rows:
        size = size_of(r["scene"])
        if size is not None and r["status"] not in ("interrupted", "error"):
            cells.setdefault(size, {}).setdefault(_method(r), []).append(r)
    return cells


def _limit(rs: list[dict]) -> float:
    return max(float(r["time_limit"]) for r in rs)


def sweep_tests(rows: list[dict]) -> str:
    """Markdown: in each (family, N, k) cell, every method's mean time against round-robin's (our planner with the
    consecutive strategy; unsolved runs at the limit), with the two-sided Mann-Whitney p and the one-sided p that
    the method is faster. The runs of a cell may be different layouts of the family (keys with a layout seed), so a
    p per cell needs no repeated scene. No p for a method run with another time limit than round-robin's (its
    unsolved runs would count at another value)."""
    from lazyground.bench.compare import mann_whitney_p
    from lazyground.bench.tables import counted_time

    lines = ["| family | N | k | method | limit s | runs | solved | mean s | median s | p vs round-robin | p (faster) |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for (fam, n, k), by in sorted(_cells(rows).items()):
        base = next((rs for rs in by.values() if rs[0]["planner"].startswith("lazyground") and rs[0]["strategy"] == Strategy.CONSECUTIVE), None)
        bt = [counted_time(r) for r in base] if base else None
        for method, rs in sorted(by.items()):
            t = [counted_time(r) for r in rs]
            p = less = ""
            if bt is not None and rs is not base and _limit(rs) == _limit(base):
                p, less = f"{mann_whitney_p(t, bt):.3g}", f"{mann_whitney_p(t, bt, 'less'):.3g}"
            lines.append(f"| {fam} | {n} | {k} | {method} | {_limit(rs):g} | {len(rs)} | {sum(r['status'] == 'solved' for r in rs)} | "
                         f"{np.mean(t):.2f} | {np.median(t):.2f} | {p} | {less} |")
    return "\n".join(lines) + "\n"


def censored_median(rows: list[dict]) -> tuple[float, bool]:
    """(median time, exact) over runs, unsolved ones counted at their limit. Not exact (a lower bound) when an
    unsolved run enters the median: its true time is beyond the limit."""
    from lazyground.bench.tables import counted_time

    true = [counted_time(r) if r["status"] == "solved" else np.inf for r in rows]
    median = float(np.median(true))
    return (median, True) if np.isfinite(median) else (float(np.median([counted_time(r) for r in rows])), False)


def sweep_ratios(rows: list[dict]) -> str:
    """Markdown: in each (family, N, k) cell, every baseline's median time over each of our methods' (how many
    times faster ours is). A censored median (an unsolved run in it) is a lower bound, so the ratio is a lower
    bound (>=) when the baseline's is censored, an upper bound (<=) when ours is, and unknown when both are.
    Empty without baseline rows."""
    from lazyground.bench.baselines import parse_planner

    lines = ["| family | N | k | ours | baseline | ours median s | baseline median s | baseline / ours |",
             "|---|---|---|---|---|---|---|---|"]
    for (fam, n, k), by in sorted(_cells(rows).items()):
        ours = {m: rs for m, rs in by.items() if rs[0]["planner"].startswith("lazyground")}
        baselines = {m: rs for m, rs in by.items() if parse_planner(rs[0]["planner"]) is not None}
        for o_name, o_rows in sorted(ours.items()):
            o, o_exact = censored_median(o_rows)
            for b_name, b_rows in sorted(baselines.items()):
                b, b_exact = censored_median(b_rows)
                bound = {(True, True): "", (True, False): ">= ", (False, True): "<= "}.get((o_exact, b_exact))
                ratio = "unknown (both censored)" if bound is None else f"{bound}{b / o:.1f}x"
                lines.append(f"| {fam} | {n} | {k} | {o_name} | {b_name} | {'' if o_exact else '>= '}{o:.2f} | "
                             f"{'' if b_exact else '>= '}{b:.2f} | {ratio} |")
    return "\n".join(lines) + "\n" if len(lines) > 2 else ""


def sweep_plot(rows: list[dict], path: Path) -> None:
    """One panel per family: median time against N (or k), a line per method, success rate marked."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    data = curves(rows)
    if not data:
        return
    fig, axes = plt.subplots(1, len(data), figsize=(6 * len(data), 4.5), squeeze=False)
    methods = sorted({m for by in data.values() for m in by})
    colour = {m: plt.get_cmap("tab10")(i % 10) for i, m in enumerate(methods)}  # one colour per method in every panel
    for ax, ((fam, fixed), by) in zip(axes[0], sorted(data.items())):
        for method, pts in sorted(by.items()):
            pts = sorted(pts)
            xs, med, ok = [p[0] for p in pts], [p[1] for p in pts], [p[2] for p in pts]
            line, = ax.plot(xs, med, marker="o", label=method, color=colour[method])
            for x, m, s in zip(xs, med, ok):
                if s < 1:
                    ax.annotate(f"{s:.0%}", (x, m), textcoords="offset points", xytext=(3, 4), fontsize=7, color=line.get_color())
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_xlabel("interpretations N" if fixed.startswith("k") else "reachable k")
        ax.set_ylabel("median time to first solution (s)")
        ax.set_title(f"{fam}, {fixed} (labels: success rate < 100 %)", fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
