"""MoveIt import with Drake (#15): a start in collision, mesh obstacles, the CLI's exit codes."""

import textwrap

import numpy as np
import pytest

from lazyground.bench.moveit_corpus import CORPUS
from lazyground.cli import main
from lazyground.drake.world import DrakeWorld
from lazyground.moveit import ImportOptions, import_moveit_file
from lazyground.scene import load_scene
from lazyground.typed_yaml import SceneError
from tests.unit.test_scene_meshes_and_robot_fill import FETCH


def test_a_start_in_collision_names_the_pairs_and_the_free_named_poses(tmp_path):
    with pytest.raises(SceneError) as info:
        import_moveit_file(CORPUS / "can_in_open_box.yaml", tmp_path / "out.yaml", ImportOptions())
    message = str(info.value)
    assert "the start (the scene's robot_state) is in collision" in message and "collides with open_box_wall" in message
    assert "free named poses: tucked (use --start NAME)" in message and "\n" not in message
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("mesh", ["meshes/fridge.stl", "kitchen_description/meshes/counter.obj"])
def test_mesh_obstacles_collide_as_their_shape(tmp_path, mesh):
    path = tmp_path / "s.yaml"
    path.write_text(textwrap.dedent(f"""
        name: m
        robot: {FETCH}
        obstacles: [{{id: block, geometry: {{mesh: {{file: {CORPUS / mesh}}}}}, pose: {{xyz: [X, 0, 0]}}}}]
    """))
    far = DrakeWorld(load_scene(_with(path, "X", "2.5")), visual=False)
    stretched = np.zeros_like(far.start)  # the arm stretched out along +x
    assert far.config_free(far.start) and far.config_free(stretched)
    near = DrakeWorld(load_scene(_with(path, "X", "0.9")), visual=False)
    assert near.config_free(near.start)  # tucked: clear of a block 0.55-0.6 m away
    assert not near.config_free(stretched) and "block" in near.explain(stretched)


def test_a_mesh_file_that_is_not_an_obj_is_a_scene_error(tmp_path):
    # audit8: a PNG renamed .obj (or an OBJ without vertices) was "internal error: RuntimeError: MakeConvexHull()
    # cannot be used on a mesh with fewer than three vertices", exit 3
    (tmp_path / "block.obj").write_bytes(b"\x89PNG\r\n\x1a\n" + bytes(64))
    path = tmp_path / "s.yaml"
    path.write_text(f"name: m\nrobot: {FETCH}\nobstacles: [{{id: block, geometry: {{mesh: {{file: block.obj}}}}, pose: {{xyz: [2, 0, 0]}}}}]\n")
    with pytest.raises(SceneError, match=r"s\.yaml: block: cannot use its geometry: MakeConvexHull\(\) cannot be used on a mesh "
                                         r"with fewer than three vertices"):
        DrakeWorld(load_scene(path), visual=False)


def _with(path, key, value):
    out = path.with_name(f"{path.stem}_{value}.yaml")
    out.write_text(path.read_text().replace(key, value))
    return out


def test_cli_import_and_plan_start_options(tmp_path, capsys):
    out = tmp_path / "noisy.yaml"
    assert main(["import-moveit", str(CORPUS / "noisy_small_shelves.yaml"), "-o", str(out)]) == 0
    captured = capsys.readouterr()
    assert "planner: bidirectional" in captured.out and "start: the scene's robot_state" in captured.out
    assert "clamped" in captured.err
    (tmp_path / "r.urdf").write_text("<robot name='r'><link name='a'/></robot>\n")
    for argv, words in [
        (["import-moveit", str(tmp_path / "r.urdf"), "-o", str(tmp_path / "x.yaml")], "this is a URDF robot model"),
        (["import-moveit", str(CORPUS / "can_in_open_box_request.yaml"), "-o", str(tmp_path / "x.yaml")], "--start-from"),
        (["import-moveit", str(CORPUS / "bookshelf_cans.yaml"), "-o", str(tmp_path / "x.yaml"), "--type", "bad"], "REGEX=TYPE"),
        (["import-moveit", str(CORPUS / "kitchen_meshes.yaml"), "-o", str(tmp_path / "x.yaml"), "--package", "k"], "NAME=DIR"),
        (["plan", str(out), "pick up a can", "--start", "home"], "no named pose 'home'"),
        (["plan", str(out), "pick up a can", "--start-joints", "torso_lift_joint=1"], "outside its limits"),
    ]:
        assert main(argv) == 2, argv
        err = capsys.readouterr().err.strip()
        assert words in err and len(err.splitlines()) == 1, err
    assert not (tmp_path / "x.yaml").exists()


def test_plan_from_a_start_in_collision_lists_free_named_poses(tmp_path, capsys):
    out = tmp_path / "box.yaml"
    assert main(["import-moveit", str(CORPUS / "can_in_open_box.yaml"), "-o", str(out), "--start", "tucked"]) == 0
    assert main(["plan", str(out), "pick up a can", "--start", "zero"]) == 1
    err = capsys.readouterr().err
    assert "hint: free named poses: tucked (plan ... --start NAME)" in err
