"""Shapes as solids with a cheap signed distance, and sphere covers that enclose them (for lazyground.drake.spheres).

A *solid* is a box with half extents ``half``, rounded by ``rounding`` (every point
within ``rounding`` of the box), or a cylinder (``half`` = (r, r, h)). That is
exact for Drake's Box, Cylinder, Sphere (a point box, rounded), Capsule (a segment
box, rounded) and HalfSpace (a box ``FAR`` deep, exact within ``FAR`` of its origin);
Mesh, Convex and Ellipsoid get the box around them (for a mesh, around its convex
hull, the shape SceneGraph's distance queries use). A solid's distance is thus
exact or a lower bound of its shape's.

A *cover* is a set of spheres whose union encloses a shape, so a sphere's
distance to anything is a lower bound of the shape's.
"""

from __future__ import annotations

import numpy as np
from pydrake.geometry import Box, Capsule, Convex, Cylinder, Ellipsoid, HalfSpace, Mesh, Sphere

FAR = 1e6  # metres: a half-space as a box this deep
MAX_SPHERES = 96  # per cover; a large box gets a coarser cover (more slack) rather than more spheres


def solid(shape) -> tuple[np.ndarray, np.ndarray, float, bool]:
    """(centre, half extents, rounding, cylinder) of the solid of ``shape``, in the shape's frame.

    Raises:
        ValueError: a shape with no solid here, or a mesh Drake cannot read.
    """
    zero = np.zeros(3)
    if isinstance(shape, Box):
        return zero, np.asarray(shape.size(), float) / 2, 0.0, False
    if isinstance(shape, Sphere):
        return zero, zero, shape.radius(), False
    if isinstance(shape, Capsule):
        return zero, np.array([0.0, 0.0, shape.length() / 2]), shape.radius(), False
    if isinstance(shape, Cylinder):
        return zero, np.array([shape.radius(), shape.radius(), shape.length() / 2]), 0.0, True
    if isinstance(shape, Ellipsoid):
        return zero, np.array([shape.a(), shape.b(), shape.c()]), 0.0, False
    if isinstance(shape, HalfSpace):  # z <= 0 in its frame
        return np.array([0.0, 0.0, -FAR]), np.full(3, FAR), 0.0, False
    if isinstance(shape, (Mesh, Convex)):
        try:
            hull = shape.GetConvexHull()
            v = np.array([hull.vertex(i) for i in range(hull.num_vertices())])
        except Exception as e:  # noqa: BLE001  (Drake raises RuntimeError or others for an unreadable file)
            raise ValueError(f"mesh {shape.source()}: {e}") from None
        lo, hi = v.min(axis=0), v.max(axis=0)
        return (lo + hi) / 2, (hi - lo) / 2, 0.0, False
    raise ValueError(f"no solid for a {type(shape).__name__}")


def solid_radius(half: np.ndarray, rounding: float, cylinder: bool) -> float:
    """The radius of the sphere about a solid's centre that encloses it."""
    return float(np.hypot(half[0], half[2]) if cylinder else np.linalg.norm(half)) + rounding


def solid_distance(x: np.ndarray, half: np.ndarray, rounding: np.ndarray, cylinder: np.ndarray) -> np.ndarray:
    """Signed distance from points ``x`` (..., 3), given in their solids' centred frames, to the solids."""
    d0, d1, d2 = (np.abs(x[..., k]) - half[..., k] for k in range(3))
    if np.any(cylinder):  # radial and axial distance only
        d0 = np.where(cylinder, np.hypot(x[..., 0], x[..., 1]) - half[..., 0], d0)
        d1 = np.where(cylinder, -np.inf, d1)
    outside = np.sqrt(np.maximum(d0, 0.0) ** 2 + np.maximum(d1, 0.0) ** 2 + np.maximum(d2, 0.0) ** 2)
    return outside + np.minimum(np.maximum(np.maximum(d0, d1), d2), 0.0) - rounding


def cover(shape, slack: float) -> tuple[np.ndarray, np.ndarray]:
    """Spheres (centres in the shape's frame, radii) whose union encloses ``shape``, reaching about ``slack`` beyond it.

    Box (and the box of a mesh, convex or ellipsoid): a grid of sub-boxes, each inside
    the sphere through its corners. Cylinder and capsule: slices along the axis, each
    inside the sphere through its rims; a capsule's ends as their own spheres. Sphere: itself.

    Raises:
        ValueError: a shape that cannot be enclosed (a half-space, an unreadable mesh).
    """
    if isinstance(shape, HalfSpace):
        raise ValueError("a half-space cannot be enclosed by spheres")
    center, half, rounding, cylinder = solid(shape)
    if isinstance(shape, Sphere):
        c, r = np.zeros((1, 3)), np.array([rounding])
    elif isinstance(shape, (Cylinder, Capsule)):
        c, r = _axis_cover(half[0] if cylinder else rounding, half[2], slack, capsule=not cylinder)
    else:
        c, r = _box_cover(half, slack)
    return c + center, r


def _axis_cover(radius: float, half_length: float, slack: float, capsule: bool) -> tuple[np.ndarray, np.ndarray]:
    """Slices of a cylinder along z, each inside the sphere through its rims (a capsule: plus its two end spheres)."""
    step = np.sqrt(2 * radius * slack + slack * slack)  # the half-slice whose sphere reaches ``slack`` beyond the side
    n = min(max(1, int(np.ceil(half_length / step - 1e-9))), MAX_SPHERES - 2)
    h = half_length / n
    z = -half_length + h * (2 * np.arange(n) + 1)
    c, r = np.column_stack([np.zeros(n), np.zeros(n), z]), np.full(n, np.hypot(radius, h))
    if capsule:
        c = np.vstack([c, [[0.0, 0.0, -half_length], [0.0, 0.0, half_length]]])
        r = np.append(r, [radius, radius])
    return c, r


def _box_cover(half: np.ndarray, slack: float) -> tuple[np.ndarray, np.ndarray]:
    """A grid of sub-boxes of a box, the longest sub-box side split until a corner sphere
    reaches at most ``slack`` beyond the thinnest side (or MAX_SPHERES would be exceeded)."""
    n = np.ones(3, int)
    while np.linalg.norm(half / n) - (half / n).min() > slack:
        grow = n.copy()
        grow[np.argmax(half / n)] += 1
        if grow.prod() > MAX_SPHERES:
            break
        n = grow
    h = half / n
    axes = [-half[i] + h[i] * (2 * np.arange(n[i]) + 1) for i in range(3)]
    return np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3), np.full(int(n.prod()), np.linalg.norm(h))


MAX_INNER = 27  # inner spheres per shape


def exact(shape) -> bool:
    """Whether the solid of ``shape`` is the shape itself (within FAR for a half-space), not a box around it."""
    return isinstance(shape, (Box, Sphere, Capsule, Cylinder, HalfSpace))


def inner(shape) -> tuple[np.ndarray, np.ndarray]:
    """Spheres (centres in the shape's frame, radii) inside ``shape``: a point of one within its radius of
    its centre is a point of the shape (#31: a sphere reaching into an obstacle proves a collision).
    None for shapes whose solid is not exact (a mesh, convex, ellipsoid) or that are not bounded."""
    if isinstance(shape, Sphere):
        return np.zeros((1, 3)), np.array([shape.radius()])
    if isinstance(shape, Capsule):
        return _line(shape.radius(), shape.length() / 2 + shape.radius())
    if isinstance(shape, Cylinder):
        return _line(min(shape.radius(), shape.length() / 2), shape.length() / 2)
    if isinstance(shape, Box):
        half = np.asarray(shape.size(), float) / 2
        r = half.min()
        axes = [np.linspace(-(h - r), h - r, min(1 + int(np.ceil((h - r) / r - 1e-9)), 3)) if r > 0 else np.zeros(1)
                for h in half]
        c = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
        return c, np.full(len(c), r)
    return np.zeros((0, 3)), np.zeros(0)


def _line(r: float, half_length: float) -> tuple[np.ndarray, np.ndarray]:
    """Spheres of radius r inside a body of revolution about z reaching ``half_length`` along it (r <= its radius)."""
    reach = max(half_length - r, 0.0)
    n = min(1 + int(np.ceil(reach / r - 1e-9)) if r > 0 else 1, MAX_INNER)
    z = np.linspace(-reach, reach, n)
    return np.column_stack([np.zeros(n), np.zeros(n), z]), np.full(n, r)
