"""Configurations in sequence, each close to the one before, certified from an anchor (#31, compiled with numba).

A densely checked path (a shortcut's fine check, a timed trajectory's dense check) asks
about thousands of configurations a few millimetres apart. At an *anchor* configuration
qa, :func:`_clearance` bounds, per moving geometry, how far its bounding sphere may move
before a checked pair with the environment comes within its threshold (the bounding
sphere against each obstacle's world box and solid: the first level of
:func:`lazyground.drake.sphere_kernels._row`'s test), per self pair how far its two
bounding spheres may move relative to each other, and per geometry and joint the lever:
the farthest distance of the bounding sphere from the joint's axis (1 for a prismatic joint,
0 for a joint not above it). On the straight line from qa to q = qa + dq no point of the
sphere moves farther than (sum_j |dq_j| lever_j) (1 + s), s = sum |dq_j| over revolute joints
(<= 1; see ``SphereCertifier.levers``: M <= a (e^s - 1) / s). A self pair's two geometries move
relative to each other by at most the sum of both bounds over the joints above only one of them
(in the frame of the body above both, the joints above it move neither). A configuration where every
geometry moved less than its clearance, and every self pair's two geometries less than the
pair's, is free for Drake's checker as the anchor is (the same lower bounds, less the
distances moved). Any other configuration gets the whole test (``_row``): its answer then
is the whole test's. A configuration not covered becomes the next anchor when every clearance there
is positive; after a failed attempt the next ones wait 4, 8, ... MAX_WAIT rows.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from lazyground.drake.sphere_kernels import (_HEAD, _NF, _G, _O, _P, _M, PRISMATIC_KIND, _blocks, _centres, _forward,
                                             _offset_distance, _row, _views)

ROOM = 0.1  # metres: clearances are bounded to this (farther obstacles need no distance)
ENOUGH = 0.05  # metres: a bounding-sphere clearance this large is not refined by the solid's distance
MAX_WAIT = 32  # rows: the most between two anchor attempts (near an obstacle most attempts fail: ~1/2 of the rows
# of a Fetch trajectory; a whole test per attempt and row there, or 1/16 more rows tested in full)
SAFETY = 1e-9  # metres: a moved distance must stay this far below its clearance (rounding of the bound itself)


@njit(cache=True)
def _clearance(q, fd, idata, Rs, ps, Rb, pb, centre, W, above, lever, clear_g, clear_k):
    """At q: per geometry its environment clearance into ``clear_g``, per self pair its clearance into ``clear_k``,
    the levers (G, m) into ``lever``; returns whether all are positive (q is then free for Drake's checker)."""
    _forward(q, fd, idata, Rs, ps, Rb, pb)
    m, G, O, P = idata[_M], idata[_G], idata[_O], idata[_P]
    (gR, go, ghalf, ground, grad, sc, sr, oR, oo, ohalf, oround, ac, ah, reach2, env, sthr, ic, ir, below, node, start,
     gcyl, ocyl, mover, other, istart, gexact, oexact) = _blocks(fd, idata)  # the cover and inner spheres: unused
    kinds = idata[idata[7 + _NF + 1]:idata[7 + _NF + 1] + m]
    _centres(node, go, Rb, pb, centre)
    ok = True
    for g in range(G):
        cx, cy, cz, rg = centre[g, 0], centre[g, 1], centre[g, 2], grad[g]
        best = ROOM
        for o in range(O):
            if reach2[g, o] < 0.0:
                continue  # a pair Drake does not check
            dx = max(abs(cx - ac[0, o]) - ah[0, o], 0.0)
            dy = max(abs(cy - ac[1, o]) - ah[1, o], 0.0)
            dz = max(abs(cz - ac[2, o]) - ah[2, o], 0.0)
            d2, t = dx * dx + dy * dy + dz * dz, best + rg + env[g, o]
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


@njit(cache=True)
def sweep_rows(Q, fd, idata, work, above, pairs):
    """Per row of plant positions Q (in sequence): its code as ``certify_rows`` gives it (0 certified, open pairs'
    count, -1, COLLIDES) and its open pairs in ``pairs[row]``; a row within reach of the last anchor is 0."""
    Rs, ps, Rb, pb, centre, sph, done, W, A, gap = _views(idata, work)
    m, G, P = idata[_M], idata[_G], idata[_P]
    i = idata[7 + _NF:_HEAD]
    o_ = 7 + _NF
    kinds = idata[idata[o_ + 1]:idata[o_ + 1] + m]
    index = idata[idata[o_ + 2]:idata[o_ + 2] + m]
    mover = idata[i[8]:i[8] + P]
    other = idata[i[9]:i[9] + P]
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
                    moved[g] = a * (1.0 + s) * (1.0 + SAFETY) + SAFETY
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
                    if a * (1.0 + s) * (1.0 + SAFETY) + SAFETY >= clear_k[k]:
                        covered = False
                        break
            if covered:
                out[r] = 0
                continue
        if wait == 0:
            if _clearance(Q[r], fd, idata, Rs, ps, Rb, pb, centre, W, above, lever, clear_g, clear_k):
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
                # a self pair: the joints above one of its geometries only (the others move both alike)
                for k in range(P):
                    g, h = mover[k], other[k]
                    for j in range(m):
                        pair_lever[k, j] = lever[g, j] + lever[h, j] if above[g, j] != above[h, j] else 0.0
                out[r] = 0
                continue
            anchored = False
            backoff = min(2 * backoff, MAX_WAIT)
            wait = backoff
        else:
            wait -= 1
        out[r] = _row(Q[r], fd, idata, Rs, ps, Rb, pb, centre, sph, done, W, A, gap, pairs[r], cap)
    return out
