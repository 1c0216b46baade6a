"""The approach-clearance test of :mod:`lazyground.drake.approach` in compiled code (issue #33): pose by pose, with
an early exit at a pose's first hit and at the first pose that backs out (the numpy form it replaced computed every
point against every nearby solid; the same arithmetic in the same order: the same flags on the racks tested)."""

from __future__ import annotations

import math

from numba import njit

from lazyground.user_cache import use_kernel_cache

use_kernel_cache()  # before any kernel is defined: caches keyed by every kernel file's text


@njit(cache=True)
def retreats(p, dw, steps, centres, axes, half, rounding, reach, keep, tol):
    """Whether for some pose k the points ``p[k]`` (k, points, 3) moved by every one of ``steps`` along ``dw[k]``
    stay ``tol`` away from every kept solid (stacked centres, axes, half extents, roundings; ``reach`` their
    bounding half extents)."""
    for k in range(p.shape[0]):
        free = True
        for s in range(steps.shape[0]):
            if not free:
                break
            sx, sy, sz = steps[s] * dw[k, 0], steps[s] * dw[k, 1], steps[s] * dw[k, 2]
            for i in range(p.shape[1]):
                if not free:
                    break
                x, y, z = p[k, i, 0] + sx, p[k, i, 1] + sy, p[k, i, 2] + sz
                for m in range(centres.shape[0]):
                    if not keep[m]:
                        continue
                    d0, d1, d2 = x - centres[m, 0], y - centres[m, 1], z - centres[m, 2]
                    if abs(d0) > reach[m, 0] + tol or abs(d1) > reach[m, 1] + tol or abs(d2) > reach[m, 2] + tol:
                        continue  # outside the solid's bounding box grown by tol: farther than tol
                    e0 = abs(d0 * axes[m, 0, 0] + d1 * axes[m, 1, 0] + d2 * axes[m, 2, 0]) - half[m, 0]
                    e1 = abs(d0 * axes[m, 0, 1] + d1 * axes[m, 1, 1] + d2 * axes[m, 2, 1]) - half[m, 1]
                    e2 = abs(d0 * axes[m, 0, 2] + d1 * axes[m, 1, 2] + d2 * axes[m, 2, 2]) - half[m, 2]
                    o0, o1, o2 = max(e0, 0.0), max(e1, 0.0), max(e2, 0.0)
                    inside = min(max(max(e0, e1), e2), 0.0)
                    if math.sqrt(o0 ** 2 + o1 ** 2 + o2 ** 2) + inside - rounding[m] < tol:
                        free = False
                        break
        if free:
            return True
    return False
