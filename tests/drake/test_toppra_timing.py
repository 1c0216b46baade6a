"""Drake's Toppra as the timing uses it: its s(t) evaluated as arrays, and the grid it is given (#31)."""

import numpy as np
import pytest

pytest.importorskip("pydrake")

from lazyground.motion.curve import blended_curve  # noqa: E402
from lazyground.motion.limits import Limits  # noqa: E402
from lazyground.motion.trajectory import _drake_bspline, _point_plant, _Quadratics, _toppra_grid  # noqa: E402


def _solved(seed):
    from pydrake.multibody.optimization import Toppra

    rng = np.random.default_rng(seed)
    path = np.cumsum(rng.uniform(-1.0, 1.0, (5, 3)), axis=0)
    curve = blended_curve(path, 0.2)
    limits = Limits(rng.uniform(0.5, 2.0, 3), rng.uniform(0.5, 3.0, 3))
    path = _drake_bspline(curve)  # Toppra keeps a reference to it, not the object: it must outlive the solve
    toppra = Toppra(path, _point_plant(3), _toppra_grid(curve, (4, 2)))
    toppra.AddJointVelocityLimit(-limits.velocity, limits.velocity)
    toppra.AddJointAccelerationLimit(-limits.acceleration, limits.acceleration)
    s_of_t = toppra.SolvePathParameterization()
    assert s_of_t is not None
    return s_of_t


@pytest.mark.parametrize("seed", range(4))
def test_the_arrays_give_drakes_s_and_its_derivatives(seed):
    s_of_t = _solved(seed)
    fast = _Quadratics.of(s_of_t)
    t = np.concatenate([np.linspace(0.0, s_of_t.end_time(), 500), fast.breaks])
    s, sd, sdd = fast(t)
    scale = max(1.0, float(np.max(np.abs(s_of_t.derivative(2).vector_values(t)))))
    assert np.allclose(s, s_of_t.vector_values(t)[0], rtol=0, atol=1e-9)
    assert np.allclose(sd, s_of_t.derivative(1).vector_values(t)[0], rtol=0, atol=1e-9 * scale)
    # s'' jumps at the breaks (constant on each piece): compared away from them
    inner = np.linspace(0.0, s_of_t.end_time(), 500)
    inner = inner[np.min(np.abs(inner[:, None] - fast.breaks[None, :]), axis=1) > 1e-9]
    assert np.allclose(fast(inner)[2], s_of_t.derivative(2).vector_values(inner)[0], rtol=0, atol=1e-9 * scale)
    assert fast.end_time == s_of_t.end_time()


def test_a_blended_paths_curve_runs_straight_in_the_middle_of_every_segment():
    curve = blended_curve(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 2.0], [3.0, 2.5]]), 0.2)
    straight = curve.straight_spans
    assert len(straight) == len(curve.breaks) - 1 == 7
    assert straight.tolist() == [True, False, False, True, False, False, True]
    grid = _toppra_grid(curve, (4, 2))  # 3 straight spans of 3 intervals, 4 bending ones of 1
    assert len(grid) == 3 * 3 + 4 + 1 and np.all(np.diff(grid) > 0) and grid[0] == 0.0 and grid[-1] == 1.0
    assert len(_toppra_grid(curve, (4, 4))) == 7 * 3 + 1
