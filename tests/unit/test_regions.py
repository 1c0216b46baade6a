"""Goal regions as classes: registry by kind, sampling, JSON, drawing, and goal sources looked up by kind."""

from dataclasses import dataclass
from textwrap import dedent

import numpy as np
import pytest
from scipy.spatial.transform import Rotation
from hypothesis import given, settings
from hypothesis import strategies as st

from lazyground.scene.types import occupant_geometry
from lazyground import goals
from lazyground.geometry import Pose, wrap_angle
from lazyground.goals import ConfigGoalSource, goal_source_for, register_goal_source
from lazyground.regions import REGION_KINDS, ConfigRegion, GoalRegion, PlacementRegion, RegionDrawing, WorkspaceRegion, register_region
from lazyground.regions import base as regions_base
from lazyground.scene import parse_scene
from tests.unit.toy import SPACE, WALLS, BoxWorld

LOT = dedent("""
    name: lot
    robot: {model: car, start: {}}
    objects:
      - {id: spot_1, type: parking_spot, geometry: {box: [5.0, 2.5, 0.05]}, pose: {xyz: [10, 5, 0], rpy: [0, 0, 1.5708]}}
      - {id: spot_2, type: parking_spot, occupied: true, geometry: {box: [5.0, 2.5, 0.05]}, pose: {xyz: [10, 8, 0]}}
      - {id: spot_3, type: parking_spot, occupied: true, occupant: {box: [3.0, 1.5, 1.2]}, geometry: {box: [5.0, 2.5, 0.05]}, pose: {xyz: [10, 11, 0]}}
""")


def _pose_fields():
    return dict(interpretation="pick:c", object="c", lower=(-0.1, 0, 0.2, -np.pi, 0, 0), upper=(0.1, 0, 0.2, np.pi, 0, 0),
                X_WR=Pose((1.0, 2.0, 0.5), (0.0, np.pi / 2, 0.3)), X_SE=Pose((-0.05, 0.0, 0.0)))


def test_every_kind_has_one_class_and_make_builds_it():
    assert REGION_KINDS == {"config": ConfigRegion, "workspace": WorkspaceRegion, "placement": PlacementRegion}
    r = GoalRegion.make("config", id="a", interpretation="i", object="a", lower=(0.0,), upper=(1.0,))
    assert type(r) is ConfigRegion and r.kind == "config"
    with pytest.raises(ValueError, match="unknown goal region kind 'cone'"):
        GoalRegion.make("cone", id="a", interpretation="i", object="a", lower=(0.0,), upper=(1.0,))
    with pytest.raises(ValueError, match="x, y, z, roll, pitch, yaw"):
        WorkspaceRegion(id="w", interpretation="i", object="o", lower=(0, 0), upper=(1, 1))


def test_config_sampling_wraps_and_stays_inside():
    r = ConfigRegion(id="s/forwards", interpretation="park:s", object="s", lower=(0.0, 0.0, 3.0), upper=(1.0, 1.0, -3.0), wrap=(2,))
    rng = np.random.default_rng(7)
    for _ in range(200):
        v = r.sample(rng)
        assert r.contains(v) and -np.pi <= v[2] < np.pi
        assert abs(v[2]) >= 3.0 - 1e-12  # the short arc across pi, never through 0
    assert not r.contains(np.array([0.5, 0.5, 0.0]))


def test_samples_are_the_uniform_draws_mapped_onto_the_bounds():
    """A sample is lower + u * (upper - lower) for the generator's next uniform draws u (worked out here, not by
    sampling twice), wrapped across pi where the axis is an angle; the mean of many lies at the box centre."""
    u = np.random.default_rng(3).random(3)
    c = ConfigRegion(id="c", interpretation="i", object="c", lower=(0.0, -1.0, 3.0), upper=(1.0, 1.0, -3.0), wrap=(2,))
    want = np.array([u[0], -1.0 + 2.0 * u[1], 3.0 + u[2] * (2 * np.pi - 6.0)])
    want[2] = want[2] - 2 * np.pi if want[2] >= np.pi else want[2]
    assert np.allclose(c.sample(np.random.default_rng(3)), want, atol=1e-12)
    w = WorkspaceRegion(id="w", frame="ee", **_pose_fields())
    u6 = np.random.default_rng(3).random(6)
    assert np.allclose(w.sample(np.random.default_rng(3)), [-0.1 + 0.2 * u6[0], 0, 0.2, -np.pi + 2 * np.pi * u6[3], 0, 0])
    many = np.array([c.sample(np.random.default_rng(s))[:2] for s in range(400)])
    assert np.allclose(many.mean(axis=0), [0.5, 0.0], atol=0.1)


@pytest.mark.parametrize("lower, upper", [(-2.0, 2.0), (-1.0, 2.5), (0.5, -0.5), (2.0, 1.9), (-3.0, 0.3), (2.5, 0.0)])
def test_wrapped_arcs_wider_than_pi_contain_their_own_samples(lower, upper):
    """An arc wider than pi (crossing pi or not) holds every sample it draws, and rejects the middle of its gap."""
    r = ConfigRegion(id="a", interpretation="i", object="a", lower=(lower,), upper=(upper,), wrap=(0,))
    width = (upper - lower) % (2 * np.pi)
    assert width > np.pi
    rng = np.random.default_rng(11)
    assert all(r.contains(r.sample(rng)) for _ in range(300))
    gap_middle = upper + (2 * np.pi - width) / 2
    assert not r.contains([gap_middle]) and not r.contains([gap_middle - 2 * np.pi])


@settings(max_examples=100, deadline=None, derandomize=True)
@given(st.floats(-np.pi, np.pi), st.floats(1e-3, 2 * np.pi - 1e-2), st.integers(0, 2**32 - 1))
def test_any_wrapped_arc_contains_its_own_samples(lower, width, seed):
    """Property: for every arc (lower, width), wrapped widths above pi included, samples lie in the region."""
    upper = float(wrap_angle(lower + width))
    r = ConfigRegion(id="a", interpretation="i", object="a", lower=(lower,), upper=(upper,), wrap=(0,))
    rng = np.random.default_rng(seed)
    assert all(r.contains(r.sample(rng)) for _ in range(20))
    # the middle of the gap is out
    assert not r.contains([lower + width + (2 * np.pi - width) / 2])


def test_wrapped_bounds_minus_two_to_two_contain_zero():
    r = ConfigRegion(id="a", interpretation="i", object="a", lower=(-2.0,), upper=(2.0,), wrap=(0,))
    assert r.contains([0.0]) and r.contains([1.99]) and r.contains([-1.99])
    assert not r.contains([3.0]) and not r.contains([np.pi]) and not r.contains([-2.2])


@pytest.mark.parametrize("wrap", [(), (0,)])
def test_contains_allows_tol_beyond_either_bound_and_no_more(wrap):
    """Bounds are kept within ``tol`` on every axis, wrapped or not: 0.5 tol outside is in, 2 tol outside is out."""
    for lo, hi in [(-1.0, 0.5), (0.2, 3.1)]:
        r = ConfigRegion(id="a", interpretation="i", object="a", lower=(lo,), upper=(hi,), wrap=wrap)
        tol = 1e-4
        assert r.contains([hi + 0.5 * tol], tol) and r.contains([lo - 0.5 * tol], tol)
        assert not r.contains([hi + 2 * tol], tol) and not r.contains([lo - 2 * tol], tol)
        assert r.contains([hi + 0.5e-6]) and not r.contains([hi + 2e-6])  # the default tol, 1e-6


def test_full_circle_wrapped_axis_contains_every_angle():
    r = ConfigRegion(id="a", interpretation="i", object="a", lower=(-np.pi,), upper=(np.pi,), wrap=(0,))
    assert all(r.contains([a]) for a in np.linspace(-4, 4, 17))


def test_pose_coordinates_invert_pose_in_world():
    r = WorkspaceRegion(id="w", frame="ee", **_pose_fields())
    rng = np.random.default_rng(1)
    for _ in range(20):
        v = r.sample(rng)
        back = r.coordinates_of(r.pose_in_world(v).matrix())
        assert np.allclose(back, v, atol=1e-9) and r.contains(back)


def test_json_keys_per_kind():
    c = ConfigRegion(id="c", interpretation="i", object="c", lower=(0, 0), upper=(1, 2), label="forwards")
    assert list(c.to_json()) == ["id", "kind", "label", "object", "lower", "upper"]
    w = WorkspaceRegion(id="w", frame="ee", approach=(-0.08, 0, 0), **_pose_fields())
    j = w.to_json()
    assert list(j) == ["id", "kind", "label", "object", "lower", "upper", "frame", "X_WR", "X_SE", "approach"]
    assert j["kind"] == "workspace" and j["frame"] == "ee" and j["approach"] == [-0.08, 0, 0]
    assert PlacementRegion(id="p", **_pose_fields()).to_json()["kind"] == "placement"


def test_drawings_say_what_to_draw_without_a_switch_in_the_viewer():
    scene = parse_scene(LOT)
    fwd = ConfigRegion(id="spot_1/forwards", interpretation="park:spot_1", object="spot_1", lower=(0, 0, 0), upper=(1, 1, 1))
    rev = ConfigRegion(id="spot_1/reversing", interpretation="park:spot_1", object="spot_1", lower=(0, 0, 0), upper=(1, 1, 1))
    d = fwd.drawing(scene)
    assert d == rev.drawing(scene) and d.name == "spot_1"  # one box per spot
    assert np.allclose(d.size, (5.0, 2.5, 1.0)) and np.allclose(d.X_WB.xyz, (10, 5, 0.5))
    w = WorkspaceRegion(id="c/top", frame="ee", **_pose_fields())
    dw = w.drawing(scene)
    assert dw.name == "c/top" and np.allclose(dw.size, (0.2, 0.03, 0.03))  # a thin axis stays visible
    assert np.allclose(dw.X_WB.matrix(), w.X_WR.compose(Pose((0.0, 0.0, 0.2))).matrix())


def test_goal_sources_are_looked_up_by_kind():
    world = BoxWorld(WALLS)
    world.space = SPACE
    r = ConfigRegion(id="c", interpretation="i", object="c", lower=(8.0, 8.0), upper=(9.0, 9.0))
    assert isinstance(goal_source_for((r,), world), ConfigGoalSource)
    with pytest.raises(ValueError, match="no goal regions"):
        goal_source_for((), world)


def test_a_new_kind_is_one_class_plus_its_registration(monkeypatch):
    monkeypatch.setattr(regions_base, "REGION_KINDS", dict(REGION_KINDS))
    monkeypatch.setattr(goals, "REGION_KINDS", regions_base.REGION_KINDS)
    monkeypatch.setattr(goals, "GOAL_SOURCES", dict(goals.GOAL_SOURCES))

    @register_region
    @dataclass(frozen=True)
    class DiscRegion(GoalRegion):
        kind = "disc"

        def drawing(self, scene):
            return RegionDrawing(self.id, (1.0, 1.0, 0.01), Pose())

    built = []
    register_goal_source(("disc",), lambda regions, world: built.append(regions) or "disc source")
    disc = GoalRegion.make("disc", id="d", interpretation="i", object="d", lower=(0.0, 0.0), upper=(1.0, 1.0))
    assert isinstance(disc, DiscRegion) and goal_source_for((disc,), object()) == "disc source" and built == [(disc,)]
    cfg = ConfigRegion(id="c", interpretation="i", object="c", lower=(0.0,), upper=(1.0,))
    with pytest.raises(ValueError, match="need different goal sources"):
        goal_source_for((disc, cfg), object())
    with pytest.raises(ValueError, match="unknown goal region kind 'cone'"):
        register_goal_source(("cone",), lambda regions, world: None)


def test_a_kind_without_a_source_is_one_clear_error(monkeypatch):
    monkeypatch.setattr(goals, "GOAL_SOURCES", {})
    r = ConfigRegion(id="c", interpretation="i", object="c", lower=(0.0,), upper=(1.0,))
    with pytest.raises(ValueError, match="no goal source registered for region kind 'config'"):
        goal_source_for((r,), object())


def test_what_an_occupied_spot_holds_is_type_data_overridable_per_object():
    scene = parse_scene(LOT)
    assert occupant_geometry(scene.object("spot_2"), scene).box == (4.5, 1.8, 1.5)  # lazyground/scene/types.yaml
    assert occupant_geometry(scene.object("spot_3"), scene).box == (3.0, 1.5, 1.2)  # the object's own
    assert occupant_geometry(scene.object("spot_1"), scene).box == (4.5, 1.8, 1.5)  # asked only when occupied


def test_an_occupant_override_is_checked_by_the_strict_loader():
    with pytest.raises(ValueError, match=r"objects\[0\]\.occupant\.box"):
        parse_scene(LOT.replace("occupant: {box: [3.0, 1.5, 1.2]}", "occupant: {box: [3.0, -1.5, 1.2]}").replace(
            "  - {id: spot_1", "  - {id: spot_0, type: parking_spot, occupied: true, occupant: {box: [3.0, -1.5, 1.2]}, geometry: {box: [5.0, 2.5, 0.05]}, pose: {xyz: [0, 20, 0]}}\n  - {id: spot_1", 1))


class _StubWorld:
    """Forward kinematics by table: frame -> pose, whatever q is; optionally carrying an object."""

    def __init__(self, poses, attached=None):
        self.poses, self.attached = poses, attached

    def frame_pose(self, frame, q):
        return self.poses[frame]


@dataclass(frozen=True)
class _Attached:
    body: str
    X_BO: Pose


def test_reached_asks_each_kind_its_own_question():
    c = ConfigRegion(id="c", interpretation="i", object="c", lower=(0, 0), upper=(1, 2))
    assert c.reached(np.array([0.5, 1.5]), None) and not c.reached(np.array([1.5, 1.5]), None)
    w = WorkspaceRegion(id="w", frame="ee", **_pose_fields())
    v = w.sample(np.random.default_rng(4))
    inside = w.pose_in_world(v)
    assert w.reached(None, _StubWorld({"ee": inside}), tol=1e-6)
    assert not w.reached(None, _StubWorld({"ee": inside.compose(Pose((0.0, 0.0, 0.05)))}), tol=0.01)
    p = PlacementRegion(id="p", **_pose_fields())
    X_BO = Pose((0.0, 0.0, 0.1), (0.0, 0.0, 0.4))
    X_WB = p.pose_in_world(v).compose(X_BO.inverse())  # the hand where the object lands inside
    assert p.reached(None, _StubWorld({"hand": X_WB}, _Attached("hand", X_BO)), tol=1e-6)
    with pytest.raises(ValueError, match="attached"):
        p.reached(None, _StubWorld({"hand": X_WB}))


# --- written to kill surviving mutants (tools/mutation.py regions) -------------------------------------------------

def test_a_kind_has_one_class_and_re_registering_it_is_harmless():
    assert register_region(ConfigRegion) is ConfigRegion

    @dataclass(frozen=True)
    class Other(GoalRegion):
        kind = "config"

    with pytest.raises(ValueError, match="goal region kind 'config' is already ConfigRegion"):
        register_region(Other)
    assert REGION_KINDS["config"] is ConfigRegion
    with pytest.raises(ValueError, match=r"\(known: config, workspace, placement\)"):
        GoalRegion.make("cone", id="a", interpretation="i", object="a", lower=(0.0,), upper=(1.0,))
    with pytest.raises(ValueError, match="^workspace bounds are"):
        PlacementRegion(id="p", interpretation="i", object="o", lower=(0,), upper=(1,))


def test_json_bounds_are_rounded_to_a_millionth():
    r = ConfigRegion(id="c", interpretation="i", object="c", lower=(0.12345678, -1.0000004), upper=(0.98765432, 2.0))
    assert r.to_json()["lower"] == [0.123457, -1.0] and r.to_json()["upper"] == [0.987654, 2.0]


def test_integer_and_zero_width_wrapped_bounds():
    """Bounds given as integers wrap as floats (a span of 2 pi - 6, not 0); a wrapped axis with lower == upper is
    that one angle, not the whole circle."""
    r = ConfigRegion(id="c", interpretation="i", object="c", lower=(3,), upper=(-3,), wrap=(0,))
    assert r.unit_map()[1] == pytest.approx([2 * np.pi - 6])
    rng = np.random.default_rng(0)
    assert all(abs(r.sample(rng)[0]) >= 3.0 - 1e-12 for _ in range(50))
    point = ConfigRegion(id="c", interpretation="i", object="c", lower=(0.0, 1.0), upper=(1.0, 1.0), wrap=(1,))
    assert point.unit_map()[1][1] == 0.0 and point.sample(rng)[1] == pytest.approx(1.0)
    assert not point.contains([0.5, 1.5]) and point.contains([0.5, 1.0])


def test_exact_bounds_are_inside_with_zero_tolerance():
    r = ConfigRegion(id="c", interpretation="i", object="c", lower=(-1.0, 0.25), upper=(0.5, 2.0))
    assert r.contains([-1.0, 2.0], tol=0.0) and r.contains([0.5, 0.25], tol=0.0)
    assert not r.contains([0.5 + 1e-12, 1.0], tol=0.0)


def test_a_config_region_is_reached_within_the_tolerance_given():
    r = ConfigRegion(id="c", interpretation="i", object="c", lower=(0.0,), upper=(1.0,))
    assert r.reached(np.array([1.05]), None, tol=0.1) and not r.reached(np.array([1.05]), None)


def test_a_tall_object_is_drawn_its_own_height():
    scene = parse_scene(dedent("""
        name: tall
        robot: {model: car, start: {}}
        objects:
          - {id: tower, type: parking_spot, geometry: {box: [2.0, 2.0, 3.0]}, pose: {xyz: [1, 1, 1.5]}}
    """))
    d = ConfigRegion(id="t", interpretation="park:tower", object="tower", lower=(0, 0, 0), upper=(1, 1, 1)).drawing(scene)
    assert np.allclose(d.size, (2.0, 2.0, 3.0)) and np.allclose(d.X_WB.xyz, (1, 1, 3.0))


class _FrameWorld:
    """A world whose frame ``name`` sits at q[:3] (no rotation) and may carry an object."""

    def __init__(self, attached=None):
        self.attached = attached

    def frame_pose(self, name, q):
        assert name in ("ee", "hand")
        return Pose(tuple(np.asarray(q, float)[:3]))


def test_pose_regions_are_reached_by_the_frame_they_bound():
    from types import SimpleNamespace

    f = dict(interpretation="i", object="c", lower=(-0.1, -0.1, -0.1, -np.pi, -np.pi / 2, -np.pi),
             upper=(0.1, 0.1, 0.1, np.pi, np.pi / 2, np.pi), X_WR=Pose((1.0, 0.0, 0.0)))
    w = WorkspaceRegion(id="w", frame="ee", **f)
    assert w.reached(np.array([1.05, 0.0, 0.0]), _FrameWorld())
    assert not w.reached(np.array([1.15, 0.0, 0.0]), _FrameWorld())
    assert w.reached(np.array([1.15, 0.0, 0.0]), _FrameWorld(), tol=0.1)
    p = PlacementRegion(id="p", **f)
    hand = SimpleNamespace(body="hand", X_BO=Pose((0.2, 0.0, 0.0)))  # the object 0.2 m ahead of the hand
    assert p.reached(np.array([0.8, 0.0, 0.0]), _FrameWorld(hand))
    assert not p.reached(np.array([1.0, 0.0, 0.0]), _FrameWorld(hand))
    for carries_nothing in (_FrameWorld(), SimpleNamespace(frame_pose=_FrameWorld().frame_pose)):  # no attribute
        with pytest.raises(ValueError, match="needs a world with an attached object"):
            p.reached(np.array([0.8, 0.0, 0.0]), carries_nothing)


def _angled_region():
    """An angled grasp's region (grounding/grasps.py angled): roll fixed, tilt 20-50 deg, any yaw, a small depth shift."""
    return WorkspaceRegion(id="can/angled", interpretation="pick:can", object="can", frame="ee", wrap=(5,),
                           lower=(0, 0, -0.006, 0, np.radians(20), -np.pi), upper=(0, 0, 0.006, 0, np.radians(50), np.pi),
                           X_WR=Pose((0.4, 0.5, 0.79), (np.pi, 0.0, 0.0)), X_SE=Pose((0.0, 0.0, -0.01), (0.0, -np.pi / 2, 0.0)))


def test_a_tilted_pose_is_reached_within_its_rotation_error_not_its_roll_pitch_yaw_error():
    """Regression (stress run 38, fetch_cans_1 "pick up a can", Can3/angled): IK met a 42-degree tilted grasp within
    0.010 rad, and reached(tol=0.01) said no: a rotation of e about the sampled frame's (cos p, 0, sin p) axis moves
    roll by e / cos p. reached now measures the rotation to the nearest pose of the region."""
    w = _angled_region()
    rng = np.random.default_rng(0)
    for _ in range(40):
        v = w.sample(rng)
        p = v[4]
        e = 0.009  # within tol = 0.01 of the drawn pose, in the direction roll-pitch-yaw stretches most
        X_WS = w.X_WR.compose(Pose(tuple(v[:3]), tuple(v[3:6])))
        turned = X_WS.compose(Pose(rpy=tuple(Rotation.from_rotvec(e * np.array([np.cos(p), 0.0, np.sin(p)])).as_euler("xyz"))))
        X_WE = turned.compose(w.X_SE)
        assert w.reached(None, _StubWorld({"ee": X_WE}), tol=0.01), v
        dp, angle = w.pose_error(X_WE.matrix())
        assert dp <= 1e-4 and angle <= e + 1e-9  # the fit may trade a little position (X_SE lever, 1 cm) for rotation
    # a turn about the fixed roll axis the free tilt and yaw cannot absorb stays out: 0.03 rad leaves 0.03 cos p
    v = np.array([0.0, 0.0, 0.0, 0.0, np.radians(45), 1.0])
    X_WE = w.X_WR.compose(Pose(tuple(v[:3]), tuple(v[3:6]))).compose(Pose(rpy=(0.03, 0.0, 0.0))).compose(w.X_SE)
    assert w.pose_error(X_WE.matrix())[1] == pytest.approx(0.03 * np.cos(np.radians(45)), rel=1e-3)
    assert not w.reached(None, _StubWorld({"ee": X_WE}), tol=0.01)
    # and a shift 5 mm beyond the depth range is 5 mm out (less a trade of rotation for position under 0.1 mm)
    X_WE = w.pose_in_world(np.array([0.0, 0.0, 0.011, 0.0, np.radians(30), 0.2]))
    assert w.pose_error(X_WE.matrix()) == pytest.approx((0.005, 0.0), abs=1e-4)
    assert not w.reached(None, _StubWorld({"ee": X_WE}), tol=0.004)
