"""Benchmark logs in OMPL's text format, and a reader for them.

The writer follows ``ompl::tools::Benchmark::saveResultsToStream`` (the
format ``ompl_benchmark_statistics.py`` turns into a database and Planner
Arena plots): one experiment (scene) per file; one "planner" per
configuration (``lazyground_reward-penalty_bias0.05``, ``ompl_RRT_bias0.05``,
...); per run the properties below. Besides OMPL's own (``time``,
``solved``, ``status``, ``graph states``, ``solution length``, ...) the runs
carry the chosen grounding as enums (``chosen interpretation``, ``chosen
region``), the number of goal samples and resamplings, and the time split.
Unsolved runs report the time they used (OMPL's convention); the Markdown
table counts them at the time limit instead.
"""

from __future__ import annotations

import platform
import socket
from dataclasses import dataclass, field
from datetime import datetime

# OMPL's PlannerStatus::StatusType order (ompl/base/PlannerStatus.h).
OMPL_STATUS = (
    "Unknown status", "Invalid start", "Invalid goal", "Unrecognized goal type", "Timeout",
    "Approximate solution", "Exact solution", "Crash", "Abort", "Infeasible",
)
STATUS_INDEX = {"solved": 6, "timeout": 4, "invalid_start": 1, "no_valid_goal": 2, "error": 7, "interrupted": 8}

# (property name with type, CSV field); None fields are computed below.
PROPERTIES = (
    ("time REAL", "time_s"),
    ("solved BOOLEAN", None),
    ("status ENUM", None),
    ("iterations INTEGER", "iterations"),
    ("graph states INTEGER", "tree_size"),
    ("solution length REAL", "path_length"),
    ("grounding time REAL", "grounding_s"),
    ("goal sampling time REAL", "goal_sampling_s"),
    ("collision checking time REAL", "collision_s"),
    ("other time REAL", "other_s"),
    ("goal samples INTEGER", "goal_samples"),
    ("resamplings INTEGER", "resamplings"),
    ("chosen interpretation ENUM", None),
    ("chosen region ENUM", None),
    ("seed INTEGER", "seed"),
)
NONE_LABEL = "none"


def planner_name(row: dict) -> str:
    """One OMPL "planner" per configuration; no spaces (OMPL uses the name as a table name)."""
    base = row["planner"].replace("-", "_")
    if row["planner"].startswith("lazyground"):
        base += "_" + row["strategy"]
    return base + (f"_bias{row['bias']}" if row["bias"] not in ("", None) else "")


def write_log(path, experiment: str, rows: list[dict], time_limit: float, total_s: float, setup: str = "", seed: int = 0) -> None:
    """Write the rows of one scene as one OMPL benchmark experiment."""
    planners: dict[str, list[dict]] = {}
    for row in rows:
        planners.setdefault(planner_name(row), []).append(row)
    interps = sorted({r["interpretation"] for r in rows if r["interpretation"]})
    regions = sorted({r["region"] for r in rows if r["region"]})
    enums = {
        "status": list(OMPL_STATUS),
        "chosen_interpretation": [NONE_LABEL] + interps,
        "chosen_region": [NONE_LABEL] + regions,
    }
    runs = max((len(v) for v in planners.values()), default=0)
    lines = [
        "lazyground version 0.1.0",
        f"Experiment {experiment}",
        f"Running on {socket.gethostname() or 'UNKNOWN'}",
        f"Starting at {datetime.now().isoformat(timespec='seconds')}",
        "<<<|", *(setup.splitlines() or [""]), "|>>>",
        "<<<|", f"{platform.processor() or platform.machine()}", "|>>>",
        f"{seed} is the random seed",
        f"{time_limit:g} seconds per run",
        "0 MB per run",
        f"{runs} runs per planner",
        f"{total_s:.3f} seconds spent to collect the data",
        f"{len(enums)} enum types",
        *("|".join([name] + values) for name, values in enums.items()),
        f"{len(planners)} planners",
    ]
    names = [p for p, _ in PROPERTIES]
    for name, prows in planners.items():
        lines += [name, "0 common properties", f"{len(names)} properties for each run", *names, f"{len(prows)} runs"]
        for row in prows:
            lines.append("".join(f"{v}; " for v in _values(row, enums)))
        lines.append(".")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def _values(row: dict, enums: dict) -> list[str]:
    out = []
    for prop, fld in PROPERTIES:
        if prop == "solved BOOLEAN":
            out.append("1" if row["status"] == "solved" else "0")
        elif prop == "status ENUM":
            out.append(str(STATUS_INDEX.get(row["status"], 0)))
        elif prop == "chosen interpretation ENUM":
            out.append(str(enums["chosen_interpretation"].index(row["interpretation"] or NONE_LABEL)))
        elif prop == "chosen region ENUM":
            out.append(str(enums["chosen_region"].index(row["region"] or NONE_LABEL)))
        else:
            v = row.get(fld, "")
            out.append("" if v in ("", None) else (f"{float(v):.6f}" if prop.endswith("REAL") else str(int(float(v)))))
    return out


@dataclass
class Experiment:
    """A parsed OMPL benchmark log."""

    name: str
    host: str
    time_limit: float
    runs_per_planner: int
    enums: dict[str, list[str]]
    planners: dict[str, list[dict]] = field(default_factory=dict)  # name -> runs (property -> value or None)
    properties: dict[str, list[str]] = field(default_factory=dict)  # name -> "name TYPE" lines
    version: str = ""


class LogFormatError(ValueError):
    """The text is not an OMPL benchmark log."""


def read_log(path) -> Experiment:
    """Parse an OMPL benchmark log (the layout ``saveResultsToStream`` writes).

    Values come back as float (REAL, INTEGER, BOOLEAN, ENUM) or None when empty.

    Raises:
        LogFormatError: with the line number of the first line that does not fit.
    """
    with open(path) as f:
        lines = f.read().split("\n")
    pos = 0

    def line() -> str:
        nonlocal pos
        if pos >= len(lines):
            raise LogFormatError(f"{path}: unexpected end of file")
        pos += 1
        return lines[pos - 1]

    def expect(words: str) -> str:
        text = line()
        if words not in text:
            raise LogFormatError(f"{path}:{pos}: expected '... {words}', got {text!r}")
        return text

    version = ""
    first = line()
    if " version " in first:
        version = first.split()[-1]
        first = line()
    if not first.startswith("Experiment "):
        raise LogFormatError(f"{path}:{pos}: expected 'Experiment <name>', got {first!r}")
    name = first.split(" ", 1)[1]
    text = line()
    if text.endswith("experiment properties"):
        for _ in range(int(text.split()[0])):
            line()
        text = line()
    host = text.split()[-1]
    expect("Starting at")
    _multiline(line, path)  # set-up information
    if pos < len(lines) and lines[pos] == "<<<|":  # optional CPU information
        _multiline(line, path)
    int(expect("is the random seed").split()[0])
    time_limit = float(expect("seconds per run").split()[0])
    expect("MB per run")
    runs = int(expect("runs per planner").split()[0])
    expect("seconds spent to collect the data")
    text = line()
    enums: dict[str, list[str]] = {}
    if "enum" in text:
        for _ in range(int(text.split()[0])):
            parts = line().split("|")
            enums[parts[0]] = parts[1:]
        text = line()
    if not text.endswith("planners"):
        raise LogFormatError(f"{path}:{pos}: expected '<n> planners', got {text!r}")
    exp = Experiment(name, host, time_limit, runs, enums, version=version)
    for _ in range(int(text.split()[0])):
        pname = line()
        for _ in range(int(expect("common properties").split()[0])):
            line()
        props = [line() for _ in range(int(expect("properties for each run").split()[0]))]
        keys = ["_".join(p.split()[:-1]) for p in props]
        out = []
        for _ in range(int(expect("runs").split()[0])):
            values = line().split("; ")[:-1]
            if len(values) != len(keys):
                raise LogFormatError(f"{path}:{pos}: {len(values)} values for {len(keys)} properties")
            out.append({k: (float(v) if v.strip() else None) for k, v in zip(keys, values)})
        text = line()
        if text.strip() != ".":  # progress properties: skipped
            for _ in range(int(text.split()[0])):
                line()
            for _ in range(int(line().split()[0])):
                line()
            if line().strip() != ".":
                raise LogFormatError(f"{path}:{pos}: expected '.' after planner {pname}")
        exp.planners[pname] = out
        exp.properties[pname] = props
    return exp


def _multiline(line, path) -> str:
    if line() != "<<<|":
        raise LogFormatError(f"{path}: expected '<<<|'")
    out = []
    while (text := line()) != "|>>>":
        out.append(text)
    return "\n".join(out)
