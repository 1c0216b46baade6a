"""The sphere certifier's per-configuration test, compiled with numba (#31).

One call runs the whole test for many configurations: forward kinematics of the
body tree, then every checked pair coarse to fine (the moving geometry's bounding
sphere against the other side's world box, then against its solid, then sphere by
sphere), as :class:`lazyground.drake.spheres.SphereCertifier` describes. A row is
certified when every pair clears; otherwise its open pairs are written out for
SceneGraph to measure (at most ``cap`` of them; a row with more is marked -1 and
goes to Drake's whole check).

Edges are checked configuration by configuration in a given order (bisection
order, or sequential for the free prefix), stopping at the first one not
certified: VAMP's early exit, for a one-sided test. Configurations in sequence along a densely
checked path are mostly proven from an earlier one's clearance (:func:`sweep_rows`, at the end).

The data come in two flat arrays (a float and an int one, laid out by
:func:`pack`): numba's call costs ~0.13 µs per array argument, and a certifier
has some thirty arrays. ``cache=True``: compiled once per machine into
``__pycache__`` (:func:`warm_up` reports whether that happened now).
"""

from __future__ import annotations

import numpy as np
from numba import njit
from numba.core import cgutils, types
from numba.extending import intrinsic
from numba.np.arrayobj import make_array

from lazyground.user_cache import use_kernel_cache

use_kernel_cache()  # before any kernel is defined: caches keyed by every kernel file's text

PRISMATIC_KIND = 1  # lazyground.drake.chain.PRISMATIC (checked in pack)

# int header: counts, then offsets of each float and int block
_M, _N, _G, _S, _O, _P, _I = range(7)
_FLOAT_BLOCKS = ("K", "F", "gR", "go", "ghalf", "ground", "grad", "sc", "sr", "oR", "oo", "ohalf", "oround",
                 "ac", "ah", "env", "self_thr", "ic", "ir", "below", "reach2", "glo", "ginv", "greach")
_INT_BLOCKS = ("parent", "kinds", "index", "slot", "node", "start", "gcyl", "ocyl", "mover", "other", "istart",
               "gexact", "oexact", "gdim", "gstart", "gitem", "gcell")
GRID_FROM = 64  # obstacles: fewer are tested all at once (no branches; ~25 on a bundled Fetch scene)
GRID_CELLS = 48  # cells along an axis at most
GRID_CELL = 0.2  # metres: a cell's edge (at most GRID_CELLS along an axis; a longer extent gets longer cells)
GRID_MARGIN = 1e-6  # metres: boxes and reaches are widened by this in the grid (its rounding: a superset)
COLLIDES = -2  # a row's code when a pair is proven to collide (see open_pairs_row)
_NF, _NI = len(_FLOAT_BLOCKS), len(_INT_BLOCKS)
_HEAD = 7 + _NF + _NI


def pack(blocks: dict, grid_from: int = GRID_FROM) -> tuple[np.ndarray, np.ndarray]:
    """(float data, int data) of the named blocks (see the names above) in one flat array each; with
    ``grid_from`` obstacles or more, their grid (:func:`obstacle_grid`) too."""
    blocks = {**blocks, **obstacle_grid(blocks, grid_from)}
    f_parts, i_parts, f_off, i_off = [], [], [], []
    pos = 0
    for name in _FLOAT_BLOCKS:
        a = np.ascontiguousarray(blocks[name], float).reshape(-1)
        f_off.append(pos)
        f_parts.append(a)
        pos += len(a)
    pos = 0
    for name in _INT_BLOCKS:
        a = np.ascontiguousarray(blocks[name], np.int64).reshape(-1)
        i_off.append(pos)
        i_parts.append(a)
        pos += len(a)
    counts = [blocks["counts"][k] for k in ("m", "n", "G", "S", "O", "P", "I")]
    head = np.array(counts + f_off + [_HEAD + o for o in i_off], np.int64)
    return np.concatenate(f_parts + [np.zeros(1)]), np.concatenate([head] + i_parts + [np.zeros(1, np.int64)])


# ---- the obstacles' grid (#33) -------------------------------------------------------------------------------------
# The first test of a moving geometry's pairs with the obstacles (its bounding sphere against their world boxes) ran
# over every obstacle: with hundreds (a rack of 64 cubbies) it was most of a row's time. With GRID_FROM obstacles or
# more, a uniform grid over their world boxes lists per cell the obstacles whose box meets it; a geometry's test
# visits the cells its sphere's reach meets and tests those obstacles only, each once (in the cell of the lower
# corner of its box's and the reach's overlap), then in ascending order: the same tests, answers and open pairs
# in the same order as over every obstacle.


def obstacle_grid(blocks: dict, grid_from: int = GRID_FROM) -> dict:
    """The grid's blocks: glo (its lower corner), ginv (cells per metre along each axis), greach (per moving
    geometry the farthest its bounding sphere's first test reaches, widened by GRID_MARGIN), gdim (cells along
    each axis, then 1 when the grid is used), gstart and gitem (per cell its obstacles, CSR), gcell (per obstacle
    the cell of its box's lower corner). Unused (gdim[3] == 0): fewer than ``grid_from`` obstacles."""
    G, O = blocks["counts"]["G"], blocks["counts"]["O"]
    reach2 = np.asarray(blocks["reach2"], float).reshape(G, O)
    checked = (reach2 >= 0.0).any(axis=0)  # an obstacle no geometry's pair is checked with never passes
    if O < grid_from or not checked.any():
        return dict(glo=np.zeros(3), ginv=np.zeros(3), greach=np.zeros(G), gdim=np.zeros(4, np.int64),
                    gstart=np.zeros(1, np.int64), gitem=np.zeros(0, np.int64), gcell=np.zeros(3 * O, np.int64))
    ac, ah = np.asarray(blocks["ac"], float).reshape(3, O), np.asarray(blocks["ah"], float).reshape(3, O)
    lo, hi = ac - ah - GRID_MARGIN, ac + ah + GRID_MARGIN
    glo, ghi = lo[:, checked].min(axis=1), hi[:, checked].max(axis=1)
    dim = np.clip(np.ceil((ghi - glo) / GRID_CELL), 1, GRID_CELLS).astype(np.int64)
    inv = dim / np.maximum(ghi - glo, 1e-9)
    first, last = _cells(lo, glo, inv, dim), _cells(hi, glo, inv, dim)
    cells = [[] for _ in range(int(np.prod(dim)))]
    for o in np.flatnonzero(checked):
        for i in range(first[0, o], last[0, o] + 1):
            for j in range(first[1, o], last[1, o] + 1):
                for k in range(first[2, o], last[2, o] + 1):
                    cells[(i * dim[1] + j) * dim[2] + k].append(o)
    gstart = np.cumsum([0] + [len(c) for c in cells])
    top = np.sqrt(np.maximum(reach2, 0.0).max(axis=1))
    return dict(glo=glo, ginv=inv, greach=top * (1.0 + 1e-9) + GRID_MARGIN, gdim=np.append(dim, 1),
                gstart=gstart, gitem=np.array([o for c in cells for o in c], np.int64), gcell=first.T.copy())


def _cells(x, lo, inv, dim):
    """Per axis the cell of coordinates x (3, ...): :func:`_cell`'s arithmetic."""
    return np.clip(np.floor((x - lo.reshape(3, *[1] * (x.ndim - 1))) * inv.reshape(3, *[1] * (x.ndim - 1))), 0,
                   (dim - 1).reshape(3, *[1] * (x.ndim - 1))).astype(np.int64)


@njit(cache=True, inline="always")
def _cell(x, lo, inv, n):
    """The grid cell along one axis of coordinate x (clamped to the grid: both sides alike, so still a superset)."""
    return min(max(int(np.floor((x - lo) * inv)), 0), n - 1)


@njit(cache=True, inline="always")
def box_gap2(cx, cy, cz, ac, ah, o):
    """Squared distance from point c to obstacle o's world box (centre ac[:, o], half extents ah[:, o]): the first
    test's, the grid query's and the sweep anchors' one expression (inlined: the loop over every obstacle stays
    vectorised, #33)."""
    dx = max(abs(cx - ac[0, o]) - ah[0, o], 0.0)
    dy = max(abs(cy - ac[1, o]) - ah[1, o], 0.0)
    dz = max(abs(cz - ac[2, o]) - ah[2, o], 0.0)
    return dx * dx + dy * dy + dz * dz


@njit(cache=True)
def _near(g, cx, cy, cz, ac, ah, reach2, grid, cand, room):
    """The obstacles near geometry g (bounding-sphere centre c) in ascending order into ``cand``; returns their
    count: the grid's cells only. ``room`` 0: those whose pair passes the first test (the sphere against the world
    box; reach2: (radius + threshold)^2, or -1 for a pair Drake does not check); ``room`` > 0: every checked one
    whose box comes within ``room`` of the geometry's farthest first-test reach (a sweep anchor's clearance,
    bounded to ``room``: :func:`_clearance`). Per geometry in the row test's loop (a row proven colliding stops
    before the geometries after it); not inlined: as fast (2.2 µs a rack:fetch:64 row) and ~30 s less of the
    first compile than three inlined copies (#33)."""
    glo, ginv, greach, gdim, gstart, gitem, gcell = grid
    r = greach[g] + room
    n = 0
    i0, i1 = _cell(cx - r, glo[0], ginv[0], gdim[0]), _cell(cx + r, glo[0], ginv[0], gdim[0])
    j0, j1 = _cell(cy - r, glo[1], ginv[1], gdim[1]), _cell(cy + r, glo[1], ginv[1], gdim[1])
    k0, k1 = _cell(cz - r, glo[2], ginv[2], gdim[2]), _cell(cz + r, glo[2], ginv[2], gdim[2])
    for i in range(i0, i1 + 1):
        for j in range(j0, j1 + 1):
            for k in range(k0, k1 + 1):
                cell = (i * gdim[1] + j) * gdim[2] + k
                for t in range(gstart[cell], gstart[cell + 1]):
                    o = gitem[t]
                    if max(gcell[o, 0], i0) != i or max(gcell[o, 1], j0) != j or max(gcell[o, 2], k0) != k:
                        continue  # met in another cell too: tested in the lower corner's
                    d2 = box_gap2(cx, cy, cz, ac, ah, o)
                    if (d2 - reach2[g, o] <= 0.0) if room == 0.0 else (reach2[g, o] >= 0.0 and d2 <= r * r):
                        at = n  # insertion in order: few pass
                        while at > 0 and cand[at - 1] > o:
                            cand[at] = cand[at - 1]
                            at -= 1
                        cand[at] = o
                        n += 1
    return n


@njit(cache=True, inline="always")
def solid_distance(x0, x1, x2, h0, h1, h2, rounding, cylinder):
    """Signed distance from a point in a solid's centred frame to the solid: one point's
    :func:`lazyground.drake.solids.solid_distance`, a cylinder's radius as sqrt(x0^2 + x1^2) (numpy's hypot can
    differ in the last bit). The certifier's and the hand probe's (lazyground.drake.ik.kernels) one code."""
    if cylinder:
        d0 = np.sqrt(x0 * x0 + x1 * x1) - h0
        d1 = -np.inf
    else:
        d0 = abs(x0) - h0
        d1 = abs(x1) - h1
    d2 = abs(x2) - h2
    a, b, c = max(d0, 0.0), max(d1, 0.0), max(d2, 0.0)
    return np.sqrt(a * a + b * b + c * c) + min(max(max(d0, d1), d2), 0.0) - rounding


@njit(cache=True, inline="always")
def _offset_distance(vx, vy, vz, R, half, rounding, cylinder):
    """Signed distance to a solid with world axes R (columns) from a point at world offset v from its centre."""
    return solid_distance(R[0, 0] * vx + R[1, 0] * vy + R[2, 0] * vz, R[0, 1] * vx + R[1, 1] * vy + R[2, 1] * vz,
                          R[0, 2] * vx + R[1, 2] * vy + R[2, 2] * vz, half[0], half[1], half[2], rounding, cylinder)


@intrinsic
def c_view(typingctx, flat, lo, shape):
    """flat[lo:lo + prod(shape)] as a C-contiguous view of that shape, without numba's reshape, which calls a
    helper checking the layout (~35 ns a view; a call makes ~30 of them: ~1 µs of an edge's ~8, #31), nor
    ``as_strided``, whose any-layout views make a row ~2x slower. The caller keeps the block inside ``flat``.

    The view is borrowed: it has no memory info (no reference count), so making and dropping one costs no
    atomic increment and decrement (a kernel call makes ~50: ~0.5 µs of a proven-colliding edge's ~3, #31).
    It lives only inside the kernel call whose argument ``flat`` keeps the memory alive; a kernel never
    returns one to Python (tests/drake/test_edge_kernel.py checks that the kernels' results own their data)."""
    if not (isinstance(flat, types.Array) and flat.ndim == 1 and flat.layout == "C"):
        return None  # only a contiguous flat array's blocks are contiguous
    nd = len(shape)
    retty = types.Array(flat.dtype, nd, "C")

    def codegen(context, builder, sig, args):
        aryty, loty, shapety = sig.args
        src = make_array(aryty)(context, builder, args[0])
        shapes = [context.cast(builder, v, t, types.intp)
                  for v, t in zip(cgutils.unpack_tuple(builder, args[2], nd), shapety)]
        itemsize = context.get_constant(types.intp, context.get_abi_sizeof(context.get_data_type(aryty.dtype)))
        strides, acc = [None] * nd, itemsize
        for d in reversed(range(nd)):
            strides[d] = acc
            acc = builder.mul(acc, shapes[d])
        nitems = context.get_constant(types.intp, 1)
        for v in shapes:
            nitems = builder.mul(nitems, v)
        data = builder.gep(src.data, [context.cast(builder, args[1], loty, types.intp)])
        # the array's fields by the data model's names (populate_array's, without the struct proxy's private
        # accessors); memory info and owner stay null (borrowed, see above)
        model = context.data_model_manager[retty]
        value = cgutils.get_null_value(context.get_value_type(retty))
        for name, field in (("nitems", nitems), ("itemsize", itemsize), ("data", data),
                            ("shape", cgutils.pack_array(builder, shapes)), ("strides", cgutils.pack_array(builder, strides))):
            value = builder.insert_value(value, field, model.get_field_position(name))
        return value

    return retty(flat, lo, shape), codegen


@njit(cache=True, inline="always")
def _grid(flat, lo, rows, cols):
    """flat[lo:lo + rows * cols] as a (rows, cols) view (:func:`c_view`)."""
    return c_view(flat, lo, (rows, cols))


@njit(cache=True, inline="always")
def _stack(flat, lo, count, rows, cols):
    """flat[lo:lo + count * rows * cols] as a (count, rows, cols) view (:func:`c_view`)."""
    return c_view(flat, lo, (count, rows, cols))


@njit(cache=True, inline="always")
def tree_views(fd, idata):
    """Views of the body tree's blocks (joint and body frames, parents, kinds, position indices, slots) for
    :func:`_forward`: made once per kernel call, not per configuration (~20 % of a row's time, #31)."""
    m, n = idata[_M], idata[_N]
    o = 7 + _NF
    return (_stack(fd, idata[7], m, 3, 4), _stack(fd, idata[8], n, 3, 4),
            c_view(idata, idata[o], (m,)), c_view(idata, idata[o + 1], (m,)), c_view(idata, idata[o + 2], (m,)),
            c_view(idata, idata[o + 3], (n,)))


@njit(cache=True, inline="always")
def _forward(q, tree, Rs, ps, Rb, pb):
    """World rotation Rb (n, 3, 3) and position pb (n, 3) of every tree body at plant positions q (``tree``: :func:`tree_views`).

    Every joint's cos and sin first (into its frame's last row, Rs[j + 1, 2, :2], which the chain writes only
    after reading them), then the chain on scalars: the calls overlap instead of waiting on each frame, and each
    frame's rows are read once (~0.6 -> ~0.4 µs a configuration on Fetch, #31). The same products and sums in
    the same order as the chain written element by element: the same bits. Inlined into the row test: a call
    passing the views costs more than the chain (#31)."""
    K, F, parent, kinds, index, slot = tree
    m, n = len(parent), len(slot)
    for j in range(m):  # (a prismatic joint's slot is left as it is: its cos and sin are not read)
        if kinds[j] != PRISMATIC_KIND:
            qj = q[index[j]]
            Rs[j + 1, 2, 0] = np.cos(qj)
            Rs[j + 1, 2, 1] = np.sin(qj)
    for j in range(m):
        a = parent[j]
        k00, k01, k02, k03 = K[j, 0, 0], K[j, 0, 1], K[j, 0, 2], K[j, 0, 3]
        k10, k11, k12, k13 = K[j, 1, 0], K[j, 1, 1], K[j, 1, 2], K[j, 1, 3]
        k20, k21, k22, k23 = K[j, 2, 0], K[j, 2, 1], K[j, 2, 2], K[j, 2, 3]
        prism = kinds[j] == PRISMATIC_KIND
        qj = q[index[j]]
        cj, sj = Rs[j + 1, 2, 0], Rs[j + 1, 2, 1]
        for r in range(3):
            x0, x1, x2 = Rs[a, r, 0], Rs[a, r, 1], Rs[a, r, 2]
            c0 = x0 * k00 + x1 * k10 + x2 * k20
            c1 = x0 * k01 + x1 * k11 + x2 * k21
            c2 = x0 * k02 + x1 * k12 + x2 * k22
            p = ps[a, r] + x0 * k03 + x1 * k13 + x2 * k23
            if prism:
                ps[j + 1, r] = p + c2 * qj
                Rs[j + 1, r, 0] = c0
                Rs[j + 1, r, 1] = c1
            else:
                ps[j + 1, r] = p
                Rs[j + 1, r, 0] = c0 * cj + c1 * sj
                Rs[j + 1, r, 1] = c1 * cj - c0 * sj
            Rs[j + 1, r, 2] = c2
    for k in range(n):
        a = slot[k]
        f00, f01, f02, f03 = F[k, 0, 0], F[k, 0, 1], F[k, 0, 2], F[k, 0, 3]
        f10, f11, f12, f13 = F[k, 1, 0], F[k, 1, 1], F[k, 1, 2], F[k, 1, 3]
        f20, f21, f22, f23 = F[k, 2, 0], F[k, 2, 1], F[k, 2, 2], F[k, 2, 3]
        for r in range(3):
            x0, x1, x2 = Rs[a, r, 0], Rs[a, r, 1], Rs[a, r, 2]
            Rb[k, r, 0] = x0 * f00 + x1 * f10 + x2 * f20
            Rb[k, r, 1] = x0 * f01 + x1 * f11 + x2 * f21
            Rb[k, r, 2] = x0 * f02 + x1 * f12 + x2 * f22
            pb[k, r] = ps[a, r] + x0 * f03 + x1 * f13 + x2 * f23


@njit(cache=True, inline="always")
def block_views(fd, idata):
    """Views of the certifier's blocks in the flat arrays (see :func:`pack`), in the order open_pairs_row unpacks them."""
    G, S, O, P, I = idata[_G], idata[_S], idata[_O], idata[_P], idata[_I]
    f = c_view(idata, 7, (_NF,))
    i = c_view(idata, 7 + _NF, (_NI,))
    gR = _stack(fd, f[2], G, 3, 3)
    go = _grid(fd, f[3], G, 3)
    ghalf = _grid(fd, f[4], G, 3)
    ground, grad = c_view(fd, f[5], (G,)), c_view(fd, f[6], (G,))
    sc = _grid(fd, f[7], S, 3)
    sr = c_view(fd, f[8], (S,))
    oR = _stack(fd, f[9], O, 3, 3)
    oo = _grid(fd, f[10], O, 3)
    ohalf = _grid(fd, f[11], O, 3)
    oround = c_view(fd, f[12], (O,))
    ac = _grid(fd, f[13], 3, O)
    ah = _grid(fd, f[14], 3, O)
    reach2 = _grid(fd, f[20], G, O)
    env = _grid(fd, f[15], G, O)
    sthr = c_view(fd, f[16], (P,))
    ic = _grid(fd, f[17], I, 3)
    ir = c_view(fd, f[18], (I,))
    below = fd[f[19]]
    node = c_view(idata, i[4], (G,))
    start = c_view(idata, i[5], (G + 1,))
    gcyl = c_view(idata, i[6], (G,))
    ocyl = c_view(idata, i[7], (O,))
    mover = c_view(idata, i[8], (P,))
    other = c_view(idata, i[9], (P,))
    istart = c_view(idata, i[10], (G + 1,))
    gexact = c_view(idata, i[11], (G,))
    oexact = c_view(idata, i[12], (O,))
    gdim = c_view(idata, i[13], (4,))
    grid = (c_view(fd, f[21], (3,)), c_view(fd, f[22], (3,)), c_view(fd, f[23], (G,)), gdim,
            c_view(idata, i[14], (gdim[0] * gdim[1] * gdim[2] + 1,)), c_view(idata, i[15], (idata[i[14] + gdim[0] * gdim[1] * gdim[2]],)),
            _grid(idata, i[16], O, 3))
    return (gR, go, ghalf, ground, grad, sc, sr, oR, oo, ohalf, oround, ac, ah, reach2, env, sthr, ic, ir, below, node,
            start, gcyl, ocyl, mover, other, istart, gexact, oexact, grid)


@njit(cache=True, inline="always")
def _centres(node, go, Rb, pb, centre):
    """World centres of every moving geometry's solid (its bounding sphere's) into ``centre``."""
    for g in range(len(node)):
        b = node[g]
        for r in range(3):
            centre[g, r] = Rb[b, r, 0] * go[g, 0] + Rb[b, r, 1] * go[g, 1] + Rb[b, r, 2] * go[g, 2] + pb[b, r]


@njit(cache=True, inline="always")
def open_pairs_row(q, idata, tree, blocks, Rs, ps, Rb, pb, centre, sph, done, W, A, gap, pairs, cap, shift):
    """Open pairs of one configuration into ``pairs``; returns their count (0: certified; -1: more than ``cap``;
    COLLIDES: a pair proven closer than Drake's padding, by a sphere inside a moving geometry reaching into the
    exact solid of the other side). ``shift``: 0, or the padding for the tentative question whether any pair
    penetrates (config_unpadded_free): the solids' distance then only needs to clear the threshold less the
    padding; COLLIDES stays a padded collision (that check's False, as before #31).

    Per pair, coarse to fine: the moving geometry's bounding sphere against the other solid; its inner spheres
    reaching into it (a proof of collision); its cover spheres, and at the first one within reach, the boxes around
    both solids, then both solids' distance (:func:`_solids`; the sphere and box tests stay at the threshold: clear
    there is clear for less). The robot-vs-obstacle and robot-vs-robot loops are written out twice: one inline pair test for both
    measured ~15 % slower per row (#31)."""
    _forward(q, tree, Rs, ps, Rb, pb)
    G, O, P = idata[_G], idata[_O], idata[_P]
    (gR, go, ghalf, ground, grad, sc, sr, oR, oo, ohalf, oround, ac, ah, reach2, env, sthr, ic, ir, below, node, start,
     gcyl, ocyl, mover, other, istart, gexact, oexact, grid) = blocks
    _centres(node, go, Rb, pb, centre)
    gridded = grid[3][3] != 0
    gap, cand = gap[0], gap[1]  # (rows of a C array: contiguous, so the gap loop stays vectorised)
    done[:] = 0.0
    count = 0
    for last in range(G):
        g = G - 1 - last  # the geometries far down the tree first: they collide most (edge ends: ~10 % sooner, #31)
        cx, cy, cz, rg = centre[g, 0], centre[g, 1], centre[g, 2], grad[g]
        todo = O
        if gridded:
            todo = _near(g, cx, cy, cz, ac, ah, reach2, grid, cand, 0.0)
        else:
            # the bounding sphere against every obstacle's world box at once (no branches: vectorised); reach2 is
            # (radius + threshold)^2, or -1 for a pair Drake does not check
            for o in range(O):
                gap[o] = box_gap2(cx, cy, cz, ac, ah, o) - reach2[g, o]
        for c in range(todo):
            o = c
            if gridded:
                o = int(cand[c])
            elif gap[o] > 0.0:
                continue
            thr = env[g, o]
            vx, vy, vz = cx - oo[o, 0], cy - oo[o, 1], cz - oo[o, 2]
            if _offset_distance(vx, vy, vz, oR[o], ohalf[o], oround[o], ocyl[o]) - rg - thr > 0.0:
                continue
            if oexact[o] and _inner_reach(node[g], Rb, pb, ic, ir, istart[g], istart[g + 1], oR[o], oo[o], ohalf[o],
                                          oround[o], ocyl[o], thr - below):
                return COLLIDES
            if done[g] == 0.0:
                _spheres(g, node[g], Rb, pb, sc, start, sph)
                done[g] = 1.0
            for s in range(start[g], start[g + 1]):
                vx, vy, vz = sph[s, 0] - oo[o, 0], sph[s, 1] - oo[o, 1], sph[s, 2] - oo[o, 2]
                if _offset_distance(vx, vy, vz, oR[o], ohalf[o], oround[o], ocyl[o]) - sr[s] - thr <= 0.0:
                    _solid_axes(Rb, node[g], gR, g, A)
                    if _box_gap(A, centre[g], ghalf[g], oR[o], oo[o], ohalf[o]) - ground[g] - oround[o] - thr > 0.0:
                        break  # the two boxes around the solids are apart: clear
                    if _solids(A, centre[g], ghalf[g], ground[g], gcyl[g], oR[o], oo[o], ohalf[o], oround[o], ocyl[o],
                               thr, shift):
                        break
                    if count >= cap:
                        return -1
                    pairs[count] = g * O + o
                    count += 1
                    break
    for k in range(P):
        g, h, thr = mover[k], other[k], sthr[k]
        vx, vy, vz = centre[g, 0] - centre[h, 0], centre[g, 1] - centre[h, 1], centre[g, 2] - centre[h, 2]
        reach = grad[g] + grad[h] + thr
        if vx * vx + vy * vy + vz * vz > reach * reach:
            continue
        # the other geometry's solid axes in the world: R_WH = Rb[node[h]] @ gR[h]
        bh = node[h]
        for r in range(3):
            for c in range(3):
                W[r, c] = Rb[bh, r, 0] * gR[h, 0, c] + Rb[bh, r, 1] * gR[h, 1, c] + Rb[bh, r, 2] * gR[h, 2, c]
        if _offset_distance(vx, vy, vz, W, ghalf[h], ground[h], gcyl[h]) - grad[g] - thr > 0.0:
            continue
        if gexact[h] and _inner_reach(node[g], Rb, pb, ic, ir, istart[g], istart[g + 1], W, centre[h], ghalf[h],
                                      ground[h], gcyl[h], thr - below):
            return COLLIDES
        if done[g] == 0.0:
            _spheres(g, node[g], Rb, pb, sc, start, sph)
            done[g] = 1.0
        for s in range(start[g], start[g + 1]):
            vx, vy, vz = sph[s, 0] - centre[h, 0], sph[s, 1] - centre[h, 1], sph[s, 2] - centre[h, 2]
            if _offset_distance(vx, vy, vz, W, ghalf[h], ground[h], gcyl[h]) - sr[s] - thr <= 0.0:
                _solid_axes(Rb, node[g], gR, g, A)
                if _box_gap(A, centre[g], ghalf[g], W, centre[h], ghalf[h]) - ground[g] - ground[h] - thr > 0.0:
                    break
                if _solids(A, centre[g], ghalf[g], ground[g], gcyl[g], W, centre[h], ghalf[h], ground[h], gcyl[h], thr,
                           shift):
                    break
                if count >= cap:
                    return -1
                pairs[count] = G * O + k
                count += 1
                break
    return count


@njit(cache=True, inline="always")
def _solids(A, ca, ha, ra, cyla, B, cb, hb, rb, cylb, thr, shift):
    """The last test of a pair whose cover leaves it open: whether both solids' distance provably exceeds
    ``thr - shift`` (:func:`_gjk`'s lower bound). Never a proof of collision: Drake's distance of a separated pair
    is that of two points on the shapes, so at least the true one (a free claim stays Drake's), but it can be far
    above it (FCL's GJK stopping early: 12.4 mm for a true 4.8 mm, box against box, on fetch_cans_2), so a
    collision claim from the true distance would not be Drake's answer."""
    return _gjk(A, ca, ha, ra, cyla, B, cb, hb, rb, cylb, thr - shift)


@njit(cache=True)
def _inner_reach(b, Rb, pb, ic, ir, lo, hi, R, c, half, rounding, cylinder, limit):
    """Whether a sphere lo..hi inside a geometry on body b comes within ``limit`` of the solid with world axes
    R (columns) about c (the pair's distance is at most that: a proof of collision where the solid is exact)."""
    for s in range(lo, hi):
        wx = Rb[b, 0, 0] * ic[s, 0] + Rb[b, 0, 1] * ic[s, 1] + Rb[b, 0, 2] * ic[s, 2] + pb[b, 0] - c[0]
        wy = Rb[b, 1, 0] * ic[s, 0] + Rb[b, 1, 1] * ic[s, 1] + Rb[b, 1, 2] * ic[s, 2] + pb[b, 1] - c[1]
        wz = Rb[b, 2, 0] * ic[s, 0] + Rb[b, 2, 1] * ic[s, 1] + Rb[b, 2, 2] * ic[s, 2] + pb[b, 2] - c[2]
        if _offset_distance(wx, wy, wz, R, half, rounding, cylinder) - ir[s] <= limit:
            return True
    return False


@njit(cache=True, inline="always")
def _solid_axes(Rb, b, gR, g, A):
    """World axes (columns) of geometry g's solid on body b: Rb[b] @ gR[g], into A."""
    for r in range(3):
        for c in range(3):
            A[r, c] = Rb[b, r, 0] * gR[g, 0, c] + Rb[b, r, 1] * gR[g, 1, c] + Rb[b, r, 2] * gR[g, 2, c]


@njit(cache=True)
def _box_gap(A, ca, ha, B, cb, hb):
    """A lower bound of the distance between two boxes (world axes as the columns of A and B, centres, half
    extents): the largest gap along the 15 axes of the separating-axis test. Along any unit axis L the boxes
    span intervals of half widths sum_i h_i |L . axis_i| about L . centre, and two points of them are at least
    the gap between the intervals apart. A cylinder's box (r, r, h) and a rounded box's core enclose them,
    so the bound holds for the solids less their rounding."""
    dx, dy, dz = cb[0] - ca[0], cb[1] - ca[1], cb[2] - ca[2]
    best = -np.inf
    for k in range(15):
        if k < 3:
            lx, ly, lz = A[0, k], A[1, k], A[2, k]
        elif k < 6:
            lx, ly, lz = B[0, k - 3], B[1, k - 3], B[2, k - 3]
        else:
            i, j = (k - 6) // 3, (k - 6) % 3
            lx = A[1, i] * B[2, j] - A[2, i] * B[1, j]
            ly = A[2, i] * B[0, j] - A[0, i] * B[2, j]
            lz = A[0, i] * B[1, j] - A[1, i] * B[0, j]
            norm = np.sqrt(lx * lx + ly * ly + lz * lz)
            if norm < 1e-6:
                continue
            lx, ly, lz = lx / norm, ly / norm, lz / norm
        g = abs(lx * dx + ly * dy + lz * dz)
        for c in range(3):
            g -= ha[c] * abs(lx * A[0, c] + ly * A[1, c] + lz * A[2, c])
            g -= hb[c] * abs(lx * B[0, c] + ly * B[1, c] + lz * B[2, c])
        if g > best:
            best = g
    return best


@njit(cache=True, inline="always")
def _spheres(g, b, Rb, pb, sc, start, sph):
    """World centres of geometry g's cover spheres into ``sph``."""
    for s in range(start[g], start[g + 1]):
        for r in range(3):
            sph[s, r] = Rb[b, r, 0] * sc[s, 0] + Rb[b, r, 1] * sc[s, 1] + Rb[b, r, 2] * sc[s, 2] + pb[b, r]


# ---- exact convex distance between two solids (#31) ----------------------------------------------------------------
# A pair the sphere cover leaves open is decided between the two solids themselves (boxes, rounded boxes -- spheres
# and capsules --, cylinders) by GJK on their support functions. Only the lower bound is used, so GJK's own numerics
# never decide an answer:
# * lower: for any direction n (unit), every point of A - B has n . x >= n . s_A(-n) - n . s_B(n) (s: the support
#   point), so the distance is at least that (a separating axis); GJK only picks a good n. A solid encloses its
#   shape, so this bounds the shapes' distance too.
# * GJK's iterate, a convex combination of support points of A - B, lies in A - B: once it is within the threshold
#   (or the origin lies inside a simplex of them) no lower bound can clear it, and the test stops. It is no proof
#   of collision for the kernel: Drake's own distance can be far above the true one (see _solids).

GJK_ITERATIONS = 32
GJK_SAFETY = 1e-9  # metres: a lower bound must clear its threshold by this much (the arithmetic's rounding)


@njit(cache=True, inline="always")
def _support(dx, dy, dz, R, c, half, rounding, cylinder):
    """The point of a solid (world axes R as columns, centre c) farthest along direction d."""
    px, py, pz = c[0], c[1], c[2]
    if cylinder:  # in the cylinder's own axes, so the point lies on it whatever the direction (d along the axis too)
        ex = dx * R[0, 0] + dy * R[1, 0] + dz * R[2, 0]
        ey = dx * R[0, 1] + dy * R[1, 1] + dz * R[2, 1]
        t = dx * R[0, 2] + dy * R[1, 2] + dz * R[2, 2]
        s = half[2] if t >= 0.0 else -half[2]
        rn = np.sqrt(ex * ex + ey * ey)
        u, w = (half[0] * ex / rn, half[0] * ey / rn) if rn > 0.0 else (0.0, 0.0)
        px += u * R[0, 0] + w * R[0, 1] + s * R[0, 2]
        py += u * R[1, 0] + w * R[1, 1] + s * R[1, 2]
        pz += u * R[2, 0] + w * R[2, 1] + s * R[2, 2]
    else:
        for i in range(3):
            t = dx * R[0, i] + dy * R[1, i] + dz * R[2, i]
            s = half[i] if t >= 0.0 else -half[i]
            px += s * R[0, i]
            py += s * R[1, i]
            pz += s * R[2, i]
    if rounding > 0.0:
        n = np.sqrt(dx * dx + dy * dy + dz * dz)
        if n > 0.0:
            px += rounding * dx / n
            py += rounding * dy / n
            pz += rounding * dz / n
    return px, py, pz


@njit(cache=True)
def _closest(S, lam, n, T, K):
    """The point of the simplex S[:n] nearest the origin as weights ``lam`` (>= 0, sum 1), the simplex reduced to
    the vertices with positive weight (S and lam compacted); returns the new count, 0 when the origin lies inside a
    non-flat tetrahedron. T, K: (3, 3) scratch."""
    if n == 1:
        lam[0] = 1.0
        return 1
    if n == 2:
        ex, ey, ez = S[1, 0] - S[0, 0], S[1, 1] - S[0, 1], S[1, 2] - S[0, 2]
        ee = ex * ex + ey * ey + ez * ez
        t = -(S[0, 0] * ex + S[0, 1] * ey + S[0, 2] * ez) / ee if ee > 0.0 else 0.0
        if t <= 0.0:
            lam[0] = 1.0
            return 1
        if t >= 1.0:
            S[0] = S[1]
            lam[0] = 1.0
            return 1
        lam[0], lam[1] = 1.0 - t, t
        return 2
    if n == 3:
        return _triangle(S, lam, 0, 1, 2)
    # a tetrahedron: the origin inside (each face's plane has it on the fourth vertex's side), or the nearest face
    best = np.inf
    vol = _orient(S, 0, 1, 2, 3)
    scale = 0.0
    for i in range(4):
        scale = max(scale, S[i, 0] * S[i, 0] + S[i, 1] * S[i, 1] + S[i, 2] * S[i, 2])
    flat = abs(vol) <= 1e-12 * scale ** 1.5  # every face is a candidate
    outside = False
    kept, l0, l1, l2 = 1, 0.0, 0.0, 0.0
    for f in range(4):
        a, b, c, d = (0, 1, 2, 3) if f == 0 else (0, 1, 3, 2) if f == 1 else (0, 2, 3, 1) if f == 2 else (1, 2, 3, 0)
        if not flat and _orient_origin(S, a, b, c) * _orient(S, a, b, c, d) >= 0.0:
            continue
        outside = True
        T[0], T[1], T[2] = S[a], S[b], S[c]
        m = _triangle(T, lam, 0, 1, 2)
        x = y = z = 0.0
        for i in range(m):
            x += lam[i] * T[i, 0]
            y += lam[i] * T[i, 1]
            z += lam[i] * T[i, 2]
        d2 = x * x + y * y + z * z
        if d2 < best:
            best, kept, l0, l1, l2 = d2, m, lam[0], lam[1], lam[2]
            K[:m] = T[:m]
    if not outside:
        return 0
    S[:kept] = K[:kept]
    lam[0], lam[1], lam[2] = l0, l1, l2
    return kept


@njit(cache=True, inline="always")
def _orient(S, a, b, c, d):
    """(S[b] - S[a]) x (S[c] - S[a]) . (S[d] - S[a])."""
    ux, uy, uz = S[b, 0] - S[a, 0], S[b, 1] - S[a, 1], S[b, 2] - S[a, 2]
    vx, vy, vz = S[c, 0] - S[a, 0], S[c, 1] - S[a, 1], S[c, 2] - S[a, 2]
    wx, wy, wz = S[d, 0] - S[a, 0], S[d, 1] - S[a, 1], S[d, 2] - S[a, 2]
    return (uy * vz - uz * vy) * wx + (uz * vx - ux * vz) * wy + (ux * vy - uy * vx) * wz


@njit(cache=True, inline="always")
def _orient_origin(S, a, b, c):
    """:func:`_orient` with the origin as the fourth point."""
    ux, uy, uz = S[b, 0] - S[a, 0], S[b, 1] - S[a, 1], S[b, 2] - S[a, 2]
    vx, vy, vz = S[c, 0] - S[a, 0], S[c, 1] - S[a, 1], S[c, 2] - S[a, 2]
    return -((uy * vz - uz * vy) * S[a, 0] + (uz * vx - ux * vz) * S[a, 1] + (ux * vy - uy * vx) * S[a, 2])


@njit(cache=True, inline="always")
def _vertex(S, lam, x, y, z):
    """A triangle's Voronoi vertex region: S[0] = (x, y, z), weight 1; returns 1 (:func:`_triangle`)."""
    S[0, 0], S[0, 1], S[0, 2] = x, y, z
    lam[0] = 1.0
    return 1


@njit(cache=True, inline="always")
def _edge(S, lam, px, py, pz, qx, qy, qz, t):
    """A triangle's Voronoi edge region: S[0] = p, S[1] = q, weights 1 - t, t; returns 2 (:func:`_triangle`)."""
    S[0, 0], S[0, 1], S[0, 2] = px, py, pz
    S[1, 0], S[1, 1], S[1, 2] = qx, qy, qz
    lam[0], lam[1] = 1.0 - t, t
    return 2


@njit(cache=True)
def _triangle(S, lam, ia, ib, ic):
    """Nearest point of triangle S[ia], S[ib], S[ic] to the origin (Ericson, Real-Time Collision Detection 5.1.5):
    the vertices of its Voronoi feature into S[0..], their weights into lam; returns their count."""
    ax, ay, az = S[ia, 0], S[ia, 1], S[ia, 2]
    bx, by, bz = S[ib, 0], S[ib, 1], S[ib, 2]
    cx, cy, cz = S[ic, 0], S[ic, 1], S[ic, 2]
    abx, aby, abz = bx - ax, by - ay, bz - az
    acx, acy, acz = cx - ax, cy - ay, cz - az
    d1 = -(abx * ax + aby * ay + abz * az)
    d2 = -(acx * ax + acy * ay + acz * az)
    if d1 <= 0.0 and d2 <= 0.0:
        return _vertex(S, lam, ax, ay, az)
    d3 = -(abx * bx + aby * by + abz * bz)
    d4 = -(acx * bx + acy * by + acz * bz)
    if d3 >= 0.0 and d4 <= d3:
        return _vertex(S, lam, bx, by, bz)
    vc = d1 * d4 - d3 * d2
    if vc <= 0.0 and d1 >= 0.0 and d3 <= 0.0:
        return _edge(S, lam, ax, ay, az, bx, by, bz, d1 / (d1 - d3))
    d5 = -(abx * cx + aby * cy + abz * cz)
    d6 = -(acx * cx + acy * cy + acz * cz)
    if d6 >= 0.0 and d5 <= d6:
        return _vertex(S, lam, cx, cy, cz)
    vb = d5 * d2 - d1 * d6
    if vb <= 0.0 and d2 >= 0.0 and d6 <= 0.0:
        return _edge(S, lam, ax, ay, az, cx, cy, cz, d2 / (d2 - d6))
    va = d3 * d6 - d5 * d4
    if va <= 0.0 and (d4 - d3) >= 0.0 and (d5 - d6) >= 0.0:
        return _edge(S, lam, bx, by, bz, cx, cy, cz, (d4 - d3) / ((d4 - d3) + (d5 - d6)))
    den = va + vb + vc
    if not den > 0.0:  # a degenerate triangle: its nearest vertex
        return _vertex(S, lam, ax, ay, az)
    v, w = vb / den, vc / den
    S[0, 0], S[0, 1], S[0, 2] = ax, ay, az
    S[1, 0], S[1, 1], S[1, 2] = bx, by, bz
    S[2, 0], S[2, 1], S[2, 2] = cx, cy, cz
    lam[0], lam[1], lam[2] = 1.0 - v - w, v, w
    return 3


@njit(cache=True)
def _gjk(RA, cA, hA, rA, cylA, RB, cB, hB, rB, cylB, free_above):
    """Whether the two solids are proven farther apart than ``free_above`` (a lower bound of their distance
    exceeds it; see above)."""
    S, lam, T, K = np.empty((4, 3)), np.empty(4), np.empty((3, 3)), np.empty((3, 3))
    vx, vy, vz = cA[0] - cB[0], cA[1] - cB[1], cA[2] - cB[2]  # both centres lie in their solids: a point of A - B
    S[0, 0], S[0, 1], S[0, 2] = vx, vy, vz
    n = 1
    for _ in range(GJK_ITERATIONS):
        vv = vx * vx + vy * vy + vz * vz
        if vv <= (free_above + GJK_SAFETY) ** 2:  # a point of A - B this near: never provable farther (stop early)
            return False
        if vv <= 1e-30:
            return False
        ax, ay, az = _support(-vx, -vy, -vz, RA, cA, hA, rA, cylA)
        bx, by, bz = _support(vx, vy, vz, RB, cB, hB, rB, cylB)
        wx, wy, wz = ax - bx, ay - by, az - bz
        vw = vx * wx + vy * wy + vz * wz
        if vw > 0.0 and vw * vw > (free_above + GJK_SAFETY) ** 2 * vv:  # the separating axis along v
            return True
        if vv - vw <= 1e-12 * vv:  # converged: w adds nothing
            return False
        S[n, 0], S[n, 1], S[n, 2] = wx, wy, wz
        n = _closest(S, lam, n + 1, T, K)
        if n == 0:  # the origin inside a tetrahedron of points of A - B: the solids intersect
            return False
        x = y = z = 0.0
        for i in range(n):
            x += lam[i] * S[i, 0]
            y += lam[i] * S[i, 1]
            z += lam[i] * S[i, 2]
        if x * x + y * y + z * z >= vv:  # no progress (rounding)
            return False
        vx, vy, vz = x, y, z
    return False


def work_size(idata: np.ndarray) -> int:
    """Floats of scratch space a call needs (see scratch_views)."""
    m, n, G, S = idata[_M], idata[_N], idata[_G], idata[_S]
    return int(12 * (m + 1) + 12 * n + 4 * G + 3 * S + 18 + 2 * idata[_O])


@njit(cache=True)
def scratch_views(idata, work):
    """Scratch arrays over ``work``: slot frames (identity world frame), body poses, centres, spheres, a rotation,
    and per geometry whether its spheres are posed yet."""
    m, n, G, S = idata[_M], idata[_N], idata[_G], idata[_S]
    a = 0
    Rs = _stack(work, a, m + 1, 3, 3)
    a += 9 * (m + 1)
    ps = _grid(work, a, m + 1, 3)
    a += 3 * (m + 1)
    Rb = _stack(work, a, n, 3, 3)
    a += 9 * n
    pb = _grid(work, a, n, 3)
    a += 3 * n
    centre = _grid(work, a, G, 3)
    a += 3 * G
    sph = _grid(work, a, S, 3)
    a += 3 * S
    done = c_view(work, a, (G,))
    a += G
    W = _grid(work, a, 3, 3)
    a += 9
    A = _grid(work, a, 3, 3)
    a += 9
    gap = _grid(work, a, 2, idata[_O])  # per obstacle its first test's gap; with a grid, the obstacles passing it
    Rs[0] = 0.0
    Rs[0, 0, 0] = Rs[0, 1, 1] = Rs[0, 2, 2] = 1.0
    ps[0] = 0.0
    return Rs, ps, Rb, pb, centre, sph, done, W, A, gap


@njit(cache=True, inline="always")
def row_inline(q, fd, idata, work, pairs, cap, shift):
    """:func:`open_pairs_row` of plant positions ``q`` with its views made here (borrowed, :func:`c_view`: making
    them costs no reference count). Inlined only where a planner's single checks run (edge_kernel's edge_call and
    config_call: ~0.1 µs a check less than a call, #31); the other kernels call :func:`row_code`. Each inlined row
    test costs ~20-30 s of the kernels' first compile (#31)."""
    Rs, ps, Rb, pb, centre, sph, done, W, A, gap = scratch_views(idata, work)
    return open_pairs_row(q, idata, tree_views(fd, idata), block_views(fd, idata), Rs, ps, Rb, pb, centre, sph, done,
                          W, A, gap, pairs, cap, shift)


@njit(cache=True)
def row_code(q, fd, idata, work, pairs, cap, shift):
    """:func:`row_inline` compiled once: the row test of the kernels off a planner's single checks (a batch, a
    sweep, the steps after one left open, :func:`certify_one`); a call costs ~0.04 µs a row (#31)."""
    return row_inline(q, fd, idata, work, pairs, cap, shift)


@njit(cache=True)
def certify_rows(Q, fd, idata, work, pairs):
    """Per row of plant positions Q: the count of its open pairs (0: certified, -1: more than pairs.shape[1],
    COLLIDES: proven colliding), the pairs in ``pairs[row]``."""
    out = np.empty(Q.shape[0], np.int64)
    cap = pairs.shape[1]
    for r in range(Q.shape[0]):
        out[r] = row_code(Q[r], fd, idata, work, pairs[r], cap, 0.0)
    return out


@njit(cache=True)
def certify_one(fd, idata, work, pairs, q, shift):
    """:func:`certify_rows` of one configuration; its open pairs in ``pairs[:-1]``; ``shift``: see :func:`open_pairs_row`.
    (The certifier's arrays first: a checker binds them once, functools.partial.)"""
    return row_code(q, fd, idata, work, pairs, len(pairs) - 1, shift)


@njit(cache=True)
def first_open(qa, qb, n, order, begin, fd, idata, work, pairs):
    """The first position p >= ``begin`` of ``order`` whose configuration qa + (order[p] / n) (qb - qa) is not
    certified (its code in ``pairs[-1]``, its open pairs before), or -1 when all are."""
    q = np.empty(len(qa))
    cap = len(pairs) - 1
    for p in range(begin, len(order)):
        t = order[p] / n
        for j in range(len(qa)):
            q[j] = qa[j] + t * (qb[j] - qa[j])
        c = row_code(q, fd, idata, work, pairs, cap, 0.0)
        if c != 0:
            pairs[-1] = c
            return p
    return -1


# ---- configurations in sequence (#31) ------------------------------------------------------------------------------
# Configurations in sequence, each close to the one before, certified from an anchor (sweep_rows).
#
# A densely checked path (a shortcut's fine check, a timed trajectory's dense check) asks
# about thousands of configurations a few millimetres apart. At an *anchor* configuration
# qa, :func:`_clearance` bounds, per moving geometry, how far its bounding sphere may move
# before a checked pair with the environment comes within its threshold (the bounding
# sphere against each obstacle's world box and solid: the first level of
# :func:`open_pairs_row`'s test), per self pair how far its two
# bounding spheres may move relative to each other, and per geometry and joint the lever:
# the farthest distance of the bounding sphere from the joint's axis (1 for a prismatic joint,
# 0 for a joint not above it). On the straight line from qa to q = qa + dq no point of the
# sphere moves farther than (sum_j |dq_j| lever_j) (1 + s), s = sum |dq_j| over revolute joints
# (<= 1; see ``SphereCertifier.levers``: M <= a (e^s - 1) / s). A self pair's two geometries move
# relative to each other by at most the sum of both bounds over the joints above only one of them
# (in the frame of the body above both, the joints above it move neither). A configuration where every
# geometry moved less than its clearance, and every self pair's two geometries less than the
# pair's, is free for Drake's checker as the anchor is (the same lower bounds, less the
# distances moved). Any other configuration gets the whole test (``open_pairs_row``): its answer then
# is the whole test's. A configuration not covered becomes the next anchor when every clearance there
# is positive; after a failed attempt the next ones wait 4, 8, ... MAX_WAIT rows.

ROOM = 0.1  # metres: clearances are bounded to this (farther obstacles need no distance)
ENOUGH = 0.05  # metres: a bounding-sphere clearance this large is not refined by the solid's distance
MAX_WAIT = 32  # rows: the most between two anchor attempts (near an obstacle most of them fail: ~1/2 of the rows of
# a Fetch trajectory, where each failed attempt costs about a whole test more)
SAFETY = 1e-9  # metres: a moved distance must stay this far below its clearance (rounding of the bound itself)


@njit(cache=True, inline="always")
def moved_bound(a, s):
    """How far a point moves at most from an anchor when the joints turn by |dq_j| with lever sum
    a = sum_j |dq_j| lever_j and s = sum |dq_j| over revolute joints (<= 1): the true bound a (e^s - 1) / s
    (``SphereCertifier.levers``) is below a (1 + s); plus the bound's own rounding."""
    return a * (1.0 + s) * (1.0 + SAFETY) + SAFETY


@njit(cache=True)
def _clearance(q, idata, tree, blocks, Rs, ps, Rb, pb, centre, W, cand, above, lever, clear_g, clear_k):
    """At q: per geometry its environment clearance into ``clear_g``, per self pair its clearance into ``clear_k``,
    the levers (G, m) into ``lever``; returns whether all are positive (q is then free for Drake's checker).
    With an obstacle grid, a geometry's loop visits only the obstacles within ROOM of its reach (:func:`_near`
    into ``cand``), in the same order: the others are skipped below anyway (their box is farther than the
    clearance can be), so the clearances are the same bits (rack:fetch:64 sweeps 5.5 -> 3-4.5 µs a row, #33)."""
    _forward(q, tree, Rs, ps, Rb, pb)
    m, G, O, P = idata[_M], idata[_G], idata[_O], idata[_P]
    (gR, go, ghalf, ground, grad, sc, sr, oR, oo, ohalf, oround, ac, ah, reach2, env, sthr, ic, ir, below, node, start,
     gcyl, ocyl, mover, other, istart, gexact, oexact, grid) = blocks  # the cover and inner spheres: unused
    kinds = tree[3]
    _centres(node, go, Rb, pb, centre)
    ok = True
    gridded = grid[3][3] != 0
    for g in range(G):
        cx, cy, cz, rg = centre[g, 0], centre[g, 1], centre[g, 2], grad[g]
        best = ROOM
        todo = _near(g, cx, cy, cz, ac, ah, reach2, grid, cand, ROOM) if gridded else O
        for c in range(todo):
            o = int(cand[c]) if gridded else c
            if reach2[g, o] < 0.0:
                continue  # a pair Drake does not check
            d2, t = box_gap2(cx, cy, cz, ac, ah, o), best + rg + env[g, o]
            if t > 0.0 and d2 >= t * t:
                continue  # the world box is farther than the clearance so far
            low = np.sqrt(d2) - rg - env[g, o]  # the world box holds the obstacle
            if low < best and low < ENOUGH:
                low = max(low, _offset_distance(cx - oo[o, 0], cy - oo[o, 1], cz - oo[o, 2], oR[o], ohalf[o],
                                                oround[o], ocyl[o]) - rg - env[g, o])
            best = min(best, low)
        clear_g[g] = best
        if best <= 0.0:
            ok = False
        for j in range(m):
            if above[g, j] == 0:
                lever[g, j] = 0.0
            elif kinds[j] == PRISMATIC_KIND:
                lever[g, j] = 1.0
            else:  # distance from the joint's axis (its frame's z through its origin), plus the radius
                vx, vy, vz = cx - ps[j + 1, 0], cy - ps[j + 1, 1], cz - ps[j + 1, 2]
                along = vx * Rs[j + 1, 0, 2] + vy * Rs[j + 1, 1, 2] + vz * Rs[j + 1, 2, 2]
                lever[g, j] = np.sqrt(max(vx * vx + vy * vy + vz * vz - along * along, 0.0)) + rg
    for k in range(P):
        g, h = mover[k], other[k]
        vx, vy, vz = centre[g, 0] - centre[h, 0], centre[g, 1] - centre[h, 1], centre[g, 2] - centre[h, 2]
        t = ROOM + grad[g] + grad[h] + sthr[k]
        d2 = vx * vx + vy * vy + vz * vz
        if d2 >= t * t:
            clear_k[k] = ROOM
            continue
        low = np.sqrt(d2) - grad[g] - grad[h] - sthr[k]
        if low < ENOUGH:
            bh = node[h]
            for r in range(3):
                for c in range(3):
                    W[r, c] = Rb[bh, r, 0] * gR[h, 0, c] + Rb[bh, r, 1] * gR[h, 1, c] + Rb[bh, r, 2] * gR[h, 2, c]
            low = max(low, _offset_distance(vx, vy, vz, W, ghalf[h], ground[h], gcyl[h]) - grad[g] - sthr[k])
        clear_k[k] = low
        if clear_k[k] <= 0.0:
            ok = False
    return ok


@njit(cache=True, inline="always")
def _pair_levers(blocks, above, lever, pair_lever):
    """Per self pair and joint, its lever (P, m) into ``pair_lever`` from the geometries' (G, m): the sum of its two
    geometries' over the joints above one of them only (the others move both alike)."""
    mover, other = blocks[23], blocks[24]
    for k in range(len(mover)):
        g, h = mover[k], other[k]
        for j in range(lever.shape[1]):
            pair_lever[k, j] = lever[g, j] + lever[h, j] if above[g, j] != above[h, j] else 0.0


@njit(cache=True)
def sweep_rows(Q, fd, idata, work, above, pairs):
    """Per row of plant positions Q (in sequence): its code as ``certify_rows`` gives it (0 certified, open pairs'
    count, -1, COLLIDES) and its open pairs in ``pairs[row]``; a row within reach of the last anchor is 0."""
    Rs, ps, Rb, pb, centre, sph, done, W, A, gap = scratch_views(idata, work)
    tree, blocks = tree_views(fd, idata), block_views(fd, idata)
    m, G, P = idata[_M], idata[_G], idata[_P]
    kinds, index = tree[3], tree[4]
    lever, pair_lever = np.empty((G, m)), np.empty((P, m))
    order = np.empty(P, np.int64)
    tight = 0
    clear_g, clear_k, moved, dq = np.empty(G), np.empty(P), np.empty(G), np.empty(m)
    qa = np.empty(Q.shape[1])
    out = np.empty(Q.shape[0], np.int64)
    cap = pairs.shape[1]
    anchored = False
    wait, backoff = 0, 2  # rows to go before the next anchor attempt; after each that fails, twice as many
    for r in range(Q.shape[0]):
        if anchored:
            s = 0.0
            for j in range(m):
                dq[j] = abs(Q[r, index[j]] - qa[index[j]])
                if kinds[j] != PRISMATIC_KIND:
                    s += dq[j]
            covered = s <= 1.0
            if covered:
                for g in range(G):
                    a = 0.0
                    for j in range(m):
                        a += dq[j] * lever[g, j]
                    moved[g] = moved_bound(a, s)
                    if moved[g] >= clear_g[g]:
                        covered = False
                        break
            if covered:
                # a pair's two geometries move apart by at most the sum of their moves: only the pairs with less
                # room than twice the largest move need their own bound
                most = 0.0
                for g in range(G):
                    most = max(most, moved[g])
                count = P if 2.0 * most >= ROOM else tight
                for t in range(count):
                    k = order[t]
                    a = 0.0
                    for j in range(m):
                        a += dq[j] * pair_lever[k, j]
                    if moved_bound(a, s) >= clear_k[k]:
                        covered = False
                        break
            if covered:
                out[r] = 0
                continue
        if wait == 0:
            if _clearance(Q[r], idata, tree, blocks, Rs, ps, Rb, pb, centre, W, gap[1], above, lever, clear_g, clear_k):
                anchored = True
                backoff = 2
                for c in range(Q.shape[1]):
                    qa[c] = Q[r, c]
                tight = 0  # the pairs with less than ROOM first, in ``order``
                for k in range(P):
                    if clear_k[k] < ROOM:
                        order[tight] = k
                        tight += 1
                rest = tight
                for k in range(P):
                    if clear_k[k] >= ROOM:
                        order[rest] = k
                        rest += 1
                _pair_levers(blocks, above, lever, pair_lever)
                out[r] = 0
                continue
            anchored = False
            backoff = min(2 * backoff, MAX_WAIT)
            wait = backoff
        else:
            wait -= 1
        out[r] = row_code(Q[r], fd, idata, work, pairs[r], cap, 0.0)
    return out
