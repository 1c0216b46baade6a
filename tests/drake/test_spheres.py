"""The sphere certifier (#16, #19): never certifies what Drake calls colliding, covers enclose their shapes,
and the checker's answers stay Drake's."""

import textwrap
from pathlib import Path

import numpy as np
import pytest
from numba import njit

pytest.importorskip("pydrake")

from pydrake.geometry import Box, Capsule, Cylinder, Ellipsoid, Sphere  # noqa: E402

from lazyground.bench.moveit_corpus import CORPUS  # noqa: E402
from lazyground.drake import sphere_kernels  # noqa: E402
from lazyground.drake.chain import PRISMATIC, body_tree  # noqa: E402
from lazyground.drake.solids import cover, solid, solid_distance  # noqa: E402
from lazyground.drake.spheres import _growth  # noqa: E402
from lazyground.drake.world import Attachment, DrakeWorld  # noqa: E402
from lazyground.geometry import Pose  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402
from tests.unit.test_scene_meshes_and_robot_fill import FETCH  # noqa: E402

SCENES = sorted(p.stem for p in Path("yaml_scenes").glob("*.yaml"))
ARMS = [s for s in SCENES if not s.startswith("parking")]


def _drake_free(world, q_full: np.ndarray) -> np.ndarray:
    return np.asarray(world.checker.drake.CheckConfigsCollisionFree(list(q_full), parallelize=False), bool)


def _near_contact(world, rng, n_pairs: int, steps: int = 16) -> np.ndarray:
    """Configurations from bisecting free-colliding pairs down to ~1e-4 rad: many within the padding."""
    qs = world.full(np.array([world.space.sample(rng) for _ in range(4 * n_pairs)]))
    free = _drake_free(world, qs)
    a, b = qs[free][:n_pairs], qs[~free][:n_pairs]
    n = min(len(a), len(b))
    a, b, out = a[:n], b[:n], []
    for _ in range(steps):
        mid = (a + b) / 2
        ok = _drake_free(world, mid)
        a[ok], b[~ok] = mid[ok], mid[~ok]
        out.append(mid)
    return np.vstack(out + [a, b])


def _dense_paths(world, rng, n: int, steps: int = 120) -> np.ndarray:
    """Rows along straight segments between random configurations, in order (as a path's fine re-check asks)."""
    a = np.array([world.space.sample(rng) for _ in range(n)])
    b = np.array([world.space.sample(rng) for _ in range(n)])
    t = np.linspace(0.0, 1.0, steps)[None, :, None]
    return world.full((a[:, None] + t * (b - a)[:, None]).reshape(-1, a.shape[1]))


def _rows_through_contact(world, rng, n: int) -> np.ndarray:
    """Rows 0.01 rad apart (twice the fine re-check's step), in order, along n segments in random
    directions through configurations within ~1e-4 rad of contact (the free ends of the bisections)."""
    near = _near_contact(world, rng, n)
    near = near[-2 * len(near) // 18: -len(near) // 18]  # 18 blocks: 16 halvings, then the free and colliding ends
    planned = list(world.coordinates.planned)
    u = rng.normal(size=(len(near), len(planned)))
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    t = (np.arange(160) - 80) * 0.01
    rows = np.repeat(near[:, None], len(t), axis=1)
    rows[:, :, planned] += t[None, :, None] * u[:, None]
    return rows.reshape(-1, near.shape[1])


def _assert_sound(world, q_full: np.ndarray) -> np.ndarray:
    """The certifier proves only Drake-free configurations; the checker answers as Drake. Returns the certified mask."""
    certified = world.checker.certifier.certified_free(q_full)
    drake = _drake_free(world, q_full)
    assert int((certified & ~drake).sum()) == 0
    planned = q_full[:, list(world.coordinates.planned)]
    assert np.array_equal(world.configs_free(planned), drake)
    return certified


@pytest.mark.parametrize("scene", ARMS)
def test_never_certifies_a_colliding_configuration(scene):
    world = DrakeWorld(load_scene(f"yaml_scenes/{scene}.yaml"), visual=False)
    assert world.checker.certifier is not None
    rng = np.random.default_rng(7)
    random = world.full(np.array([world.space.sample(rng) for _ in range(3000)]))
    near = _near_contact(world, rng, 150)
    certified = _assert_sound(world, np.vstack([random, near]))
    dense = _dense_paths(world, rng, 20)
    assert 0 < _assert_sound(world, dense).sum() < len(dense)
    through = _rows_through_contact(world, rng, 15)
    assert 0 < _assert_sound(world, through).sum() < len(through)
    drake = _drake_free(world, random)
    assert certified[: len(random)].sum() > 0.3 * drake.sum()  # it proves a good share, so soundness means something
    # near contact: within 0.5 mm of the boundary the certifier must leave the call to Drake
    assert 0 < _drake_free(world, near).sum() < len(near)


def test_a_carried_object_and_mesh_obstacles_are_bounded(tmp_path):
    scene = load_scene("yaml_scenes/fetch_put_box_on_table.yaml")
    obj = next(o for o in scene.objects if o.geometry.box)
    carrying = DrakeWorld(scene, visual=False, attached=Attachment(obj, "gripper_link", Pose((0.15, 0.0, 0.0), (0.0, 0.0, 0.0))))
    rng = np.random.default_rng(3)
    qs = carrying.full(np.array([carrying.space.sample(rng) for _ in range(1500)]))
    assert _assert_sound(carrying, np.vstack([qs, _near_contact(carrying, rng, 100)])).any()
    path = tmp_path / "s.yaml"
    path.write_text(textwrap.dedent(f"""
        name: m
        robot: {FETCH}
        obstacles: [{{id: block, geometry: {{mesh: {{file: {CORPUS / "meshes/fridge.stl"}}}}}, pose: {{xyz: [0.9, 0, 0]}}}}]
    """))
    meshed = DrakeWorld(load_scene(str(path)), visual=False)
    assert meshed.checker.certifier is not None
    qs = meshed.full(np.array([meshed.space.sample(rng) for _ in range(1500)]))
    assert _assert_sound(meshed, np.vstack([qs, _near_contact(meshed, rng, 100)])).any()


@pytest.mark.parametrize("scene", [s for s in SCENES if s.startswith("parking")])
def test_a_car_is_left_to_drake(scene):
    world = DrakeWorld(load_scene(f"yaml_scenes/{scene}.yaml"), visual=False)
    assert world.checker.certifier is None  # a planar joint: no body tree
    rng = np.random.default_rng(0)
    qs = np.array([world.space.sample(rng) for _ in range(64)])
    assert np.array_equal(world.configs_free(qs), _drake_free(world, world.full(qs)))


def test_dense_rows_near_self_collision_stay_sound(tmp_path):
    """A Fetch alone (every collision a self collision): rows 0.01 rad apart (twice the fine re-check's step)
    along segments through near-contact configurations, as a path's fine re-check asks; no Drake-colliding row
    is certified."""
    path = tmp_path / "alone.yaml"
    path.write_text(f"name: alone\nrobot: {FETCH}\nobstacles: []\n")
    world = DrakeWorld(load_scene(str(path)), visual=False)
    rows = _rows_through_contact(world, np.random.default_rng(11), 40)
    drake = _drake_free(world, rows)
    assert 0 < drake.sum() < len(rows)  # the segments cross the boundary
    certified = _assert_sound(world, rows)
    assert certified.sum() > 0.3 * drake.sum()


def _cover_centres(cert, qs: np.ndarray) -> np.ndarray:
    """Every cover sphere's centre in the world (B, spheres, 3): points of the geometry's bounding sphere."""
    R, p = cert.tree.forward(qs)
    n = cert._sphere_node
    return np.einsum("bsij,sj->bsi", R[:, n], cert._centers) + p[:, n]


def test_no_point_moves_farther_than_its_levers_allow():
    """Per geometry, sphere centres move no farther than the levers at q allow; per self pair, the distance
    between the two geometries' sphere centres changes no more than the pair's relative bound, which counts
    only the joints below both bodies."""
    world = DrakeWorld(load_scene("yaml_scenes/fetch_cans_1.yaml"), visual=False)
    cert = world.checker.certifier
    rng = np.random.default_rng(2)
    q = world.full(np.array([world.space.sample(rng) for _ in range(300)]))
    moving = np.zeros(q.shape[1], bool)
    moving[cert.tree.index] = True
    q2 = q + rng.normal(0.0, 0.1, q.shape) * moving
    dq = np.abs(q2 - q)[:, cert.tree.index]
    s = dq[:, cert._revolute].sum(axis=1)
    assert (s <= 1.0).mean() > 0.5  # most pairs within the bound's range (beyond it the bound is inf)
    bound = np.einsum("bj,bcj->bc", dq, cert.levers(q)) * _growth(s)[:, None]
    a, b = _cover_centres(cert, q), _cover_centres(cert, q2)
    owner = np.repeat(np.arange(len(cert._count)), cert._count)
    G = len(cert._count)
    moved = np.linalg.norm(b - a, axis=-1)
    assert np.all(moved <= bound[:, owner] + 1e-12)
    ok = s <= 1.0
    assert np.max(moved[ok] / bound[ok][:, owner]) > 0.3  # the bound is not vacuous
    first = np.concatenate([[0], np.cumsum(cert._count)])
    tight, gained = 0.0, 0
    for k, (g, o) in enumerate(zip(cert._self.mover, cert._self.other)):
        ig, io = np.arange(first[g], first[g + 1]), np.arange(first[o], first[o + 1])
        dist = lambda c: np.linalg.norm(c[:, ig, None] - c[:, None, io], axis=-1)  # noqa: E731
        change = np.abs(dist(b) - dist(a)).max(axis=(1, 2))
        assert np.all(change <= bound[:, G + k] + 1e-12), (g, o)
        tight = max(tight, float(np.max(change[ok] / bound[ok, G + k])))
        gained += bool(np.all(bound[ok, G + k] < bound[ok, g] + bound[ok, o] - 1e-9))
    assert tight > 0.3
    assert gained > len(cert._self.mover) / 2  # most pairs share joints above them that the relative bound leaves out


@njit
def _kernel_levers(q, fd, idata, work, above, lever, pair_lever):
    """The levers the compiled sweep takes at an anchor q (sphere_kernels.sweep_rows): its _clearance, _pair_levers."""
    Rs, ps, Rb, pb, centre, sph, done, W, A, gap = sphere_kernels.scratch_views(idata, work)
    tree, blocks = sphere_kernels.tree_views(fd, idata), sphere_kernels.block_views(fd, idata)
    clear_g, clear_k = np.empty(lever.shape[0]), np.empty(pair_lever.shape[0])
    sphere_kernels._clearance(q, idata, tree, blocks, Rs, ps, Rb, pb, centre, W, gap[1], above, lever, clear_g, clear_k)
    sphere_kernels._pair_levers(blocks, above, lever, pair_lever)


@pytest.mark.parametrize("scene", ["fetch_cans_1", "panda_tabletop"])
def test_the_compiled_sweep_s_levers_are_the_reference_s(scene):
    """The levers the sweep proves rows from (sphere_kernels) are :meth:`SphereCertifier.levers`, whose bound the
    test above checks against the motion of every sphere: per geometry and per self pair, at random configurations
    (Fetch's torso joint is prismatic)."""
    world = DrakeWorld(load_scene(f"yaml_scenes/{scene}.yaml"), visual=False)
    cert, compiled = world.checker.certifier, world.checker.compiled
    rng = np.random.default_rng(4)
    q = world.full(np.array([world.space.sample(rng) for _ in range(100)]))
    want = cert.levers(q)
    G, P, m = len(cert._count), len(cert._self.mover), len(cert.tree.kinds)
    assert P and (cert.tree.kinds == PRISMATIC).any() == (scene == "fetch_cans_1")
    lever, pair_lever = np.empty((G, m)), np.empty((P, m))
    for b in range(len(q)):
        _kernel_levers(q[b], compiled.fd, compiled.idata, compiled.work, compiled._above, lever, pair_lever)
        # (a centre on a joint's axis: sqrt(|v|^2 - along^2) of a difference of two ~1 m^2 roundings, ~1e-8 m)
        np.testing.assert_allclose(np.vstack([lever, pair_lever]), want[b], rtol=0.0, atol=1e-7)
    assert (want[:, G:] == 0).any() and (want[:, G:] > 0).any()  # pairs share joints and move by others


def test_the_growth_factor_bounds_the_distance_moved_from_the_lever_at_q():
    """levers(): a point moved along a straight joint line with total revolute motion s is at most a (e^s - 1) / s
    away, a its speed bound at q; _growth must be at least (e^s - 1) / s wherever it is finite (a smaller factor,
    such as 1 + s / 2, certifies rows whose geometry may have moved into an obstacle)."""
    s = np.linspace(1e-6, 1.0, 2001)
    assert np.all(_growth(s) >= np.expm1(s) / s)
    assert _growth(np.array([0.0]))[0] >= 1.0 and np.isinf(_growth(np.array([1.0 + 1e-9, 3.0]))).all()


def test_the_body_tree_matches_the_plant():
    world = DrakeWorld(load_scene("yaml_scenes/panda_tabletop.yaml"), visual=False)
    plant = world.plant
    tree = body_tree(plant, [plant.get_body(b) for b in plant.GetBodyIndices(world.robot)])
    rng = np.random.default_rng(1)
    qs = world.full(np.array([world.space.sample(rng) for _ in range(5)]))
    R, p = tree.forward(qs)
    context = plant.CreateDefaultContext()
    for i, q in enumerate(qs):
        plant.SetPositions(context, q)
        for k, b in enumerate(tree.bodies):
            X = plant.EvalBodyPoseInWorld(context, plant.get_body(b)).GetAsMatrix4()
            assert np.allclose(X[:3, :3], R[i, k], atol=1e-12) and np.allclose(X[:3, 3], p[i, k], atol=1e-12)


def _surface(shape, rng, n: int) -> np.ndarray:
    """Points on the surface of a shape (and, for a box, its corners), in its frame."""
    if isinstance(shape, Box):
        h = np.asarray(shape.size()) / 2
        x = rng.uniform(-h, h, (n, 3))
        axis = rng.integers(0, 3, n)
        x[np.arange(n), axis] = h[axis] * rng.choice([-1, 1], n)
        corners = np.array(np.meshgrid(*[[-v, v] for v in h], indexing="ij")).reshape(3, -1).T
        return np.vstack([x, corners])
    if isinstance(shape, Sphere):
        u = rng.normal(size=(n, 3))
        return shape.radius() * u / np.linalg.norm(u, axis=1, keepdims=True)
    if isinstance(shape, Ellipsoid):
        u = rng.normal(size=(n, 3))
        return u / np.linalg.norm(u, axis=1, keepdims=True) * [shape.a(), shape.b(), shape.c()]
    r, half = shape.radius(), shape.length() / 2
    t = rng.uniform(0, 2 * np.pi, n)
    z = rng.uniform(-half, half, n)
    side = np.column_stack([r * np.cos(t), r * np.sin(t), z])
    if isinstance(shape, Capsule):
        u = rng.normal(size=(n, 3))
        u = r * u / np.linalg.norm(u, axis=1, keepdims=True)
        u[:, 2] = np.abs(u[:, 2])  # the outer half of each end sphere
        return np.vstack([side, u + [0, 0, half], -u - [0, 0, half]])
    rho = r * np.sqrt(rng.uniform(0, 1, n))
    cap = np.column_stack([rho * np.cos(t), rho * np.sin(t), rng.choice([-half, half], n)])
    rim = np.column_stack([r * np.cos(t), r * np.sin(t), rng.choice([-half, half], n)])
    return np.vstack([side, cap, rim])


SHAPES = [Box(0.25, 0.3, 0.6), Box(0.06, 0.014, 0.034), Box(1.0, 0.02, 0.5), Cylinder(0.05, 0.16), Cylinder(0.28, 0.37),
          Cylinder(0.03, 1.2), Capsule(0.04, 0.3), Sphere(0.07), Ellipsoid(0.1, 0.2, 0.05)]


@pytest.mark.parametrize("shape", SHAPES, ids=lambda s: f"{type(s).__name__}")
def test_a_cover_encloses_its_shape_and_the_solid_distance_is_a_lower_bound(shape):
    rng = np.random.default_rng(5)
    points = _surface(shape, rng, 4000)
    centres, radii = cover(shape, slack=0.015)
    inside = np.linalg.norm(points[:, None] - centres[None], axis=-1) <= radii[None] + 1e-12
    assert inside.any(axis=1).all()
    centre, half, rounding, cylinder = solid(shape)
    d = solid_distance(points - centre, half, np.full(len(points), rounding), np.full(len(points), cylinder))
    assert d.max() <= 1e-12  # every surface point is in the solid
    exact = not isinstance(shape, Ellipsoid)
    if exact:  # points on the surface of an exact solid are on its boundary
        assert d.min() >= -1e-12
    far = rng.normal(size=(500, 3)) * 2
    d_far = solid_distance(far - centre, half, np.full(500, rounding), np.full(500, cylinder))
    nearest = np.linalg.norm(far[:, None] - points[None], axis=-1).min(axis=1)  # an upper bound of the true distance
    assert np.all(d_far <= nearest + 1e-12)


def test_every_pair_drake_finds_within_its_padding_is_left_open(tmp_path):
    """certify's open pairs hold every checked pair Drake finds within its padding (so asking SceneGraph about
    them alone gives Drake's answer), at rows through near-contact configurations with and without obstacles."""
    alone = tmp_path / "alone.yaml"
    alone.write_text(f"name: alone\nrobot: {FETCH}\nobstacles: []\n")
    for path in ("yaml_scenes/fetch_cans_1.yaml", str(alone)):
        world = DrakeWorld(load_scene(path), visual=False)
        cert, drake = world.checker.certifier, world.checker.drake
        index = {}
        for k, (a, b) in enumerate(cert.pair_geometries):
            index[cert.geometry_ids[a], cert.geometry_ids[b]] = index[cert.geometry_ids[b], cert.geometry_ids[a]] = k
        rows = _rows_through_contact(world, np.random.default_rng(3), 6)
        free, row, pair = cert.certify(rows)
        query, plant = world.checker._query, drake.plant()
        inspector = drake.model().scene_graph().model_inspector()
        body = lambda g: plant.GetBodyFromFrameId(inspector.GetFrameId(g))  # noqa: E731
        found = 0
        for i, q in enumerate(rows):
            drake.UpdatePositions(q)
            close = {index[p.id_A, p.id_B] for p in query.ComputeSignedDistancePairwiseClosestPoints(drake.GetLargestPadding())
                     if not drake.IsCollisionFilteredBetween(body(p.id_A), body(p.id_B))
                     and p.distance <= drake.GetPaddingBetween(body(p.id_A), body(p.id_B))}
            assert not (free[i] and close)
            assert close <= set(pair[row == i])
            found += bool(close)
        assert 0 < found < len(rows)
