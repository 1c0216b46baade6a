"""The kernels' distance bound between two solids (#31: lazyground.drake.sphere_kernels._gjk): a pair it calls
farther than a threshold is, on cases with a known distance and on random solids against a sampled distance."""

import numpy as np
import pytest

pytest.importorskip("numba")

from lazyground.drake.solids import solid_distance  # noqa: E402
from lazyground.drake.sphere_kernels import _gjk  # noqa: E402


def rotation(rng):
    q = rng.normal(size=4)
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


@pytest.mark.parametrize("gap", [0.004, 0.02, 0.3])
@pytest.mark.parametrize("tilt", [0.0, 1e-9, 0.3])
def test_cylinder_cap_facing_a_box(gap, tilt):
    """A cylinder's axis along the direction to a box (its cap faces the box): the distance is the gap; the
    direction along the axis once gave a support point off the cylinder and a lower bound above the distance."""
    c, s = np.cos(tilt), np.sin(tilt)
    R = np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])  # cylinder axis (z) tilted about x
    half_cyl = np.array([0.045, 0.045, 0.045])
    top = 0.045 * c + 0.045 * s  # highest point of the tilted cylinder above its centre
    box_half = np.array([0.035, 0.035, 0.075])
    cb = np.array([0.0, 0.0, top + gap + 0.075])
    args = (R, np.zeros(3), half_cyl, 0.0, True, np.eye(3), cb, box_half, 0.0, False)
    assert _gjk(*args, gap - 1e-4)
    assert not _gjk(*args, gap + 1e-4)


def _solid(rng):
    kind = rng.integers(3)
    R, c = rotation(rng), rng.uniform(-0.3, 0.3, 3)
    if kind == 0:
        return R, c, rng.uniform(0.01, 0.2, 3), 0.0, False
    if kind == 1:
        r = rng.uniform(0.01, 0.1)
        return R, c, np.array([r, r, rng.uniform(0.01, 0.2)]), 0.0, True
    return R, c, np.array([0.0, 0.0, rng.uniform(0.0, 0.2)]), rng.uniform(0.01, 0.1), False


def _points(solid, rng, n=4000):
    """Points of the solid (so their least distance to another solid is at least the two solids' distance)."""
    R, c, half, rounding, cylinder = solid
    if cylinder:
        angle, radius = rng.uniform(0, 2 * np.pi, n), half[0] * np.sqrt(rng.uniform(0, 1, n))
        x = np.stack([radius * np.cos(angle), radius * np.sin(angle), rng.uniform(-half[2], half[2], n)], 1)
    else:
        x = rng.uniform(-1, 1, (n, 3)) * half
        d = rng.normal(size=(n, 3))
        x += d / np.linalg.norm(d, axis=1)[:, None] * rounding * rng.uniform(0, 1, (n, 1)) ** (1 / 3)
    return x @ R.T + c


def test_random_solids_never_called_farther_than_they_are():
    rng = np.random.default_rng(3)
    apart = proven = 0
    for _ in range(300):
        a, b = _solid(rng), _solid(rng)
        x = (_points(a, rng) - b[1]) @ b[0]
        above = solid_distance(x, np.broadcast_to(b[2], x.shape), np.full(len(x), b[3]), np.full(len(x), b[4])).min()
        threshold = rng.uniform(0.0, 0.05)
        farther = _gjk(*a, *b, threshold)
        assert not (farther and above <= threshold)  # called farther, but two of their points are this close
        apart += above > threshold + 0.005
        proven += farther and above > threshold + 0.005
    assert apart >= 200 and proven >= 0.95 * apart  # it proves nearly every pair apart (the fallback is rare)
