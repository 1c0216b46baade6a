"""Reward-penalty against the other strategies, run for run: Mann-Whitney U tests.

For each scene, planner and bias, every strategy is compared with consecutive
selection (the baseline OMPL uses) on the counted time (unsolved runs at the
time limit) and on the iteration count, which does not depend on how loaded the
machine is. Two-sided ``scipy.stats.mannwhitneyu``; the p-value says how often
samples this different would arise were both strategies equally fast.
"""

from __future__ import annotations

import numpy as np

from lazyground.bench.tables import config_label, counted_time
from lazyground.settings import Strategy

BASELINE = Strategy.CONSECUTIVE.value


def mann_whitney_p(a, b, alternative: str = "two-sided") -> float:
    """Mann-Whitney U p-value of two samples (nan when either has fewer than two or all are equal);
    ``alternative="less"``: the one-sided test that ``a`` tends to be smaller than ``b``."""
    from scipy.stats import mannwhitneyu

    if len(a) < 2 or len(b) < 2 or (np.ptp(np.r_[a, b]) == 0):
        return float("nan")
    return float(mannwhitneyu(a, b, alternative=alternative).pvalue)


def strategy_table(rows: list[dict]) -> str:
    """Markdown: per scene, planner and bias, each strategy's mean/median time, mean iterations and
    resamplings, and the Mann-Whitney p-values of time and iterations against consecutive ("" when
    the run has no consecutive rows, or fewer than two runs)."""
    ours = [r for r in rows if r["planner"].startswith("lazyground") and r["status"] not in ("interrupted", "error")]
    groups: dict[tuple, dict[str, list[dict]]] = {}
    for r in ours:
        groups.setdefault((r["scene"], r["planner"], r["bias"]), {}).setdefault(r["strategy"], []).append(r)
    head = ["Scene", "Planner", "Bias %", "Strategy", "runs", "solved", "mean s", "median s", "mean iterations",
            "resamplings", "p (time)", "p (iterations)"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for (scene, planner, bias), by in sorted(groups.items(), key=lambda kv: (kv[0][0], kv[0][1], float(kv[0][2] or 2))):
        base = by.get(BASELINE)
        for strategy in [s.value for s in Strategy if s.value in by]:
            rs = by[strategy]
            t = np.array([counted_time(r) for r in rs])
            it = np.array([float(r["iterations"] or 0) for r in rs])
            p_t = p_it = ""
            if base is not None and strategy != BASELINE:
                p_t = f"{mann_whitney_p(t, [counted_time(r) for r in base]):.3g}"
                p_it = f"{mann_whitney_p(it, [float(r['iterations'] or 0) for r in base]):.3g}"
            label = config_label(rs[0]).split(" (")[0]
            lines.append(f"| {scene} | {planner} | {float(bias) * 100:g} | {label} | {len(rs)} | "
                         f"{sum(r['status'] == 'solved' for r in rs)} | {t.mean():.3f} | {np.median(t):.3f} | "
                         f"{it.mean():.0f} | {np.mean([float(r['resamplings'] or 0) for r in rs]):.1f} | {p_t} | {p_it} |")
    return "\n".join(lines) + "\n"
