"""Grasp regions mapped to the tool frame through a cache (grounding/grasps.py ``in_tool``, #33) are the
regions the straightforward per-region mapping gives: every field, bit for bit (compared by repr, where
0.0 and -0.0 differ), in the same order, on a cold and a warm cache."""

from __future__ import annotations

import numpy as np
import pytest

from grounding import GroundingError, ground
from grounding import grasps
from lazyground.bench.families import load_family_scene
from lazyground.geometry import Pose
from lazyground.robots.defaults import EndEffectorSpec
from lazyground.robots.end_effector import X_NT, vector_in_tool
from lazyground.scene import load_scene
from tests.unit.test_grounding import REPO

FAMILIES = ("rack:panda:16:1:0", "rack:panda:64:1:3", "rack:fetch:16:1:1", "rack:fetch:64:1:2", "lot:64:2:0")
BUNDLED = ("panda_tabletop", "ur5e_tabletop", "fetch_boxes_3", "kitchen_put_cup_on_table", "fetch_put_box_on_table")
EXTRA = ("pick up a box", "put a box on the table", "put a can on a shelf", "pick up two cans")


def _straight(ee, X_SE, approach):
    """The mapping as it was computed per region before the cache."""
    return X_SE.compose(X_NT(ee)), vector_in_tool(ee, approach)


def _groundings(scene) -> list[str]:
    out = []
    for request in dict.fromkeys([e.request for e in scene.expect] + list(EXTRA)):
        try:
            out.append(repr(ground(request, scene)))
        except GroundingError as exc:
            out.append(f"error: {exc}")
    return out


def _scenes():
    yield from ((key, load_family_scene(key)) for key in FAMILIES)
    yield from ((name, load_scene(REPO / "yaml_scenes" / f"{name}.yaml")) for name in BUNDLED)
    yield "panda_stow", load_scene(REPO / "tests" / "data" / "scenes" / "panda_stow.yaml")


@pytest.mark.parametrize("name,scene", list(_scenes()), ids=lambda v: v if isinstance(v, str) else "")
def test_cached_regions_equal_straightforward(name, scene, monkeypatch):
    grasps._IN_TOOL.clear()
    cold = _groundings(scene)
    warm = _groundings(scene)
    with monkeypatch.context() as m:
        m.setattr(grasps, "in_tool", _straight)
        reference = _groundings(scene)
    assert any(not g.startswith("error") for g in reference)
    assert cold == reference
    assert warm == reference


def test_in_tool_keys_are_exact():
    """Interleaved calls on random end effectors, frames and offsets (with signed zeros) give what the
    straightforward mapping gives each time."""
    rng = np.random.default_rng(0)
    axes = [("z", "y"), ("x", "y"), ("-z", "x"), ("y", "-z")]
    calls = []
    for i in range(60):
        a, c = axes[i % len(axes)]
        ee = EndEffectorSpec(frame="t", offset_xyz=tuple(rng.choice([0.0, -0.0, 0.1], 3)),
                             offset_rpy=tuple(rng.choice([0.0, -0.0, 0.5], 3)), approach_axis=a, closing_axis=c)
        X_SE = Pose(tuple(rng.choice([0.0, -0.0, 0.03], 3)), tuple(rng.choice([0.0, -0.0, np.pi / 2], 3)))
        calls.append((ee, X_SE, tuple(float(v) for v in rng.choice([0.0, -0.0, -0.08], 3))))
    grasps._IN_TOOL.clear()
    for args in calls + calls[::-1]:
        assert repr(grasps.in_tool(*args)) == repr(_straight(*args))


@pytest.mark.parametrize("key", ("lot:64:2:0", "rack:panda:16:1:0"))
def test_a_scene_lexicon_made_once_is_the_lexicon_made_anew(key):
    # Lexicon.for_scene is made once per set of the objects' types and ids (#33): the same phrases as made anew, and
    # a scene with one id renamed gets its own
    from dataclasses import replace

    from grounding.lexicon import load_lexicon

    scene, lex = load_family_scene(key), load_lexicon()
    first = lex.for_scene(scene)
    assert lex.for_scene(scene) is first and first.phrases == lex._for_objects(scene).phrases
    renamed = replace(scene, objects=(replace(scene.objects[0], id="Zebra9"),) + tuple(scene.objects[1:]))
    other = lex.for_scene(renamed)
    assert other is not first and other.phrases == lex._for_objects(renamed).phrases and ("zebra9",) in other.phrases
