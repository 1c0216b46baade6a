"""Top-down parking PNG and GIF (paper Fig. 6 style)."""

import numpy as np
import pytest
from PIL import Image

from lazyground.typed_yaml import SceneError
from lazyground.viz import plots
from lazyground.viz.style import OBSTACLE_RGBA, PATH_RGBA


def _pixels_near(img: np.ndarray, rgba, tol: int = 12) -> int:
    target = np.array(rgba[:3]) * 255
    return int((np.abs(img[..., :3].astype(int) - target).max(axis=2) <= tol).sum())


def test_png_shows_lot_and_path(parking, tmp_path):
    scene, report = parking
    out = tmp_path / "p.png"
    plots.plot_parking(report, scene, out)
    with Image.open(out) as im:
        assert im.format == "PNG"
        img = np.asarray(im.convert("RGB"))
    assert 20_000 < out.stat().st_size < 1_000_000
    assert _pixels_near(img, OBSTACLE_RGBA) > 20_000  # walls, island, parked cars
    assert _pixels_near(img, PATH_RGBA) > 500  # the path and the footprints along it


def test_gif_is_small_and_the_car_moves(parking, parking_gif):
    scene, report = parking
    out = parking_gif[0]
    assert out.stat().st_size < 3_000_000
    with Image.open(out) as im:
        assert im.format == "GIF"
        n = im.n_frames  # identical consecutive frames (the final hold) are merged
        im.seek(plots.GROW_FRAMES)
        first_drive = np.asarray(im.convert("RGB"))
        im.seek(n - 1)
        last = np.asarray(im.convert("RGB"))
    # the drive plays the timed trajectory at real speed: one frame per frame time (#16)
    frame_s = 0.08  # 12 fps asked: 8 cs per frame, what a GIF can store
    with Image.open(out) as im:
        im.seek(plots.GROW_FRAMES + 1)
        assert im.info["duration"] == 80
    drive = int(np.ceil(report.motion.trajectory.duration / frame_s)) + 1
    assert plots.GROW_FRAMES + drive - 5 <= n <= plots.GROW_FRAMES + drive + plots.HOLD_FRAMES
    moved = np.abs(first_drive.astype(int) - last.astype(int)).max(axis=2) > 30
    assert moved.sum() > 1_000  # the car left its start and the trail was drawn


def test_non_planar_robot_is_a_one_line_error(parking, tmp_path):
    scene, report = parking
    from dataclasses import replace

    arm = replace(report, joint_names=("torso_lift_joint", "shoulder_pan_joint"))
    with pytest.raises(SceneError, match="planar robot"):
        plots.plot_parking(arm, scene, tmp_path / "x.png")
