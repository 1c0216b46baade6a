"""Benchmark results: the CSV of every run, summary statistics, Markdown tables, plots.

Statistics count an unsolved run (timeout, error, no valid goal) at the time
limit, so a configuration that often fails cannot look fast; the success rate
is shown next to it.
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from lazyground.bench.runner import FIELDS
from lazyground.settings import Algorithm, Strategy

STRATEGY_LABEL = {s: s.value.title() for s in Strategy}  # "reward-penalty" -> "Reward-Penalty"


# --- CSV ------------------------------------------------------------------------------------

class CsvSink:
    """Append rows to results.csv as they finish (flushed), so an interrupt keeps them."""

    def __init__(self, path: Path, append: bool = False):
        self.path = Path(path)
        fresh = not (append and self.path.is_file() and self.path.stat().st_size > 0)
        self._f = open(self.path, "w" if fresh else "a", newline="")
        self._w = csv.DictWriter(self._f, fieldnames=FIELDS, extrasaction="ignore")
        if fresh:
            self._w.writeheader()
            self._f.flush()

    def write(self, row: dict) -> None:
        self._w.writerow({k: _csv_value(row.get(k, "")) for k in FIELDS})
        self._f.flush()

    def close(self) -> None:
        self._f.close()


def _csv_value(v):
    return f"{v:.6f}" if isinstance(v, float) else v


def read_csv(path) -> list[dict]:
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


# --- statistics -----------------------------------------------------------------------------

def config_label(row: dict) -> str:
    """How a configuration is named in tables and plots (an objective other than ``first`` appended)."""
    objective = row.get("objective") or "first"
    label = _planner_label(row)
    return label if objective == "first" or not row["planner"].startswith("lazyground") else f"{label}, {objective}"


def _planner_label(row: dict) -> str:
    if row["planner"] == "lazyground":
        return STRATEGY_LABEL.get(row["strategy"], row["strategy"])
    if row["planner"] == "lazyground-bidirectional":
        return STRATEGY_LABEL.get(row["strategy"], row["strategy"]) + f" ({Algorithm.BIDIRECTIONAL})"
    return row["planner"].replace("ompl-", "OMPL ")


def counted_time(row: dict) -> float:
    """The run's time, or the time limit when it did not solve."""
    if row["status"] == "solved":
        return float(row["time_s"])
    return float(row["time_limit"])


@dataclass(frozen=True)
class Stats:
    n: int
    mean: float
    std: float
    median: float
    success: float  # fraction solved

    @staticmethod
    def of(rows: list[dict]) -> "Stats":
        t = np.array([counted_time(r) for r in rows])
        solved = sum(r["status"] == "solved" for r in rows)
        return Stats(len(rows), float(t.mean()), float(t.std(ddof=1)) if len(t) > 1 else 0.0, float(np.median(t)),
                     solved / len(rows))


def group(rows: list[dict]) -> dict[tuple, dict[str, list[dict]]]:
    """{(config label, bias): {scene: rows}}: ours by bias and strategy, then the peers."""
    out: dict[tuple, dict[str, list[dict]]] = {}
    for r in rows:
        out.setdefault((config_label(r), r["bias"]), {}).setdefault(r["scene"], []).append(r)
    order = list(STRATEGY_LABEL.values())
    order += [f"{label} ({Algorithm.BIDIRECTIONAL})" for label in order]

    def rank(key):  # ours (one tree, then bidirectional) by bias then strategy as in the paper, then the peers
        label, bias = key
        base, _, objective = label.partition(", ")  # ours with an objective other than first (#30) after first
        b = float(bias) if bias not in ("", None) else 2.0
        ours = base in order
        return (not ours, ours and Algorithm.BIDIRECTIONAL in label, b, order.index(base) if ours else label, objective)

    return dict(sorted(out.items(), key=lambda kv: rank(kv[0])))


def scenes_of(rows: list[dict]) -> list[str]:
    return list(dict.fromkeys(r["scene"] for r in rows))


def _rows_by_config_and_scene(rows: list[dict]):
    """(config label, bias in percent or "-", scene, its rows), one per table row, in table order."""
    scenes = scenes_of(rows)
    for (label, bias), per_scene in group(rows).items():
        for scene in [s for s in scenes if s in per_scene]:
            yield label, (f"{float(bias) * 100:g}" if bias not in ("", None) else "-"), scene, per_scene[scene]


# --- Markdown -------------------------------------------------------------------------------

def markdown_table(rows: list[dict], title: str = "") -> str:
    """The paper's layout: one row per strategy and bias, per scene mean and std (plus median, success)."""
    rows = [r for r in rows if r["status"] != "interrupted"]
    if not rows:
        return f"{title}\n\n(no finished runs)\n" if title else "(no finished runs)\n"
    scenes = scenes_of(rows)
    head = ["Strategy", "Bias %"]
    for s in scenes:
        head += [f"{s} mean", "std", "median", "solved"]
    lines = [f"{title}\n" if title else "", "| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for (label, bias), per_scene in group(rows).items():
        cells = [label, f"{float(bias) * 100:g}" if bias not in ("", None) else "-"]
        for s in scenes:
            if s in per_scene:
                st = Stats.of(per_scene[s])
                cells += [f"{st.mean:.3f}", f"{st.std:.3f}", f"{st.median:.3f}", f"{st.success * 100:.0f}% of {st.n}"]
            else:
                cells += ["", "", "", ""]
        lines.append("| " + " | ".join(cells) + " |")
    limits = sorted({float(r["time_limit"]) for r in rows})
    lines.append("")
    lines.append(f"Times in seconds, including grounding and goal sampling. Unsolved runs count at the time limit "
                 f"({', '.join(f'{t:g}' for t in limits)} s).")
    return "\n".join(lines).lstrip("\n") + "\n"


def time_split_table(rows: list[dict]) -> str:
    """Where the time goes, over every finished run (timeouts too: their time is planning time as well):
    mean seconds of grounding, goal sampling, collision checking and the rest, and the rest's share of the
    total time (the planner's own time); the median goal-sampling milliseconds per valid goal sample
    (failed attempts included) and valid samples per attempt over all runs; checks per run and time per check."""
    rows = [r for r in rows if r["status"] not in ("interrupted", "error")]  # an error row has no times
    if not rows:
        return "(no finished runs)\n"
    head = ["Scene", "Strategy", "Bias %", "runs", "solved", "time", "grounding", "goal sampling", "collision", "other",
            "other share", "IK ms / goal sample", "valid / attempt", "checks", "µs/check"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for label, b, scene, rs in _rows_by_config_and_scene(rows):
        m = {k: np.mean([float(r[k]) for r in rs]) for k in ("time_s", "grounding_s", "goal_sampling_s", "collision_s", "other_s")}
        share = m["other_s"] / m["time_s"] if m["time_s"] > 0 else float("nan")
        solved = sum(r["status"] == "solved" for r in rs)
        lines.append(f"| {scene} | {label} | {b} | {len(rs)} | {solved} | {m['time_s']:.3f} | {m['grounding_s']:.3f} | "
                     f"{m['goal_sampling_s']:.3f} | {m['collision_s']:.3f} | {m['other_s']:.3f} | {share * 100:.0f}% | "
                     f"{_goal_sampling_cells(rs)} | {_checks_cells(rs)} |")
    return "\n".join(lines) + "\n"


def _goal_sampling_cells(rows: list[dict]) -> str:
    """Median goal-sampling ms per valid goal sample over runs with one, and valid samples per attempt
    over all runs ("-" where a CSV has no attempt counts, e.g. an older one)."""
    sampled = [r for r in rows if float(r.get("goal_samples") or 0) > 0]
    ms = f"{np.median([1e3 * float(r['goal_sampling_s']) / float(r['goal_samples']) for r in sampled]):.1f}" if sampled else "-"
    counted = [r for r in rows if str(r.get("goal_attempts", "")).strip() not in ("", "0")]
    rate = (f"{sum(float(r['goal_samples']) for r in counted) / sum(float(r['goal_attempts']) for r in counted):.3f}"
            if counted else "-")
    return f"{ms} | {rate}"


def _checks_cells(rows: list[dict]) -> str:
    """Mean collision checks per run and mean microseconds per check ("-" for rows without counts, e.g. old CSVs)."""
    counted = [r for r in rows if str(r.get("collision_checks", "")).strip() not in ("", "0")]
    if not counted:
        return "- | -"
    checks = np.array([float(r["collision_checks"]) for r in counted])
    seconds = np.array([float(r["collision_s"]) for r in counted])
    return f"{checks.mean():.0f} | {seconds.sum() / checks.sum() * 1e6:.0f}"


def motion_table(rows: list[dict]) -> str:
    """Shortening and timing after the solve (solved runs with a motion): medians of the raw and final
    path lengths and their ratio, of the straight start-to-goal distance over the raw length (the
    ratio's lower bound), of shortening and timing seconds and their share of the planning time,
    and of the trajectory's duration."""
    rows = [r for r in rows if r["status"] == "solved" and r.get("raw_path_length") not in ("", None)]
    if not rows:
        return ""
    head = ["Scene", "Strategy", "Bias %", "solved", "raw length", "final length", "final / raw", "direct / raw",
            "shortcut s", "timing s", "(shortcut + timing) / planning", "duration s"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for label, b, scene, rs in _rows_by_config_and_scene(rows):
        col = {k: np.array([float(r[k]) if r[k] not in ("", None) else np.nan for r in rs])
               for k in ("raw_path_length", "path_length", "shortcut_s", "timing_s", "time_s", "duration_s")}
        direct = np.array([float(r.get("direct_path_length") or np.nan) for r in rs])  # (absent from older CSVs)
        bound = f"{np.median(direct / col['raw_path_length']) * 100:.0f}%" if np.isfinite(direct).all() else "-"
        med = {k: float(np.nanmedian(v)) for k, v in col.items()}
        ratio = float(np.median(col["path_length"] / col["raw_path_length"]))
        share = float(np.median((col["shortcut_s"] + col["timing_s"]) / col["time_s"]))
        lines.append(f"| {scene} | {label} | {b} | {len(rs)} | {med['raw_path_length']:.2f} | {med['path_length']:.2f} | "
                     f"{ratio * 100:.0f}% | {bound} | {med['shortcut_s']:.3f} | {med['timing_s']:.3f} | {share * 100:.0f}% | "
                     f"{med['duration_s']:.2f} |")
    return "\n".join(lines) + "\n"


def _total_time(row: dict) -> float:
    """What the user waits for a solved run: ``total_s`` (shortening and timing included; ``time_s`` in older
    CSVs); an unsolved run counts at its time limit."""
    if row["status"] == "solved" and row.get("total_s") not in ("", None):
        return float(row["total_s"])
    return counted_time(row)


def objective_table(rows: list[dict]) -> str:
    """Objectives side by side (#30), per scene and configuration: solved runs, the median (shortened) path
    length and the most any run's revolute joint turns from its start (max_sweep), the median total time
    (``total_s``: shortening and timing included, which ``shortest`` does for every candidate), and each
    objective's median path and time against ``first``'s of the same planner, strategy and bias (""
    without first rows). Empty when every row is ``first``."""
    rows = [r for r in rows if r["status"] != "interrupted" and r["planner"].startswith("lazyground")]
    if all((r.get("objective") or "first") == "first" for r in rows):
        return ""
    head = ["Scene", "Strategy", "Bias %", "objective", "solved", "median path", "max sweep (rad)", "runs over 1.2 pi",
            "median total s", "path / first", "total / first"]
    body: list[tuple[int, str]] = []  # (scene's place, line): each scene's objectives together
    order = scenes_of(rows)
    medians: dict[tuple, tuple[float, float]] = {}
    for label, b, scene, rs in _rows_by_config_and_scene(rows):
        base, _, objective = label.partition(", ")
        objective = objective or "first"
        solved = [r for r in rs if r["status"] == "solved"]
        path = float(np.median([float(r["path_length"]) for r in solved])) if solved else float("nan")
        time_s = float(np.median([_total_time(r) for r in rs]))
        swept = [float(r["max_sweep"]) for r in solved if r.get("max_sweep") not in ("", None)]
        if objective == "first":
            medians[(scene, base, b)] = (path, time_s)
        ref = medians.get((scene, base, b))
        ratios = f"{path / ref[0]:.2f} | {time_s / ref[1]:.2f}" if ref and objective != "first" else " | "
        sweep = f"{max(swept):.2f} | {sum(w > 1.2 * np.pi for w in swept)}" if swept else "- | -"
        body.append((order.index(scene), f"| {scene} | {base} | {b} | {objective} | {len(solved)} of {len(rs)} | "
                                         f"{path:.2f} | {sweep} | {time_s:.3f} | {ratios} |"))
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)] + [line for _, line in sorted(body, key=lambda x: x[0])]
    return "\n".join(lines) + "\n"


# --- plots ----------------------------------------------------------------------------------

def pyplot():
    """matplotlib.pyplot on the Agg backend (no display)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def box_plots(rows: list[dict], path, dpi: int = 110) -> None:
    """One panel per scene, one box per configuration (unsolved runs at the time limit)."""
    plt = pyplot()
    rows = [r for r in rows if r["status"] != "interrupted"]
    scenes = scenes_of(rows)
    fig, axes = plt.subplots(1, max(1, len(scenes)), figsize=(4.5 * max(1, len(scenes)), 4.2), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        data, labels = [], []
        for (label, bias), per_scene in group(rows).items():
            if scene in per_scene:
                data.append([counted_time(r) for r in per_scene[scene]])
                labels.append(label + (f"\n{float(bias) * 100:g}%" if bias not in ("", None) else ""))
        ax.boxplot(data)
        ax.set_xticks(range(1, len(labels) + 1), labels, rotation=30, fontsize=8)
        ax.set_title(scene)
        ax.set_ylabel("time (s)")
        ax.yaxis.grid(True, alpha=0.4)
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    plt.close(fig)


def dof_plot(rows: list[dict], path, dpi: int = 110) -> None:
    """Median time (unsolved at the limit) against DOF, one line per configuration; bars: quartiles."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6, 4))
    for (label, bias), per_scene in group(rows).items():
        pts = sorted((int(s.split("_")[-1]), [counted_time(r) for r in rs]) for s, rs in per_scene.items())
        dofs = [d for d, _ in pts]
        med = np.array([np.median(t) for _, t in pts])
        lo = med - np.array([np.percentile(t, 25) for _, t in pts])
        hi = np.array([np.percentile(t, 75) for _, t in pts]) - med
        name = label + (f" {float(bias) * 100:g}%" if bias not in ("", None) else "")
        ax.errorbar(dofs, med, yerr=[lo, hi], marker="o", capsize=3, label=name)
    ax.set_xlabel("degrees of freedom")
    ax.set_ylabel("time (s), median and quartiles")
    ax.set_yscale("log")
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.4)
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
