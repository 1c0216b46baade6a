"""Placements that leave room (lazyground/tasks/packing.py, #30): the free area's centre, the farthest
candidate, positions kept clear after a backtrack. No Drake: the preference is numpy over region draws."""

from dataclasses import replace
from pathlib import Path

import numpy as np

from grounding.regions import regions_for
from lazyground.geometry import Pose
from lazyground.scene import load_scene
from lazyground.scene.schema import PoseSpec
from lazyground.tasks.packing import footprint, preference

SCENE = load_scene(Path(__file__).parents[1] / "data/scenes/panda_pack.yaml")
(LEDGE,) = regions_for(SCENE.object("ledge"), "support", "place:cup_a:ledge", SCENE)


def draws(ys):
    """Draws (len(ys), 1, 6) of the ledge's one region at y = ys (x, z, angles 0)."""
    V = np.zeros((len(ys), 1, 6))
    V[:, 0, 1] = ys
    return V


def test_an_empty_surface_prefers_its_ends():
    p = preference(SCENE, "cup_a", (LEDGE,), draws=3)
    assert np.allclose(p.centres[0], 0.0, atol=1e-9)  # nothing on it: the centre
    assert p.pick(np.array([0]), draws([0.0, -0.04, 0.01]))[0, 1] == -0.04


def test_an_object_on_the_surface_moves_the_free_centre_away_so_the_next_packs_beside_it():
    X_WR = LEDGE.X_WR
    at = X_WR.compose(Pose((0.0, 0.045, 0.05))).xyz  # cup_b standing at the ledge's +y end
    scene = replace(SCENE, objects=tuple(replace(o, pose=PoseSpec(at)) if o.id == "cup_b" else o for o in SCENE.objects))
    p = preference(scene, "cup_a", (LEDGE,), draws=2)
    assert p.centres[0][1] < -0.01  # the free part is the -y end
    assert p.pick(np.array([0]), draws([-0.04, 0.0]))[0, 1] == 0.0  # nearer cup_b: one free stretch left


def test_a_kept_clear_position_rules_out_candidates_within_the_objects_footprint():
    X_WO = LEDGE.X_WR.compose(Pose((0.0, 0.0, 0.05))).xyz
    r = footprint(SCENE.object("cup_a"))
    p = preference(SCENE, "cup_a", (LEDGE,), draws=1, keep_clear=((*X_WO, r),))
    V = draws([0.0, 0.02, 0.04])[:, 0]
    assert p.avoided(np.zeros(3, int), V).tolist() == [True, True, False]  # within 3 cm of where it stood
