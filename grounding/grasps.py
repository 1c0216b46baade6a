"""Grasp-region templates: where a parallel gripper can hold an object, and whether it fits.

Every grasp is written for the gripper-neutral frame N at the grasp point
(lazyground/robots/end_effector.py): N.x the approach axis, N.y the closing axis.
``make_region`` maps N to the robot's tool frame through its ``EndEffectorSpec``,
so the same templates serve the Fetch's x-forward gripper_link and a ROS-style
z-forward tool frame. A grasp exists only where the object's width across the
closing axis is within the gripper's ``opening`` less a clearance.

Every template's ``depth: [d0, d1]`` is how far the fingers reach over the object along the approach
axis, past the face they enter by (the top face, a box's side face, a cylinder's near side): the grasp
point sits ``depth - ee.fingertip`` past that face (issue 34: a top grasp's depth was measured above the
top face, and the Panda's fingertips, 9 mm past its TCP, closed above a can's rim).

Templates (their numbers live in lazyground/scene/types.yaml):

- ``top``: from above, R on the top face, R.x down; one region per closing
  direction that fits (for a cylinder, any yaw). With ``tilt``, angled: the approach
  slanted from the vertical, still entering by the top face (:func:`angled`).
- ``side_faces``: into each vertical face of a box, fingers closing horizontally.
- ``side_around``: a cylinder's side from any horizontal direction at a few heights,
  approach horizontal, fingers closing horizontally.
"""

from __future__ import annotations

import math

from lazyground.geometry import Pose
from lazyground.regions import GoalRegion, WorkspaceRegion
from lazyground.robots.end_effector import X_NT, EndEffectorSpec, is_neutral, vector_in_tool

GRASP_CLEARANCE = 0.01  # m: the fingers must open this much wider than the object


def make_region(cls, obj, interpretation, label, lower, upper, ee: EndEffectorSpec | None = None, **fields) -> GoalRegion:
    """A region of class ``cls`` on ``obj``, named ``<object id>/<label>``.

    With ``ee`` (grasps), the bounds are on the neutral frame N: the region constrains ``ee.frame``
    through X_SE · X_NT, and ``approach`` (given in N) is moved to the tool frame's axes.
    """
    if ee is not None:
        fields["frame"] = ee.frame
        if not is_neutral(ee):
            fields["X_SE"], fields["approach"] = in_tool(ee, fields.get("X_SE", Pose()), fields.get("approach", (0.0, 0.0, 0.0)))
    return cls(id=f"{obj.id}/{label}", interpretation=interpretation, object=obj.id, label=label,
               lower=tuple(map(float, lower)), upper=tuple(map(float, upper)), **fields)


_IN_TOOL: dict[str, tuple[Pose, tuple[float, float, float]]] = {}
_IN_TOOL_MAX = 4096  # entries; cleared when full (a scene has a few end effectors and templates)


def in_tool(ee: EndEffectorSpec, X_SE: Pose, approach) -> tuple[Pose, tuple[float, float, float]]:
    """``X_SE`` · X_NT and ``approach`` in the tool frame's axes.

    Both depend only on the end effector and the template's numbers, not on the object's pose, so they are
    computed once (#33: done per region, they were most of grounding a 64-can rack). The key is the repr of
    the inputs, exact to the bit (0.0 and -0.0 differ there, as they may in the result).
    """
    key = repr((ee, X_SE, approach))
    out = _IN_TOOL.get(key)
    if out is None:
        if len(_IN_TOOL) >= _IN_TOOL_MAX:
            _IN_TOOL.clear()
        out = _IN_TOOL[key] = (X_SE.compose(X_NT(ee)), vector_in_tool(ee, approach))
    return out


def fits(width: float, ee: EndEffectorSpec, spec: dict) -> bool:
    """Whether an object ``width`` wide across the closing axis fits between the open fingers."""
    return ee.opening is None or width <= ee.opening - float(spec.get("clearance", GRASP_CLEARANCE))


def fit_note(obj, ee: EndEffectorSpec, spec_clearance: float = GRASP_CLEARANCE) -> str:
    """The grounding note for an object no grasp fits, with the numbers."""
    hx, hy, hz = obj.geometry.half_extents()
    widths = sorted({round(2 * hx, 3), round(2 * hy, 3)} if obj.geometry.box is not None else {round(2 * hx, 3)})
    across = " or ".join(f"{w:g}" for w in widths)
    return (f"{obj.id} cannot be grasped: it is {across} m across, wider than the gripper's opening "
            f"{ee.opening:g} m less {spec_clearance:g} m clearance ({ee.frame})")


def _approach_back(spec) -> tuple[float, float, float]:
    """The pre-pose offset in N: ``spec['approach']`` metres back along the approach axis."""
    return (-float(spec.get("approach", 0.0)), 0.0, 0.0)


def _top_face(obj) -> Pose:
    """R on the top face centre with R.x pointing down (roll about R.x = yaw about the vertical)."""
    return obj.pose.pose().compose(Pose((0.0, 0.0, obj.geometry.half_extents()[2]), (0.0, math.pi / 2, 0.0)))


def _is_cylinder(obj) -> bool:
    return obj.geometry.box is None


def _reach(spec, ee: EndEffectorSpec) -> tuple[float, float]:
    """The grasp point's range past the face the fingers enter by: ``depth`` less the fingertip's reach."""
    d0, d1 = spec["depth"]
    return float(d0) - ee.fingertip, float(d1) - ee.fingertip


def top(obj, spec, interpretation, ee):
    """From above, the fingers ``depth`` below the top face. A cylinder: any yaw. A box: the fingers close
    along its x or its y, one region for each that fits (roll fixed, the gripper being symmetric).
    With ``tilt: [t0, t1]`` (degrees), the approach slants from the vertical: :func:`angled`."""
    if "tilt" in spec:
        return angled(obj, spec, interpretation, ee)
    d0, d1 = _reach(spec, ee)
    hx, hy, _ = obj.geometry.half_extents()
    X_WR = _top_face(obj)
    # R.x points down, so "below the face" is positive x in R; at roll 0 N.y (closing) is the object's y.
    if _is_cylinder(obj):
        options = [("top", 2 * hx, (-math.pi, math.pi))]
    else:
        options = [("top y", 2 * hy, (0.0, 0.0)), ("top x", 2 * hx, (math.pi / 2, math.pi / 2))]
    return [make_region(WorkspaceRegion, obj, interpretation, label, (d0, 0, 0, roll[0], 0, 0), (d1, 0, 0, roll[1], 0, 0), ee,
                        X_WR=X_WR, approach=_approach_back(spec))
            for label, width, roll in options if fits(width, ee, spec)]


def angled(obj, spec, interpretation, ee):
    """From above at a slant (issue 34: a can in an open box whose walls block the side grasps, out of
    reach straight down): the approach tilted ``tilt: [t0, t1]`` degrees from the vertical about the
    closing axis, which stays horizontal, its line through the top face's centre, so the fingers enter
    by the top face at every tilt and reach ``depth`` past it along the approach.

    A cylinder: any yaw, tilt in [t0, t1] (one region, "angled"). A box: the fingers close across its y
    or its x as for ``top``, tilted to either side, tilt in [-t1, t1] ("angled y", "angled x").
    R sits on the top face centre with R.z down; a draw is (0, 0, u, 0, tilt, yaw): the yaw about the
    vertical, then the tilt about the closing axis; X_SE puts the grasp point the depth range's middle
    along the tilted approach, and u (a vertical shift of the line, at most half the depth range times
    cos t1) spreads the depth over the range without leaving it at any tilt.
    """
    d0, d1 = _reach(spec, ee)
    t0, t1 = (math.radians(float(t)) for t in spec["tilt"])
    if not 0.0 <= t0 <= t1 < math.pi / 2:
        raise ValueError(f"tilt must be 0 <= t0 <= t1 < 90 degrees, got {spec['tilt']}")
    hx, hy, hz = obj.geometry.half_extents()
    X_WR = obj.pose.pose().compose(Pose((0.0, 0.0, hz), (math.pi, 0.0, 0.0)))
    X_SE = Pose((0.0, 0.0, (d0 + d1) / 2), (0.0, -math.pi / 2, 0.0))  # N.x = S.z (the tilted approach), N.y = S.y
    u = (d1 - d0) / 2 * math.cos(t1)
    if _is_cylinder(obj):
        options = [("angled", 2 * hx, (t0, t1), (-math.pi, math.pi))]
    else:  # R.y is the object's -y: yaw 0 closes across its y, yaw pi/2 across its x
        options = [("angled y", 2 * hy, (-t1, t1), (0.0, 0.0)), ("angled x", 2 * hx, (-t1, t1), (math.pi / 2, math.pi / 2))]
    return [make_region(WorkspaceRegion, obj, interpretation, label, (0, 0, -u, 0, tilt[0], yaw[0]), (0, 0, u, 0, tilt[1], yaw[1]), ee,
                        X_WR=X_WR, X_SE=X_SE, approach=_approach_back(spec))
            for label, width, tilt, yaw in options if fits(width, ee, spec)]


FACES = {"+x": (0, 1, math.pi), "-x": (0, -1, 0.0), "+y": (1, 1, -math.pi / 2), "-y": (1, -1, math.pi / 2)}


def side_faces(obj, spec, interpretation, ee):
    """One region per vertical face of a box: horizontal approach into the face, the fingers closing
    horizontally across it (so the face's width must fit)."""
    half = obj.geometry.half_extents()
    hz = half[2]
    d0, d1 = _reach(spec, ee)
    l0, l1 = spec["lateral"]
    h = max(0.0, hz - spec.get("height_margin", 0.0))
    out = []
    for name, (axis, sign, yaw) in FACES.items():
        if not fits(2 * half[1 - axis], ee, spec):
            continue
        offset = [0.0, 0.0, 0.0]
        offset[axis] = sign * half[axis]
        X_WR = obj.pose.pose().compose(Pose(tuple(offset), (0.0, 0.0, yaw)))
        out.append(make_region(WorkspaceRegion, obj, interpretation, f"face {name}", (d0, l0, -h, 0, 0, 0), (d1, l1, h, 0, 0, 0), ee,
                               X_WR=X_WR, approach=_approach_back(spec)))
    return out


def side_around(obj, spec, interpretation, ee):
    """A cylinder's side from any horizontal direction: one region per height in ``heights`` (fractions
    of the length from the bottom, each a band ``height_band`` of the length wide), or one band
    ``height_fraction: [lo, hi]``. The fingers close horizontally across the diameter."""
    r, _, hz = obj.geometry.half_extents()
    if not fits(2 * r, ee, spec):
        return []
    d0, d1 = _reach(spec, ee)
    # sample yaw about the axis and a height; then back off along the approach axis by the radius
    X_SE = Pose((-(r - (d0 + d1) / 2), 0.0, 0.0), (0.0, 0.0, 0.0))
    half_depth = (d1 - d0) / 2
    if "heights" in spec:
        band = float(spec.get("height_band", 0.1)) / 2
        bands = [(f"side {100 * f:.0f}%", f - band, f + band) for f in spec["heights"]]
    else:
        bands = [("side", *spec["height_fraction"])]
    return [make_region(WorkspaceRegion, obj, interpretation, label, (-half_depth, 0, -hz + 2 * hz * f0, 0, 0, -math.pi),
                        (half_depth, 0, -hz + 2 * hz * f1, 0, 0, math.pi), ee, X_WR=obj.pose.pose(), X_SE=X_SE, approach=_approach_back(spec))
            for label, f0, f1 in bands]


GRASP_TEMPLATES = {"top": top, "side_faces": side_faces, "side_around": side_around}
