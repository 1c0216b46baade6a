"""Generated planar serial arms of any DOF in a cluttered scene, for the DOF sweep.

The arm is a chain of ``dof`` revolute joints about the vertical axis (a
planar arm at 0.5 m height) with box links whose total length is ``REACH``, so
every arm covers the same workspace and only the dimension changes. The scene
is a ring of vertical posts around the arm (seeded, the same for every DOF).
Goal regions are C-space boxes (no IK cost): ``GOALS`` of them, centred on
seeded smooth arm shapes that are the same curves at every DOF (a DOF only
changes how finely a shape is jointed, so the sweep compares dimensions, not
layouts); a region whose centre is in collision is labelled "blocked" (its
samples are nearly all invalid), the others "free". Which free
regions the planner can actually reach is left to the planner to find out,
as in the paper's scenes.

URDFs are written at run time into a temporary folder; nothing is committed.
"""

from __future__ import annotations

import math
import os
import tempfile
from pathlib import Path

import numpy as np

from lazyground.regions import ConfigRegion
from lazyground.scene.schema import Cylinder, Geometry, Obstacle, PlannerSpec, PoseSpec, RobotSpec, Scene

DOFS = (8, 12, 16, 24, 32)
REACH = 1.2  # metres, total length of the chain
HEIGHT = 0.5  # the plane of the arm
BASE_LIMIT = 0.95 * math.pi  # the first joint turns almost all the way round
TOTAL_BEND = 12.0  # radians: the other joints get +-min(1.5, TOTAL_BEND / dof), so the arm curls alike at every DOF
POSTS = 10
POST_RADIUS = 0.05
GOALS = 6
GOAL_HALF_WIDTH = 0.05  # radians, per joint
SCENE_SEED = 7  # the posts
GOAL_SEED = 8  # the goal shapes: the first seed whose centres are free or blocked alike at every DOF, a third blocked
STEP_SIZE = 1.0  # radians, Euclidean over all joints
EDGE_RESOLUTION = 0.05


def arm_urdf(dof: int) -> str:
    """URDF text of a ``dof``-joint planar arm with box links."""
    if dof < 1:
        raise ValueError("an arm needs at least one joint")
    length = REACH / dof
    thick = min(0.03, 0.4 * length)  # thin links on long chains, so non-adjacent links do not touch when bent
    box = f"{0.85 * length:.5f} {thick:.5f} {thick:.5f}"
    parts = [f'<?xml version="1.0"?>\n<robot name="arm_{dof}">', _link("base_link", "0.02 0.02 0.02", 0.0)]
    for i in range(1, dof + 1):
        parts.append(_link(f"link_{i}", box, length / 2))
        parent = "base_link" if i == 1 else f"link_{i - 1}"
        x = 0.0 if i == 1 else length
        limit = BASE_LIMIT if i == 1 else joint_limit(dof)
        parts.append(
            f'  <joint name="joint_{i}" type="revolute">\n'
            f'    <parent link="{parent}"/><child link="link_{i}"/>\n'
            f'    <origin xyz="{x:.5f} 0 0"/><axis xyz="0 0 1"/>\n'
            f'    <limit lower="{-limit:.5f}" upper="{limit:.5f}" effort="10" velocity="1"/>\n'
            f"  </joint>"
        )
    parts.append("</robot>\n")
    return "\n".join(parts)


def joint_limit(dof: int) -> float:
    """The limit of every joint but the first."""
    return min(1.5, TOTAL_BEND / dof)


def _link(name: str, box: str, x: float) -> str:
    return (
        f'  <link name="{name}">\n'
        f'    <inertial><origin xyz="{x:.5f} 0 0"/><mass value="0.1"/>'
        f'<inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>\n'
        f'    <collision><origin xyz="{x:.5f} 0 0"/><geometry><box size="{box}"/></geometry></collision>\n'
        f'    <visual><origin xyz="{x:.5f} 0 0"/><geometry><box size="{box}"/></geometry></visual>\n'
        f"  </link>"
    )


def write_arm_urdf(dof: int, folder: str | os.PathLike | None = None) -> Path:
    """Write the arm's URDF (atomically: workers may race) and return its path."""
    folder = Path(folder) if folder is not None else Path(tempfile.gettempdir()) / "lazyground_arms"
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"arm_{dof}.urdf"
    text = arm_urdf(dof)
    if not path.is_file() or path.read_text() != text:
        tmp = folder / f".arm_{dof}.{os.getpid()}.tmp"
        tmp.write_text(text)
        os.replace(tmp, path)
    return path


def post_positions(seed: int = SCENE_SEED) -> list[tuple[float, float]]:
    """Seeded posts in an annulus around the arm, clear of the stretched-out start pose."""
    rng = np.random.default_rng(seed)
    out: list[tuple[float, float]] = []
    while len(out) < POSTS:
        r = rng.uniform(0.55, REACH + 0.1)
        a = rng.uniform(-math.pi, math.pi)
        x, y = r * math.cos(a), r * math.sin(a)
        if x > 0 and abs(y) < 0.15:  # keep the start (all joints zero: arm along +x) free
            continue
        if all(math.hypot(x - u, y - v) > 0.25 for u, v in out):
            out.append((x, y))
    return out


def arm_scene(dof: int, folder=None, time_limit: float = 10.0) -> Scene:
    """The cluttered scene for the ``dof``-joint arm (built in code, not loaded from YAML)."""
    urdf = write_arm_urdf(dof, folder)
    obstacles = tuple(
        Obstacle(id=f"post_{k}", geometry=Geometry(cylinder=Cylinder(radius=POST_RADIUS, length=1.0)), pose=PoseSpec(xyz=(x, y, HEIGHT)))
        for k, (x, y) in enumerate(post_positions())
    )
    robot = RobotSpec(model=str(urdf), start={}, base=PoseSpec(xyz=(0.0, 0.0, HEIGHT)), base_link="base_link")
    planner = PlannerSpec(step_size=STEP_SIZE, time_limit=time_limit)
    return Scene(name=f"arm_{dof}", robot=robot, description=f"{dof}-DOF planar arm among {POSTS} posts", obstacles=obstacles, planner=planner, source=f"<generated arm_{dof}>")


def goal_centres(dof: int, seed: int = GOAL_SEED) -> np.ndarray:
    """Seeded smooth arm shapes, the same curves at every DOF: a base angle and a seeded curvature profile
    along the chain; each joint bends by the curvature integrated over the half links beside it, so ``dof``
    only changes how finely one shape is jointed (and the sweep compares dimensions, not layouts)."""
    rng = np.random.default_rng(seed)
    base = np.linspace(-0.8 * math.pi, 0.8 * math.pi, GOALS) + rng.uniform(-0.2, 0.2, GOALS)
    # curvature k(s) = a0 + a1 sin(pi s + p1) + a2 sin(2 pi s + p2) rad per chain length, s in [0, 1]; |k| <= 10.5 < TOTAL_BEND
    a = rng.uniform(-3.5, 3.5, size=(GOALS, 3))
    phase = rng.uniform(0.0, 2.0 * math.pi, size=(GOALS, 2))
    joints = np.arange(1, dof) / dof  # joints 2..dof sit at s = 1/dof ... (dof-1)/dof along the chain
    lo, hi = joints - 0.5 / dof, joints + 0.5 / dof  # each bends by the curvature of the half links beside it

    def integral(s):  # of every goal's curvature from 0 to s: one row per goal
        return (a[:, :1] * s - a[:, 1:2] * np.cos(math.pi * s + phase[:, :1]) / math.pi
                - a[:, 2:] * np.cos(2.0 * math.pi * s + phase[:, 1:]) / (2.0 * math.pi))

    q = np.empty((GOALS, dof))  # link i then points along the curve's heading at its midpoint (the midpoint rule)
    q[:, 0] = base + integral(0.5 / dof)[:, 0] - integral(0.0)[:, 0]
    q[:, 1:] = integral(hi) - integral(lo)
    return q


def tip_position(q: np.ndarray) -> np.ndarray:
    """Planar forward kinematics of a generated arm: the chain's end point (x, y) relative to its base."""
    dof = len(q)
    heading = np.cumsum(q)
    return (REACH / dof) * np.array([np.cos(heading).sum(), np.sin(heading).sum()])


def goal_regions(dof: int, config_free) -> tuple[ConfigRegion, ...]:
    """C-space box goal regions; ``config_free(q)`` labels each one free or blocked."""
    out = []
    for k, c in enumerate(goal_centres(dof)):
        label = "free" if config_free(c) else "blocked"
        lo = np.clip(c - GOAL_HALF_WIDTH, -joint_limit(dof), joint_limit(dof))
        hi = np.clip(c + GOAL_HALF_WIDTH, -joint_limit(dof), joint_limit(dof))
        lo[0], hi[0] = c[0] - GOAL_HALF_WIDTH, c[0] + GOAL_HALF_WIDTH
        out.append(ConfigRegion(
            id=f"goal_{k}/{label}", interpretation=f"reach:goal_{k}", object=f"goal_{k}",
            lower=tuple(float(v) for v in lo), upper=tuple(float(v) for v in hi), label=label,
        ))
    return tuple(out)


def arm_key(dof: int) -> str:
    """The scene key the bench runner understands for a generated arm."""
    return f"arm:{dof}"


def parse_arm_key(key: str) -> int | None:
    """The DOF of an ``arm:<dof>`` key, or None for a scene file."""
    if key.startswith("arm:") and key[4:].isdigit():
        return int(key[4:])
    return None
