"""A conservative test that proves configurations collision-free before Drake's checker is asked (#16, #19).

Drake's ``SceneGraphCollisionChecker`` asks FCL for the signed distance of every
geometry pair it checks: ~40-110 µs per Fetch configuration. Most configurations
the fine re-checks and shortcuts ask about are far from everything;
:class:`SphereCertifier` proves that for a whole batch in numpy, and only the
configurations it cannot prove go to Drake. The checker's answers stay exactly
Drake's because the test is one-sided:

* Drake calls a configuration colliding when some pair it checks (a collision
  candidate of SceneGraph, a robot body in it, the bodies not filtered by the
  checker) has signed distance <= the pair's padding
  (``SceneGraphCollisionChecker::DoCheckContextConfigCollisionFree``).
* Here a configuration is certified only when, for every such pair, a *lower
  bound* of the pair's distance exceeds max(padding, 0) + ``margin``: then Drake's
  distance exceeds the padding too. ``margin`` (0.1 mm) absorbs Drake's own
  distance error and the rounding of the two forward kinematics (~1e-15 m).
* Lower bounds come from supersets (the distance of two sets is at least that of
  two supersets): geometry whose pose never changes (the environment, robot links
  welded to the world) and the larger geometry of a robot-robot pair are solids
  with an exact or enclosing shape (lazyground.drake.solids); the other side of a
  pair is a cover of spheres enclosing it (a sphere's distance to a solid is its
  centre's minus its radius).
* Each pair is tried coarse to fine: bounding sphere against bounding sphere, the
  moving geometry's bounding sphere against the other solid, then sphere by sphere.
* Pairs of two never-moving geometries are decided once, by Drake, at
  construction; a world where one of them collides gets no certifier.
* A configuration it cannot prove comes back with the pairs it left open
  (:meth:`SphereCertifier.certify`); the checker asks SceneGraph about those
  pairs only, which decides as Drake's checker would (every other pair it checks
  is proven clear).

A world with a joint or shape this cannot bound (a planar or floating joint, a
moving environment body, a mesh it cannot read) gets no certifier
(:func:`sphere_certifier` returns None) and Drake checks everything.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from lazyground.drake.chain import PRISMATIC, BodyTree, body_tree
from lazyground.drake.solids import cover, exact, inner, solid, solid_distance, solid_radius

MARGIN = 1e-4  # metres beyond the padding a lower bound must clear
SLACK = 0.008  # metres a cover's spheres may reach beyond their shape (finer: more spheres)


@dataclass(frozen=True)
class _Solids:
    """Solids posed in a parent frame (the world for obstacles, the body for moving geometry)."""

    R: np.ndarray  # (n, 3, 3) R_PG
    o: np.ndarray  # (n, 3) centre in the parent frame
    half: np.ndarray  # (n, 3)
    rounding: np.ndarray  # (n,)
    cylinder: np.ndarray  # (n,) bool
    radius: np.ndarray  # (n,) of the enclosing sphere about o

    @staticmethod
    def of(shapes, X_PG: list[np.ndarray]) -> "_Solids":
        parts = [solid(s) for s in shapes]
        R = np.array([X[:3, :3] for X in X_PG]).reshape(-1, 3, 3)
        o = np.array([X[:3, :3] @ c + X[:3, 3] for X, (c, _, _, _) in zip(X_PG, parts)]).reshape(-1, 3)
        return _Solids(R, o, np.array([p[1] for p in parts]).reshape(-1, 3), np.array([p[2] for p in parts], float),
                       np.array([p[3] for p in parts], bool), np.array([solid_radius(*p[1:]) for p in parts], float))


@dataclass(frozen=True)
class _Pairs:
    """Checked pairs: a moving geometry (its spheres) against another one's solid, and the distance to clear."""

    mover: np.ndarray
    other: np.ndarray
    threshold: np.ndarray


class SphereCertifier:
    """Proves batches of plant configurations collision-free for one SceneGraphCollisionChecker (build with :func:`sphere_certifier`).

    Args:
        tree: forward kinematics of every body with geometry.
        node: per moving geometry, its body's tree node.
        solids: per moving geometry, its solid in its body's frame.
        centers, radii, start: every moving geometry's cover in its body frame; geometry g
            owns spheres start[g]:start[g + 1].
        obstacles: the never-moving geometry, in the world frame.
        env_threshold: (moving geometries, obstacles) the distance to clear; -inf: a pair Drake does not check.
        self_pairs: moving geometry (its spheres) against another moving geometry's solid.
        geometry_ids: SceneGraph's ids of the moving geometries, then of the obstacles (:attr:`pair_geometries`).
        inside: spheres inside each moving geometry (start, centres in its body frame, radii; as for the cover),
            and per moving geometry and obstacle whether its solid is its shape: with ``collide_below`` (a pair
            collides for Drake when its distance is at most this below its threshold, inf: never claimed), what
            lets the compiled test prove a collision (lazyground.drake.compiled).
    """

    def __init__(self, tree: BodyTree, node: np.ndarray, solids: _Solids, centers: np.ndarray, radii: np.ndarray,
                 start: np.ndarray, obstacles: _Solids, env_threshold: np.ndarray, self_pairs: _Pairs,
                 geometry_ids: list = (), inside=None, collide_below: float = np.inf):
        self.tree, self._node, self._solids, self._obstacles = tree, node, solids, obstacles
        G, O = env_threshold.shape
        self.inside = inside if inside is not None else (
            np.zeros(G + 1, int), np.zeros((0, 3)), np.zeros(0), np.zeros(G, bool), np.zeros(O, bool))
        self.collide_below = collide_below
        self.geometry_ids = list(geometry_ids)
        self._centers, self._radii, self._start = centers, radii, start
        self._count = np.diff(start)
        self._sphere_node = np.repeat(node, self._count)
        self._env_threshold, self._self = env_threshold, self_pairs
        self._aabb_centre, self._aabb_half = obstacles.o, _world_half_extents(obstacles)
        # squared reach of each (moving geometry, obstacle) pair; -1 where Drake does not check the pair
        reach = env_threshold + solids.radius[:, None]
        self._env_reach2 = np.where(np.isfinite(reach), np.maximum(reach, 0.0) ** 2, -1.0)
        self._env_unchecked = np.where(np.isfinite(reach), 0.0, np.inf)
        self._env_clear_offset = np.where(np.isfinite(reach), reach, -np.inf).max(axis=1, initial=0.0)
        self._revolute = tree.kinds != PRISMATIC
        self._path = _joints_up(tree, node)
        # a self pair moves only by the joints below the deepest joint above both its bodies: joints are
        # numbered down the tree, so those numbered from ``cut`` on
        m = len(tree.kinds)
        cut = np.array([max(np.flatnonzero(self._path[g] & self._path[o]), default=-1) + 1
                        for g, o in zip(self_pairs.mover, self_pairs.other)], int)
        self._pair_below = (np.arange(m) >= cut[:, None]).astype(float)  # (pairs, joints)

    def kernel_blocks(self) -> dict:
        """Every array the compiled test needs (lazyground.drake.sphere_kernels.pack's blocks)."""
        tree, solids, obstacles, pairs = self.tree, self._solids, self._obstacles, self._self
        G, O = self._env_threshold.shape
        istart, ic, ir, gexact, oexact = self.inside
        return dict(
            counts=dict(m=len(tree.kinds), n=len(tree.slot), G=G, S=self.spheres, O=O, P=len(pairs.mover), I=len(ir)),
            K=tree.K[:, :3, :], F=tree.F[:, :3, :], gR=solids.R, go=solids.o, ghalf=solids.half,
            ground=solids.rounding, grad=solids.radius, sc=self._centers, sr=self._radii, oR=obstacles.R,
            oo=obstacles.o, ohalf=obstacles.half, oround=obstacles.rounding, ac=self._aabb_centre.T,
            ah=self._aabb_half.T, reach2=self._env_reach2, env=self._env_threshold, self_thr=pairs.threshold,
            ic=ic, ir=ir, below=[self.collide_below], parent=tree.parent, kinds=tree.kinds, index=tree.index,
            slot=tree.slot, node=self._node, start=self._start, gcyl=solids.cylinder, ocyl=obstacles.cylinder,
            mover=pairs.mover, other=pairs.other, istart=istart, gexact=gexact, oexact=oexact)

    @property
    def spheres(self) -> int:
        return len(self._radii)

    @property
    def pairs(self) -> int:
        return int(np.isfinite(self._env_threshold).sum()) + len(self._self.mover)

    def certified_free(self, q_full: np.ndarray) -> np.ndarray:
        """Per plant position vector (rows of ``q_full``): True only if Drake's checker calls it free
        (see :meth:`certify`)."""
        return self.certify(q_full)[0]

    def certify(self, q_full: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(per plant position vector: True only if Drake's checker calls it free; (row, pair) of the
        checked pairs not proven clear at each row that is not, pair an index into :attr:`pair_geometries`).
        Drake's checker calls such a row free exactly when each of its open pairs is farther apart than
        the pair's padding (every other pair it checks is proven to be).

        Each row is bounded on its own, pair by pair (:meth:`clearance`): the test the compiled kernels
        run per row (lazyground.drake.sphere_kernels), in numpy. (Rows bounded from anchor rows through
        their levers, with a rule for far self pairs, were removed in #32: the product checks through the
        kernels only, and no comparison with Drake exercised that rule.)
        """
        clear, _, (row, pair) = self._bounds(q_full, levers=False)
        return clear.min(axis=1) > 0.0, row, pair

    @cached_property
    def pair_geometries(self) -> np.ndarray:
        """(pairs, 2): the pairs of :meth:`certify`, as indices into :attr:`geometry_ids`: (moving geometry,
        obstacle) for every moving geometry and obstacle (obstacles numbered after the moving geometries;
        pairs Drake does not check are never open), then the self pairs."""
        G, O = self._env_threshold.shape
        env = np.stack(np.meshgrid(np.arange(G), G + np.arange(O), indexing="ij"), axis=-1).reshape(-1, 2)
        return np.vstack([env, np.column_stack([self._self.mover, self._self.other])])

    def _pair_levers(self, lever: np.ndarray, k: np.ndarray) -> np.ndarray:
        """Geometry levers (B, geometries, joints) -> those of self pairs ``k`` (B, pairs, joints): the sum
        of their two geometries' over the joints below both bodies (moving both together changes no distance)."""
        return (lever[:, self._self.mover[k]] + lever[:, self._self.other[k]]) * self._pair_below[k]

    def levers(self, q_full: np.ndarray) -> np.ndarray:
        """Per plant position vector, clearance column (:meth:`clearance`) and moving joint (B, columns, joints):
        from q, no point of a column's geometry moves (a self pair's two geometries: relative to each
        other) farther than (|dq| @ levers[c]) * :func:`_growth` (s) on the straight line to q + dq,
        dq over the moving joints (``tree.index``), s the sum of |dq| over the revolute ones.

        A point's speed is at most sum_j |dq_j| rho_j, rho_j its distance from joint j's axis (1 for a
        prismatic joint), and rho_j grows by at most the distance moved so far (M): M' <= a + s M with
        a = sum_j |dq_j| rho_j(q), so M <= a (e^s - 1) / s. A self pair counts only the joints below
        both its bodies: moving both together changes no distance."""
        lever = self._bounds(q_full)[1]
        return np.concatenate([lever, self._pair_levers(lever, np.arange(len(self._self.mover)))], axis=1)

    def clearance(self, q_full: np.ndarray) -> np.ndarray:
        """Lower bounds (B, geometries + self pairs) per plant position vector: per moving geometry, how
        far it can move before a checked pair of it and the never-moving geometry comes within its
        threshold; per self pair, how far its two geometries can move relative to each other before
        they do. All > 0: Drake calls the configuration free."""
        return self._bounds(q_full, levers=False)[0]

    def _bounds(self, q_full: np.ndarray, levers: bool = True):
        """(:meth:`clearance`, and with ``levers`` each moving geometry's lever per joint (B, geometries,
        joints): the farthest distance of its bounding sphere from the joint's axis (1 for a prismatic
        joint, 0 for a joint not above it), (row, pair) of the pairs not proven clear (:meth:`certify`))."""
        q = np.atleast_2d(np.asarray(q_full, float))
        R, p, axis, origin = self.tree.forward(q, joints=True)
        # every moving geometry's solid centre in the world, (B, geometries, 3)
        centre = np.einsum("bgij,gj->bgi", R[:, self._node], self._solids.o) + p[:, self._node]
        env, (b, g, o, threshold) = self._near_obstacles(centre)
        pair_gap, (b_pair, k) = self._near_each_other(centre)
        clear = np.hstack([env, pair_gap])
        G, O = self._env_threshold.shape
        stuck = [self._finer(R, p, centre, clear, b, g, o, threshold, g, moving=False, pair=g * O + o)]
        if len(k):
            g, o = self._self.mover[k], self._self.other[k]
            stuck.append(self._finer(R, p, centre, clear, b_pair, g, o, self._self.threshold[k], G + k, moving=True,
                                     pair=G * O + k))
        if not levers:
            return clear, None, self._open(stuck)
        v = centre[:, :, None] - origin[:, None]  # (B, geometries, joints, 3)
        along = np.einsum("bgjk,bjk->bgj", v, axis)
        rho = np.sqrt(np.maximum(np.einsum("bgjk,bgjk->bgj", v, v) - along ** 2, 0.0)) + self._solids.radius[:, None]
        return clear, np.where(self._revolute, rho, 1.0) * self._path, self._open(stuck)

    def _open(self, stuck: list) -> tuple[np.ndarray, np.ndarray]:
        """(row, pair) from :meth:`_finer`'s pairs that do not clear, each pair once per row, by row."""
        n = len(self._env_threshold.reshape(-1)) + len(self._self.mover)
        key = np.unique(np.concatenate([b * n + pair for b, pair in stuck]))
        return np.divmod(key, n)

    def _near_obstacles(self, centre: np.ndarray):
        """(per configuration and geometry: the clearance of the pairs far from the obstacles' world boxes,
        (b, g, o, threshold) of the other pairs)."""
        shape = centre.shape[:2] + self._aabb_half.shape[:1]
        gap2, d = np.zeros(shape), np.empty(shape)  # in place: temporaries of this size cost more than the arithmetic
        for k in range(3):  # distance from each moving centre to each obstacle's axis-aligned box, squared
            np.subtract(centre[:, :, k, None], self._aabb_centre[:, k], out=d)
            np.abs(d, out=d)
            d -= self._aabb_half[:, k]
            np.maximum(d, 0.0, out=d)
            d *= d
            gap2 += d
        near = gap2 <= self._env_reach2
        b, g, o = np.nonzero(near)
        gap2[near] = np.inf
        gap2 += self._env_unchecked  # inf for pairs Drake does not check
        # the nearest far obstacle, less the largest radius + threshold of the geometry's pairs: a lower bound
        return np.sqrt(gap2.min(axis=2)) - self._env_clear_offset, (b, g, o, self._env_threshold[g, o])

    def _near_each_other(self, centre: np.ndarray):
        """(per configuration and self pair (B, pairs): the gap of the pairs whose bounding spheres are
        apart, inf for the others; (b, pair) of the others)."""
        g, o = self._self.mover, self._self.other
        v = centre[:, g] - centre[:, o]
        gap = np.sqrt(np.einsum("bki,bki->bk", v, v)) - self._solids.radius[g] - self._solids.radius[o]
        gap -= self._self.threshold
        near = gap <= 0.0
        b, k = np.nonzero(near)
        gap[near] = np.inf
        return gap, (b, k)

    def _finer(self, R, p, centre, clear, b, g, o, threshold, column, moving: bool, pair: np.ndarray):
        """Lowers ``clear[b, column]`` by the pairs (b, g, o): the moving geometry's bounding sphere against
        the other solid, then, where that comes within ``threshold``, sphere by sphere. Returns (b, pair) of
        the pairs (``pair``: each one's index) whose bound does not clear ``threshold`` (once per sphere)."""
        if not len(b):
            return np.zeros(0, int), np.zeros(0, int)
        R_WG, o_W, solids = self._other_pose(R, p, b, o, moving)
        gap = self._distance(centre[b, g], R_WG, o_W, solids, o) - self._solids.radius[g] - threshold
        near = gap <= 0.0
        _lower(clear, b[~near], column[~near], gap[~near])
        b, g, o, threshold, column = b[near], g[near], o[near], threshold[near], column[near]
        R_WG, o_W = R_WG[near], o_W[near]
        row, sphere = _ranges(self._start[g], self._count[g])
        bs, ns = b[row], self._sphere_node[sphere]
        c = np.einsum("nij,nj->ni", R[bs, ns], self._centers[sphere]) + p[bs, ns]
        gap = self._distance(c, R_WG[row], o_W[row], solids, o[row]) - self._radii[sphere] - threshold[row]
        _lower(clear, bs, column[row], gap)
        stuck = gap <= 0.0
        return bs[stuck], pair[near][row[stuck]]

    def _other_pose(self, R, p, b, o, moving: bool):
        """World pose (R_WG, centre) of the other side of pairs at configurations b, and its solids."""
        if not moving:
            return self._obstacles.R[o], self._obstacles.o[o], self._obstacles
        s, n = self._solids, self._node[o]
        return np.einsum("nij,njk->nik", R[b, n], s.R[o]), np.einsum("nij,nj->ni", R[b, n], s.o[o]) + p[b, n], s

    @staticmethod
    def _distance(points, R_WG, o_W, solids: _Solids, o) -> np.ndarray:
        """Signed distance from world points to solids ``o`` posed at (R_WG, o_W), one per point."""
        x = np.einsum("nji,nj->ni", R_WG, points - o_W)
        return solid_distance(x, solids.half[o], solids.rounding[o], solids.cylinder[o])


def _lower(clear: np.ndarray, b: np.ndarray, column: np.ndarray, gap: np.ndarray) -> None:
    """clear[b, column] = min(clear[b, column], gap), repeated indices included."""
    np.minimum.at(clear.reshape(-1), b * clear.shape[1] + column, gap)  # a view: ufunc.at is fast on one flat index


def _growth(s: np.ndarray) -> np.ndarray:
    """(e^s - 1) / s <= 1 + s for 0 <= s <= 1 (see SphereCertifier.levers); inf beyond."""
    return np.where(s <= 1.0, 1.0 + s, np.inf)


def _ranges(starts: np.ndarray, counts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For ranges start_i .. start_i + count_i - 1: (the range each index belongs to, the index), concatenated."""
    owner = np.repeat(np.arange(len(counts)), counts)
    offset = np.arange(int(counts.sum())) - np.repeat(np.cumsum(counts) - counts, counts)
    return owner, np.repeat(starts, counts) + offset


def sphere_certifier(checker, margin: float = MARGIN, slack: float = SLACK) -> SphereCertifier | None:
    """The certifier of a SceneGraphCollisionChecker, or None when this world cannot be bounded soundly.

    Args:
        checker: Drake's checker (its robot, filters and paddings are read once; lazyground never changes them).
        margin: metres beyond a pair's padding a lower bound must clear.
        slack: metres a cover's spheres may reach beyond their shape.

    Returns:
        The certifier; None for a joint that is neither revolute, prismatic nor welded, a
        moving environment body, a shape without a solid, or a pair of never-moving
        geometries that Drake finds in collision.
    """
    plant = checker.plant()
    inspector = checker.model().scene_graph().model_inspector()
    geometries = [g for g in inspector.GetAllGeometryIds() if inspector.GetProximityProperties(g) is not None]
    body = {g: plant.GetBodyFromFrameId(inspector.GetFrameId(g)) for g in geometries}
    world = plant.world_body().index()
    try:
        tree = body_tree(plant, [body[g] for g in geometries if body[g].index() != world])
    except ValueError:
        return None
    node = {b: k for k, b in enumerate(tree.bodies)}
    fixed = tree.fixed
    moving = [g for g in geometries if body[g].index() != world and not fixed[node[body[g].index()]]]
    if any(not checker.IsPartOfRobot(body[g]) for g in moving):
        return None  # an environment body that moves
    still = [g for g in geometries if g not in set(moving)]
    X_BG = {g: inspector.GetPoseInFrame(g).GetAsMatrix4() for g in geometries}
    try:
        covers = [cover(inspector.GetShape(g), slack) for g in moving]
        solids = _Solids.of([inspector.GetShape(g) for g in moving], [X_BG[g] for g in moving])
        X_W = _fixed_poses(tree, node, plant.num_positions())
        obstacles = _Solids.of([inspector.GetShape(g) for g in still], [X_W.get(body[g].index(), np.eye(4)) @ X_BG[g] for g in still])
    except ValueError:
        return None
    env, self_pairs, welded = _checked_pairs(checker, inspector, body, moving, still, [len(r) for _, r in covers], margin)
    if _welded_pair_collides(checker, welded):
        return None
    start, centers, radii = _in_bodies(covers, [X_BG[g] for g in moving])
    nodes = np.array([node[body[g].index()] for g in moving], int)
    # a collision is claimed below the pair's padding - margin: threshold (max(padding, 0) + margin) - 2 margin,
    # so only where no padding is negative
    collide_below = 2 * margin if checker.GetPaddingMatrix().min() >= 0.0 else np.inf
    inside = _in_bodies([inner(inspector.GetShape(g)) for g in moving], [X_BG[g] for g in moving]) + (
        np.array([exact(inspector.GetShape(g)) for g in moving], bool), np.array([exact(inspector.GetShape(g)) for g in still], bool))
    return SphereCertifier(tree, nodes, solids, centers, radii, start, obstacles, env, self_pairs, moving + still,
                           inside, collide_below)


def _in_bodies(spheres: list, X_BG: list) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(start, centres in the body frames, radii) of per-geometry spheres given in the geometries' frames."""
    start = np.concatenate([[0], np.cumsum([len(r) for _, r in spheres])]).astype(int)
    centers = np.vstack([c @ X[:3, :3].T + X[:3, 3] for X, (c, _) in zip(X_BG, spheres)] + [np.zeros((0, 3))])
    return start, centers, np.concatenate([r for _, r in spheres] + [np.zeros(0)])


def _joints_up(tree: BodyTree, nodes: np.ndarray) -> np.ndarray:
    """(nodes, moving joints): whether the joint lies between each node's body and the world."""
    path = np.zeros((len(nodes), len(tree.kinds)), bool)
    for g, k in enumerate(nodes):
        slot = tree.slot[k]
        while slot > 0:
            path[g, slot - 1] = True
            slot = tree.parent[slot - 1]
    return path


def _checked_pairs(checker, inspector, body, moving, still, spheres, margin):
    """The pairs Drake's checker checks, as (env thresholds, self pairs, never-moving pairs (id, id, threshold)).

    A self pair's moving side is the geometry with fewer spheres; the other is taken as a solid.
    """
    m_index, s_index = {g: i for i, g in enumerate(moving)}, {g: i for i, g in enumerate(still)}
    padding = checker.GetPaddingMatrix()
    env = np.full((len(moving), len(still)), -np.inf)
    self_pairs, welded = ([], [], []), []
    for ga, gb in inspector.GetCollisionCandidates():
        A, B = body[ga], body[gb]
        if not (checker.IsPartOfRobot(A) or checker.IsPartOfRobot(B)) or checker.IsCollisionFilteredBetween(A, B):
            continue  # pairs Drake's checker skips
        threshold = max(padding[int(A.index()), int(B.index())], 0.0) + margin
        if ga in m_index and gb in m_index:
            a, b = sorted((m_index[ga], m_index[gb]), key=lambda i: spheres[i])
            for column, v in zip(self_pairs, (a, b, threshold)):
                column.append(v)
        elif ga in m_index or gb in m_index:
            g, o = (ga, gb) if ga in m_index else (gb, ga)
            env[m_index[g], s_index[o]] = threshold
        else:
            welded.append((ga, gb, threshold))
    return env, _Pairs(np.array(self_pairs[0], int), np.array(self_pairs[1], int), np.array(self_pairs[2], float)), welded


def _world_half_extents(solids: _Solids) -> np.ndarray:
    """Half extents of each solid's world-axis-aligned box (about its centre)."""
    A = np.abs(solids.R)
    box = np.einsum("nij,nj->ni", A, solids.half)
    axis = solids.R[:, :, 2]  # a cylinder: its caps' extent along the axis, its rims' across
    cyl = A[:, :, 2] * solids.half[:, 2, None] + solids.half[:, 0, None] * np.sqrt(np.clip(1 - axis ** 2, 0.0, None))
    return np.where(solids.cylinder[:, None], cyl, box) + solids.rounding[:, None]


def _fixed_poses(tree: BodyTree, node: dict, num_positions: int) -> dict:
    """World poses of the tree's bodies at q = 0 (the never-moving ones' poses at every q), by BodyIndex."""
    R, p = tree.forward(np.zeros(num_positions))
    out = {}
    for b, k in node.items():
        out[b] = np.eye(4)
        out[b][:3, :3], out[b][:3, 3] = R[0, k], p[0, k]
    return out


def _welded_pair_collides(checker, pairs) -> bool:
    """Whether Drake finds any of these pairs (poses that never change) within its threshold."""
    if not pairs:
        return False
    query = checker.model_context().GetQueryObject()
    close = {}
    for p in query.ComputeSignedDistancePairwiseClosestPoints(max(t for _, _, t in pairs)):
        close[p.id_A, p.id_B] = close[p.id_B, p.id_A] = p.distance
    return any(close.get((a, b), np.inf) <= t for a, b, t in pairs)
