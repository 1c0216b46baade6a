"""#20: the parking PNG's legend names every kind of mark, sits outside the lot, and no spot label hides under the car."""

from __future__ import annotations

import matplotlib.figure

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
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    for want in ("start (car outline)", "obstacle", "free spot (goal region)", "parked car (occupied spot)",
                 "goal sample: heading, colour = weight", "search tree", "path", "car outline along the path", "car at the goal"):
        assert want in labels, labels
    fig.canvas.draw()
    legend, axes = ax.get_legend().get_window_extent(), ax.get_window_extent()
    assert legend.y1 <= axes.y0  # below the plot: it covers nothing


def test_spot_labels_are_drawn_above_the_car(parking, tmp_path, monkeypatch):
    fig, report = _figure(parking, tmp_path, monkeypatch)
    ax = fig.axes[0]
    spot = report.chosen_object
    label = next(t for t in ax.texts if t.get_text() == spot)
    car_z = max(p.get_zorder() for p in ax.patches if tuple(p.get_facecolor()) == (1.0, 1.0, 1.0, 1.0))
    assert label.get_zorder() > car_z
