"""#20: bundled scene names work from any directory, and a wheel ships the scenes and models."""

from __future__ import annotations

import fnmatch
import os
import subprocess
import sys
import tomllib

import pytest

from lazyground.bundled import bundled_scene, data_dir, scene_names
from lazyground.scene import SceneError, load_scene
from tests.unit.test_grounding import REPO


def test_bare_name_loads_the_bundled_scene_from_another_directory(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    scene = load_scene("parking_1")
    assert scene.name == "parking_1" and load_scene("parking_1.yaml").name == "parking_1"
    assert os.path.samefile(scene.source, REPO / "yaml_scenes" / "parking_1.yaml")


def test_a_local_file_wins_and_paths_are_never_redirected(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "parking_1.yaml").write_text((REPO / "yaml_scenes" / "parking_2.yaml").read_text())
    assert load_scene("parking_1.yaml").name == "parking_2"
    assert bundled_scene("sub/parking_1") is None
    with pytest.raises(SceneError, match=r"^sub/parking_1: no such scene file$"):
        load_scene("sub/parking_1")


def test_unknown_bare_name_lists_the_bundled_scenes():
    with pytest.raises(SceneError) as info:
        load_scene("parking_9")
    assert str(info.value).startswith("parking_9: no such scene file (bundled scenes: fetch_boxes_3, ")
    assert "parking_1" in scene_names() and "fetch_cans_1" in scene_names()


def test_cli_accepts_a_bundled_name_from_any_directory(tmp_path):
    env = dict(os.environ, PYTHONPATH=str(REPO))
    proc = subprocess.run([sys.executable, "-m", "lazyground", "ground", "parking_1", "park in spot B1"],
                          cwd=tmp_path, capture_output=True, text=True, env=env, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert "park:spot_b1" in proc.stdout


def test_package_data_covers_every_bundled_file():
    """The wheel's globs (pyproject) match every scene and model file, through lazyground/data."""
    globs = tomllib.loads((REPO / "pyproject.toml").read_text())["tool"]["setuptools"]["package-data"]["lazyground"]
    for name in ("yaml_scenes", "models"):
        assert data_dir(name) == REPO / "lazyground" / "data" / name
        files = [p for p in (REPO / name).rglob("*") if p.is_file()]
        assert files
        for p in files:
            rel = f"data/{name}/{p.relative_to(REPO / name).as_posix()}"
            assert any(fnmatch.fnmatch(rel, g) and rel.count("/") == g.count("/") for g in globs), rel
