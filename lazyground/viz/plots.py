"""Top-down parking figures in the style of the paper's Fig. 6 (PNG and animated GIF).

Obstacles red, free spots green, parked cars in occupied spots, goal samples
as arrows coloured by their final reward-penalty weight, the tree dark blue
(goal-biased nodes blue, origins of failed goal-biased extensions red), the
path light blue and the car's footprint along it.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only; never open a window
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from PIL import Image  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402
from matplotlib.patches import Circle, Polygon, Rectangle  # noqa: E402

from lazyground.scene.types import occupant_geometry  # noqa: E402
from lazyground.viz.legend import HANDLER_MAP, LABEL_STYLE, LIMITS_STYLE, OCCUPIED_LABEL_STYLE, parking_handles  # noqa: E402
from lazyground.viz.style import (  # noqa: E402
    CAR_FOOTPRINT,
    CAR_RGBA,
    FAILED_RGBA,
    GOAL_BIASED_RGBA,
    OBSTACLE_RGBA,
    PATH_DARK_RGBA,
    PATH_RGBA,
    REGION_RGBA,
    REVERSE_RGBA,
    TREE_RGBA,
    weight_rgba,
)
from lazyground.viz.trace import frames_in_time, planar_indices, rect_corners, resample_path, tree_edges  # noqa: E402

WEIGHT_CMAP = ListedColormap([weight_rgba(w) for w in np.linspace(0, 1, 256)], name="goal_weight")
GROW_FRAMES, DRIVE_FRAMES, HOLD_FRAMES = 24, 40, 8


def plot_parking(report, scene, path) -> None:
    """Write a top-down PNG of the lot, goal samples, tree and path.

    Raises:
        SceneError: the robot is not planar.
    """
    view = _View(report, scene)
    fig, ax = view.figure()
    view.draw_tree(ax)
    view.draw_samples(ax)
    view.draw_path(ax, footprints=8)
    view.finish(fig, ax)
    fig.savefig(path)
    plt.close(fig)


def animate_parking(report, scene, path, fps: int = 12) -> None:
    """Write a top-down GIF: the tree grows, then the car drives along the path, at the real speed of
    its timed trajectory when it has one (else in ``DRIVE_FRAMES`` frames).

    The scene is rendered once; each frame redraws only the tree, the trail and
    the car over it (blitting), which keeps a 70-frame GIF to about a second.

    Raises:
        SceneError: the robot is not planar.
    """
    view = _View(report, scene)
    fig, ax = view.figure(size=(7.2, 5.0), dpi=72)
    view.draw_samples(ax)
    view.draw_arrows(ax)  # the whole route's direction of travel, under the moving car
    view.draw_raw_path(ax)
    tree = LineCollection([], colors=[TREE_RGBA], linewidths=0.6, zorder=3, animated=True)
    ax.add_collection(tree)
    trail, = ax.plot([], [], color=PATH_RGBA, lw=2.5, zorder=6, animated=True)
    car = Polygon(view.footprint(view.start), closed=True, fc=CAR_RGBA, ec="black", lw=1.0, zorder=8, animated=True)
    ax.add_patch(car)
    view.finish(fig, ax, outlines=False)
    labels = list(ax.texts)  # spot labels: redrawn over the moving car, never under it
    for label in labels:
        label.set_animated(True)
    fig.canvas.draw()
    background = fig.canvas.copy_from_bbox(fig.bbox)
    segments = view.tree_segments()
    # GIFs time frames in centiseconds (browsers slow delays under 2 cs down): the nearest at least 2 cs
    frame_ms = 10 * max(2, round(100 / fps))
    if view.trajectory is not None:  # the GIF's clock is the trajectory's: one frame every frame_ms
        drive = frames_in_time(view.trajectory, 1000.0 / frame_ms)
    elif view.path is not None:
        drive = view.resampled(DRIVE_FRAMES)
    else:
        drive = np.repeat(view.start[None], DRIVE_FRAMES, 0)
    grow = GROW_FRAMES if len(segments) else 0
    frames = []
    for frame in range(grow + len(drive) + HOLD_FRAMES):
        if frame < grow:
            tree.set_segments(segments[: int(len(segments) * (frame + 1) / grow)])
        else:
            k = min(frame - grow, len(drive) - 1)
            xy = drive[: k + 1][:, list(view.ix[:2])]
            trail.set_data(xy[:, 0], xy[:, 1])
            car.set_xy(view.footprint(drive[k]))
        fig.canvas.restore_region(background)
        for artist in (tree, trail, car, *labels):
            ax.draw_artist(artist)
        frames.append(Image.fromarray(np.asarray(fig.canvas.buffer_rgba())[..., :3].copy()))
    plt.close(fig)
    palette = frames[-1].quantize(colors=128)  # one shared palette keeps the GIF small and steady
    frames = [f.quantize(palette=palette, dither=Image.Dither.NONE) for f in frames]
    frames[0].save(str(path), save_all=True, append_images=frames[1:], duration=frame_ms, loop=0, optimize=True)


class _View:
    """One report on one planar scene, in the plane's coordinates."""

    def __init__(self, report, scene):
        self.report, self.scene, self.res = report, scene, report.result
        self.ix = planar_indices(report.joint_names)
        self.path = self.res.path
        motion = getattr(report, "motion", None)
        self.trajectory = motion.trajectory if motion is not None else None
        self.raw_path = motion.raw_path if motion is not None and not np.array_equal(motion.raw_path, self.path) else None
        q0 = self.path[0] if self.path is not None else self.res.tree[0][0] if self.res.tree is not None else None
        self.start = np.asarray(q0, float) if q0 is not None else _start_from_scene(scene, report.joint_names)
        names = [report.joint_names[i] for i in self.ix[:2]]
        self.limits = np.array([scene.robot.limits[n] for n in names]).T if all(n in scene.robot.limits for n in names) else None

    # --- pieces --------------------------------------------------------------------------
    def xyh(self, q) -> tuple[float, float, float]:
        return float(q[self.ix[0]]), float(q[self.ix[1]]), float(q[self.ix[2]])

    def footprint(self, q) -> np.ndarray:
        return rect_corners(*self.xyh(q), *CAR_FOOTPRINT)

    def resampled(self, n: int) -> np.ndarray:
        wrap = np.zeros(self.path.shape[1], bool)
        wrap[self.ix[2]] = True
        return resample_path(self.path, n, wrap)

    def tree_segments(self) -> np.ndarray:
        if self.res.tree is None:
            return np.zeros((0, 2, 2))
        nodes, parents, _ = self.res.tree
        child, parent = tree_edges(parents)
        xy = nodes[:, list(self.ix[:2])]
        return np.stack([xy[parent], xy[child]], axis=1)

    # --- drawing -------------------------------------------------------------------------
    def figure(self, size=(9.0, 6.4), dpi=110):
        fig, ax = plt.subplots(figsize=size, dpi=dpi)
        ax.set_facecolor((0.93, 0.93, 0.93))
        if self.limits is not None:  # where the car's reference point may go (issue 34: not drawn, so a car outside went unseen)
            (x0, y0), (x1, y1) = self.limits
            ax.add_patch(Rectangle((x0, y0), x1 - x0, y1 - y0, zorder=1.5, **LIMITS_STYLE))
        for obs in self.scene.obstacles:
            ax.add_patch(_shape_patch(obs.geometry, obs.pose, fc=OBSTACLE_RGBA, ec="none", zorder=2))
        for obj in self.scene.objects:
            if obj.type != "parking_spot":
                ax.add_patch(_shape_patch(obj.geometry, obj.pose, fc=(0.55, 0.55, 0.55, 1), ec="none", zorder=2))
                continue
            x, y, _ = obj.pose.xyz
            yaw = obj.pose.rpy[2]
            lx, ly = obj.geometry.box[:2] if obj.geometry.box else (5.0, 2.5)
            spot = rect_corners(x, y, yaw, lx, ly)
            if obj.occupied:
                ax.add_patch(Polygon(spot, closed=True, fc="none", ec=(0.5, 0.5, 0.5), lw=0.8, zorder=1))
                occupant = occupant_geometry(obj, self.scene)
                if occupant is not None:  # the footprint of what stands in the spot (a parked car)
                    hx, hy, _ = occupant.half_extents()
                    ax.add_patch(Polygon(rect_corners(x, y, yaw, 2 * hx, 2 * hy), closed=True, fc=OBSTACLE_RGBA, ec="black", lw=0.5, zorder=2))
                ax.text(x, y, obj.id, **OCCUPIED_LABEL_STYLE)
            else:
                ax.add_patch(Polygon(spot, closed=True, fc=REGION_RGBA, ec=REGION_RGBA[:3], lw=1.2, zorder=1))
                ax.text(x, y, obj.id, **LABEL_STYLE)
        ax.add_patch(Polygon(self.footprint(self.start), closed=True, fc="none", ec="black", lw=1.0, ls="--", zorder=7))
        return fig, ax

    def draw_tree(self, ax) -> None:
        if self.res.tree is None:
            return
        ax.add_collection(LineCollection(self.tree_segments(), colors=[TREE_RGBA], linewidths=0.6, zorder=3))
        nodes, _, goal_biased = self.res.tree
        xy = nodes[:, list(self.ix[:2])]
        gb = np.asarray(goal_biased, bool)
        ax.scatter(xy[gb, 0], xy[gb, 1], s=9, color=GOAL_BIASED_RGBA, zorder=4, label="goal-biased extension / goal tree")
        if self.res.failed_from is not None and len(self.res.failed_from):
            f = xy[np.unique(self.res.failed_from)]
            ax.scatter(f[:, 0], f[:, 1], s=22, marker="x", color=FAILED_RGBA, zorder=4, label="failed goal-biased extension from")

    def draw_samples(self, ax) -> None:
        samples = self.res.goal_samples
        if not samples:
            return
        q = np.array([s.q for s in samples])
        w = np.array([s.weight for s in samples])
        h = q[:, self.ix[2]]
        ax.quiver(q[:, self.ix[0]], q[:, self.ix[1]], np.cos(h), np.sin(h), w, cmap=WEIGHT_CMAP, clim=(0, 1),
                  angles="xy", scale_units="xy", scale=0.6, width=0.004, zorder=9)

    def draw_arrows(self, ax, every: float = 1.5) -> None:
        """Direction of travel along the path, about every ``every`` metres: forwards in the path's
        colour, reverse in orange (a car's path changes gear at cusps)."""
        if self.path is None or len(self.path) < 2:
            return
        xy = self.path[:, list(self.ix[:2])]
        d = np.diff(xy, axis=0)
        step = np.hypot(d[:, 0], d[:, 1])
        s = np.concatenate([[0.0], np.cumsum(step)])
        picks = [k for k in np.unique(np.searchsorted(s, np.arange(every / 2, s[-1], every))) if 0 < k <= len(d) and step[k - 1] > 0]
        if not picks:
            return
        k = np.array(picks) - 1
        h = self.path[k, self.ix[2]]
        reverse = d[k, 0] * np.cos(h) + d[k, 1] * np.sin(h) < 0
        u = d[k] / step[k, None]
        for mask, color, label in ((~reverse, PATH_DARK_RGBA, "forwards"), (reverse, REVERSE_RGBA, "reverse")):
            if mask.any():
                ax.quiver(xy[k[mask], 0], xy[k[mask], 1], u[mask, 0], u[mask, 1], color=color, angles="xy",
                          scale_units="xy", scale=1.4, width=0.004, headwidth=4, zorder=7, label=label)

    def draw_path(self, ax, footprints: int) -> None:
        if self.path is None:
            return
        self.draw_raw_path(ax)
        ax.plot(self.path[:, self.ix[0]], self.path[:, self.ix[1]], color=PATH_RGBA, lw=2.5, zorder=6, label="path")
        self.draw_arrows(ax)
        for q in self.resampled(footprints)[1:-1]:
            ax.add_patch(Polygon(self.footprint(q), closed=True, fc="none", ec=PATH_RGBA, lw=0.8, zorder=6))
        ax.add_patch(Polygon(self.footprint(self.path[-1]), closed=True, fc=CAR_RGBA, ec="black", lw=1.0, zorder=8))

    def draw_raw_path(self, ax) -> None:
        """The planner's raw path, faint and dashed beside the shortened one."""
        if self.raw_path is not None:
            ax.plot(self.raw_path[:, self.ix[0]], self.raw_path[:, self.ix[1]], color=PATH_RGBA, alpha=0.35, lw=1.5,
                    ls="--", zorder=5, label="raw path")

    def finish(self, fig, ax, outlines: bool = True) -> None:
        lo, hi = _extent(self.scene)
        car = np.concatenate([self.footprint(self.start)] + ([self.path[:, list(self.ix[:2])]] if self.path is not None else []))
        lo, hi = np.minimum(lo, car.min(axis=0)), np.maximum(hi, car.max(axis=0))  # the start may lie outside the geometry
        if self.limits is not None:
            lo, hi = np.minimum(lo, self.limits[0]), np.maximum(hi, self.limits[1])
        ax.set_xlim(lo[0] - 1, hi[0] + 1)
        ax.set_ylim(lo[1] - 1, hi[1] + 1)
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        res = self.res
        where = f"reached {self.report.chosen_object} ({res.goal_region.label})" if res.solved else res.status.value
        ax.set_title(f"{self.report.request!r} on {self.report.scene}: {where}; tree {res.tree_size}, "
                     f"{len(res.goal_samples)} goal samples", fontsize=9)
        sm = plt.cm.ScalarMappable(cmap=WEIGHT_CMAP, norm=plt.Normalize(0, 1))
        fig.colorbar(sm, ax=ax, fraction=0.03, pad=0.02).set_label("goal-sample weight", fontsize=8)
        handles = parking_handles(res.tree is not None, res.failed_from is not None and len(res.failed_from) > 0,
                                  self.path is not None, any(o.occupied for o in self.scene.objects), outlines,
                                  self.limits is not None)
        # at the figure's foot, the axes laid out above it: never over the lot nor the axis label (issue 34: a fixed
        # offset under the axes overlapped "x (m)" in the GIF's smaller figure)
        legend = fig.legend(handles=handles, handler_map=HANDLER_MAP, loc="lower center", ncol=3, fontsize=6,
                            frameon=False)
        fig.canvas.draw()
        fig.tight_layout(rect=(0, legend.get_window_extent().height / fig.bbox.height + 0.01, 1, 1))


def _shape_patch(geometry, pose, **style):
    x, y, _ = pose.xyz
    if geometry.box:
        return Polygon(rect_corners(x, y, pose.rpy[2], geometry.box[0], geometry.box[1]), closed=True, **style)
    return Circle((x, y), geometry.half_extents()[0], **style)


def _extent(scene) -> tuple[np.ndarray, np.ndarray]:
    """The (x, y) bounding box of every obstacle and object."""
    pts = [np.zeros((0, 2))]
    for item in list(scene.obstacles) + list(scene.objects):
        x, y, _ = item.pose.xyz
        hx, hy, _ = item.geometry.half_extents()
        pts.append(rect_corners(x, y, item.pose.rpy[2], 2 * hx, 2 * hy))
    pts = np.concatenate(pts)
    if not len(pts):
        return np.zeros(2), np.ones(2)
    return pts.min(axis=0), pts.max(axis=0)


def _start_from_scene(scene, joint_names) -> np.ndarray:
    return np.array([scene.robot.start.get(n, 0.0) for n in joint_names], float)
