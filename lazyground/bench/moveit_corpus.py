"""The MoveIt corpus (#15): import every scene of tests/data/moveit_corpus (and the paper's
four reference scenes from ../shared when present) and plan its natural request with the
default settings. Shared by tools/corpus_report.py and tests/scenes/test_moveit_corpus.py.
"""

from __future__ import annotations

import statistics
from dataclasses import dataclass, field
from pathlib import Path

import yaml

from lazyground.moveit.convert import ImportOptions
from lazyground.moveit.importer import import_moveit_file
from lazyground.moveit.start import StartOptions

REPO = Path(__file__).resolve().parents[2]
CORPUS = REPO / "tests" / "data" / "moveit_corpus"
# ../shared beside the repo (a git worktree under wt/ sits one level deeper)
REFERENCE = next((p for p in (REPO.parent / "shared", REPO.parents[1] / "shared") if p.is_dir()), REPO.parent / "shared") / "reference" / "moveit_scenes"
REFERENCE_REQUESTS = {"scenario3": "pick up a box"}  # the others: "pick up a can"


@dataclass(frozen=True)
class CorpusEntry:
    """One MoveIt scene, its natural request and how it is imported."""

    name: str
    file: Path
    request: str
    start_from: Path | None = None
    packages: dict[str, Path] = field(default_factory=dict)


@dataclass(frozen=True)
class Run:
    """One (scene, seed) run."""

    scene: str
    seed: int
    status: str
    time_s: float  # grounding + planning (goal sampling and search), as the CLI reports it
    setup_s: float  # building the Drake world (once per scene, shared by its seeds)
    reached: str | None
    iterations: int = 0
    path: object = field(default=None, repr=False, compare=False)  # the solution path (rows over the planned joints)


def corpus_entries(corpus: Path = CORPUS, reference: Path = REFERENCE) -> list[CorpusEntry]:
    """The corpus scenes from corpus.yaml, then the reference scenes that exist."""
    out = []
    manifest = yaml.safe_load((corpus / "corpus.yaml").read_text())
    for name, item in manifest.items():
        out.append(CorpusEntry(name, corpus / item["file"], item["request"],
                               corpus / item["start_from"] if item.get("start_from") else None,
                               {k: corpus / v for k, v in (item.get("packages") or {}).items()}))
    for path in sorted(reference.glob("*.yml")) if reference.is_dir() else []:
        request = next((r for key, r in REFERENCE_REQUESTS.items() if key in path.stem), "pick up a can")
        out.append(CorpusEntry(path.stem.replace("test_fetch_goal_regions_", "reference_"), path, request))
    return out


def import_entry(entry: CorpusEntry, out_dir: Path):
    """Import one entry with the default options (its start file and packages); the ImportResult."""
    options = ImportOptions(robot="fetch", packages=entry.packages,
                            start=StartOptions(request=str(entry.start_from) if entry.start_from else None))
    return import_moveit_file(entry.file, out_dir / f"{entry.name}.yaml", options)


def run_entry(entry: CorpusEntry, out_dir: Path, seeds, **overrides) -> tuple[list[Run], object]:
    """Import ``entry`` and plan its request once per seed (default settings unless overridden).

    Returns:
        The runs, and the DrakeWorld they planned in (for re-checking paths).
    """
    import time

    from lazyground import api
    from lazyground.drake.world import DrakeWorld
    from lazyground.scene import load_scene

    scene = load_scene(import_entry(entry, out_dir).output)
    t0 = time.perf_counter()
    world = DrakeWorld(scene, visual=False)
    setup_s = time.perf_counter() - t0
    runs = []
    for seed in seeds:
        report = api.plan(scene, entry.request, seed=seed, world=world, **overrides)
        res = report.result
        runs.append(Run(entry.name, seed, res.status.value, report.time_s, setup_s, report.chosen_object, res.iterations, res.path))
    return runs, world


def table(runs: list[Run]) -> list[str]:
    """A markdown table per scene: solved, median and max time of the solved runs."""
    lines = ["| scene | solved | median s | max s | world set-up s | reached |", "| --- | --- | --- | --- | --- | --- |"]
    for name in dict.fromkeys(r.scene for r in runs):
        mine = [r for r in runs if r.scene == name]
        ok = [r.time_s for r in mine if r.status == "solved"]
        reached = ", ".join(sorted({r.reached for r in mine if r.reached}))
        lines.append(f"| {name} | {len(ok)}/{len(mine)} | {statistics.median(ok) if ok else float('nan'):.2f} | "
                     f"{max(ok) if ok else float('nan'):.2f} | {mine[0].setup_s:.2f} | {reached} |")
    ok = [r.time_s for r in runs if r.status == "solved"]
    lines.append(f"| **all** | {len(ok)}/{len(runs)} ({100 * len(ok) / max(len(runs), 1):.0f}%) | "
                 f"{statistics.median(ok) if ok else float('nan'):.2f} | {max(ok) if ok else float('nan'):.2f} | | |")
    return lines
