"""Keeping the k smallest values of a scan, in compiled code: the one insertion step the nearest-neighbour
kernels share (:func:`lazyground.planning.linear_kernels.nearest_k`, :func:`lazyground.planning.car_kernels.nearest`).

It is inlined into its callers, so its text is one of the kernel files whose hash names numba's cache folder
(:data:`lazyground.user_cache.KERNEL_SOURCES`): a change here recompiles them.
"""

from __future__ import annotations

from numba import njit

from lazyground.user_cache import use_kernel_cache

use_kernel_cache()  # before any kernel is defined: caches keyed by every kernel file's text


@njit(inline="always", cache=True)
def keep_smallest(vals, idx, m, k, g, i):
    """Offer value ``g`` of index ``i`` to the ``m`` kept (``vals[:m]`` ascending, ``idx`` their indices, at most
    ``k``): inserted in order, equal values after those kept first (lower index first in a scan). Returns the new count."""
    if m == k and not g < vals[m - 1]:
        return m
    p = m if m < k else k - 1
    while p > 0 and g < vals[p - 1]:
        vals[p] = vals[p - 1]
        idx[p] = idx[p - 1]
        p -= 1
    vals[p] = g
    idx[p] = i
    return m + 1 if m < k else m
