"""``lazyground demo``: plan the bundled requests and write what they look like.

"park" on the parking lot (a PNG, a GIF and an HTML replay) and, where the
Fetch scene is bundled, "pick up a can" (an HTML replay).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable
from pathlib import Path

from lazyground import api
from lazyground.bundled import data_dir
from lazyground.drake import compiled
from lazyground.report import report_lines
from lazyground.scene import load_scene

SCENES = data_dir("yaml_scenes")  # also when installed without the source tree


@dataclass(frozen=True)
class Demo:
    scene: str  # file in yaml_scenes/
    request: str
    png: str | None = None
    gif: str | None = None
    html: str | None = None


DEMOS = (
    Demo("parking_1.yaml", "park", png="parking.png", gif="parking.gif", html="parking.html"),
    Demo("fetch_cans_1.yaml", "pick up a can", html="fetch.html"),
)


def run_demo(out_dir: Path, seed: int, say: Callable[[str], None]) -> int:
    """Plan every bundled demo, write the files; 0 when every planned request is solved.

    ``say`` gets the summary line by line (the CLI prints it)."""
    from lazyground.viz import meshcat_view, plots

    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    all_solved = True
    compiled.warm_up(), compiled.warm_up_car()  # the arm's and the car's kernels, before any request's time
    if compiled.compile_report()[1]:
        say(f"compiled the planner's kernels in {compiled.compile_report()[0]:.0f} s (once per machine: numba caches them)\n")
    for demo in DEMOS:
        scene_path = SCENES / demo.scene
        if not scene_path.exists():
            say(f"skipped {demo.request!r}: {scene_path} is not bundled")
            continue
        scene = load_scene(scene_path)
        report = api.plan(scene, demo.request, seed=seed, keep_tree=True)
        all_solved &= report.result.solved
        say("\n".join(report_lines(report)))
        if demo.png:
            plots.plot_parking(report, scene, out_dir / demo.png)
            say(_wrote(out_dir / demo.png))
        if demo.gif:
            plots.animate_parking(report, scene, out_dir / demo.gif)
            say(_wrote(out_dir / demo.gif))
        if demo.html:
            meshcat_view.write_html(report, scene, out_dir / demo.html)
            say(_wrote(out_dir / demo.html))
        say("")
    say(f"output folder: {out_dir.resolve()}")
    return 0 if all_solved else 1


def _wrote(path: Path) -> str:
    return f"  wrote {path.name} ({path.stat().st_size / 1e6:.2f} MB)"
