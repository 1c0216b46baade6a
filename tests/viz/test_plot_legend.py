"""#20: the parking PNG's legend names every kind of mark, sits outside the lot, and no spot label hides under the car."""

from __future__ import annotations

import matplotlib.figure
import numpy as np

from lazyground.viz import plots


def _figure(parking, tmp_path, monkeypatch):
    scene, report = parking
    saved = []
    real = matplotlib.figure.Figure.savefig
    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", lambda fig, *a, **k: (saved.append(fig), real(fig, *a, **k)))
    monkeypatch.setattr(plots.plt, "close", lambda fig=None: None)  # keep it open to look at
    plots.plot_parking(report, scene, tmp_path / "p.png")
    return saved[0], report


def test_legend_covers_every_mark_and_stays_off_the_lot(parking, tmp_path, monkeypatch):
    fig, report = _figure(parking, tmp_path, monkeypatch)
    ax = fig.axes[0]
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    for want in ("start (car outline)", "obstacle", "free spot (goal region)", "parked car (occupied spot)",
                 "goal sample: heading, colour = weight", "search tree", "path", "car outline along the path", "car at the goal"):
        assert want in labels, labels
    fig.canvas.draw()
    legend, axes = fig.legends[0].get_window_extent(), ax.get_window_extent()
    assert legend.y1 <= axes.y0  # below the plot: it covers nothing


def test_spot_labels_are_drawn_above_the_car(parking, tmp_path, monkeypatch):
    fig, report = _figure(parking, tmp_path, monkeypatch)
    ax = fig.axes[0]
    spot = report.chosen_object
    label = next(t for t in ax.texts if t.get_text() == spot)
    car_z = max(p.get_zorder() for p in ax.patches if tuple(p.get_facecolor()) == (1.0, 1.0, 1.0, 1.0))
    assert label.get_zorder() > car_z


def test_the_legend_stays_clear_of_the_axis_labels_in_png_and_gif(parking, parking_gif, tmp_path, monkeypatch):
    # issue 34: the GIF's "x (m)" sat on the legend's first row (a fixed offset under the axes, a smaller figure)
    for fig in (_figure(parking, tmp_path, monkeypatch)[0], parking_gif[1]):
        fig.canvas.draw()
        ax = fig.axes[0]
        legend = (fig.legends[0] if fig.legends else ax.get_legend()).get_window_extent()
        for text in (ax.xaxis.label, *ax.get_xticklabels()):
            assert not legend.overlaps(text.get_window_extent()), text.get_text()
        assert legend.y1 <= ax.get_window_extent().y0


def test_the_lot_limits_are_drawn_and_every_spot_is_labelled(parking, tmp_path, monkeypatch):
    # issue 34: the PNG drew neither the lot's limits (a car outside them went unseen) nor the occupied spots' ids
    fig, report = _figure(parking, tmp_path, monkeypatch)
    scene = parking[0]
    ax = fig.axes[0]
    assert "lot limits (robot.limits)" in [t.get_text() for t in fig.legends[0].get_texts()]
    (x0, x1), (y0, y1) = scene.robot.limits["car_x"], scene.robot.limits["car_y"]
    frames = [p for p in ax.patches if p.get_fill() is False and p.get_label() != "_nolegend_"
              and np.allclose(p.get_bbox().get_points(), [[x0, y0], [x1, y1]])]
    assert len(frames) == 1
    lo, hi = ax.get_xlim(), ax.get_ylim()
    assert lo[0] < x0 and lo[1] > x1 and hi[0] < y0 and hi[1] > y1  # all of it in view
    spots = {o.id for o in scene.objects if o.type == "parking_spot"}
    assert any(o.occupied for o in scene.objects)
    assert spots <= {t.get_text() for t in ax.texts}
