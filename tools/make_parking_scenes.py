"""Write yaml_scenes/parking_1.yaml and parking_2.yaml (the paper's Fig. 6, in spirit).

Run: ``python3 tools/make_parking_scenes.py``. The YAML files are committed; this
script documents how their geometry was laid out and regenerates it.

* parking_1: a lot with two rows of spots and a planted island. The free spot
  nearest the entrance is barred by bollards across its mouth (valid goal
  samples, unreachable); another near one has a pillar inside (no valid
  samples); three further spots are reachable.
* parking_2: a three-room garage. Every free spot lies behind a wall with a
  narrow opening (3.0 m for a 1.8 m wide, 4.5 m long car), so reaching any spot
  means passing a narrow aisle; the near spots are the dead ends.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from lazyground.settings import GoalExtension, Kinematics, Strategy  # noqa: E402
SPOT = (5.5, 2.6)  # length along the spot's heading, width
HALF_PI = round(math.pi / 2, 6)


def box(id_, x, y, sx, sy, h=1.0, yaw=0.0, color=None):
    out = {"id": id_, "geometry": {"box": [sx, sy, h]}, "pose": {"xyz": [x, y, h / 2], "rpy": [0, 0, yaw]}}
    if color:
        out["color"] = color
    return out


def spot(id_, x, y, yaw, occupied):
    return {
        "id": id_,
        "type": "parking_spot",
        "geometry": {"box": [SPOT[0], SPOT[1], 0.05]},
        "pose": {"xyz": [x, y, 0.0], "rpy": [0, 0, yaw]},
        "occupied": occupied,
    }


def walls(width, height, t=0.3, gaps=()):
    """Perimeter walls of a width x height lot."""
    return [
        box("wall_south", width / 2, -t / 2, width + 2 * t, t, 2.0),
        box("wall_north", width / 2, height + t / 2, width + 2 * t, t, 2.0),
        box("wall_west", -t / 2, height / 2, t, height, 2.0),
        box("wall_east", width + t / 2, height / 2, t, height, 2.0),
    ]


def car_robot(x, y, heading, width, height):
    return {
        "model": "car",
        "start": {"car_x": x, "car_y": y, "car_qz": heading},
        "limits": {"car_x": [0.0, width], "car_y": [0.0, height]},
        "weights": {"car_qz": 2.0},
    }


def planner(step=2.0, time_limit=10.0):
    # 2 m extensions, collision-checked every 0.1 m (measured fastest of 1-4 m on both lots). Goal steps
    # all or nothing, as Algorithm 1 reads: on parking_1 that beat keeping the free part of a blocked step
    # (reward-penalty, 300 seeds: 0.037 s vs 0.046 s mean; parking_2 0.159 vs 0.162 s).
    # The car drives Reeds-Shepp curves (issue #17); --kinematics holonomic is the paper's puck.
    return {"strategy": Strategy.REWARD_PENALTY.value, "goal_bias": 0.05, "step_size": step, "edge_resolution": 0.1,
            "time_limit": time_limit, "seed": 0, "goal_extension": GoalExtension.EXTEND.value,
            "kinematics": Kinematics.REEDS_SHEPP.value}


def parked_car(id_, x, y, yaw):
    """A parked car (the 4.5 m x 1.8 m footprint, 1.5 m high) outside any spot object."""
    return box(id_, x, y, 4.5, 1.8, 1.5, yaw=yaw, color="grey")


def parking_1() -> dict:
    W, H = 36.0, 24.0
    free_bottom = {1, 9}  # spot b1: bollards at its mouth; b9: reachable
    free_top = {3, 10}  # t3: pillar inside; t10: reachable
    objects, obstacles = [], walls(W, H)
    for i in range(12):
        x = 3.0 + 2.6 * i + 1.3
        objects.append(spot(f"spot_b{i}", x, SPOT[0] / 2, -HALF_PI, i not in free_bottom))
        objects.append(spot(f"spot_t{i}", x, H - SPOT[0] / 2, HALF_PI, i not in free_top))
    # the island between the two aisles, with a gap at each end
    obstacles.append(box("island", 18.0, 12.0, 22.0, 2.0, 0.3, color="green"))
    # b1 barred by three bollards across its mouth
    xb1 = 3.0 + 2.6 * 1 + 1.3
    for k, dx in enumerate((-0.9, 0.0, 0.9)):
        obstacles.append({"id": f"bollard_{k}", "geometry": {"cylinder": {"radius": 0.15, "length": 1.0}},
                          "pose": {"xyz": [xb1 + dx, SPOT[0] + 0.3, 0.5]}})
    # t3 has a structural pillar inside
    xt3 = 3.0 + 2.6 * 3 + 1.3
    obstacles.append(box("pillar_t3", xt3, H - 2.2, 0.8, 0.8, 3.0))
    return {
        "name": "parking_1",
        "description": "Automated valet parking (paper Fig. 6a in spirit): 4 free spots; the nearest is barred by "
        "bollards, one has a pillar inside, two are reachable.",
        "robot": car_robot(3.5, 8.25, 0.0, W, H),
        "obstacles": obstacles,
        "objects": objects,
        "planner": planner(time_limit=10.0),
        "expect": [
            {"request": "park", "interpretations": ["park:spot_b1", "park:spot_b9", "park:spot_t10", "park:spot_t3"],
             "success_rate": 0.9, "seeds": 10, "max_iterations": 2000, "time_limit": 300.0,
             "reachable": ["spot_b9", "spot_t10"]},
        ],
    }


def parking_2() -> dict:
    W, H = 40.0, 30.0
    objects, obstacles = [], walls(W, H)
    # two inner walls split the lot into three bays, each passed through a 3.0 m opening
    obstacles += [
        box("wall_a_low", 13.0, 5.5, 0.3, 11.0, 2.0),  # opening A: y in [11, 14]
        box("wall_a_high", 13.0, 22.0, 0.3, 16.0, 2.0),
        box("wall_b_low", 27.0, 9.75, 0.3, 19.5, 2.0),  # opening B: y in [19.5, 22.5]
        box("wall_b_high", 27.0, 26.25, 0.3, 7.5, 2.0),
    ]
    # bay 1 (start bay, x < 13): spots along the south wall; the free one holds a trolley
    for i in range(4):
        objects.append(spot(f"spot_a{i}", 1.6 + 2.6 * i, SPOT[0] / 2, -HALF_PI, i != 2))
    obstacles.append(box("trolley_a2", 1.6 + 2.6 * 2 + 0.9, 3.5, 1.0, 1.2, 1.0))
    # bay 2 (13 < x < 27): spots along the north wall; b4 is barred by bollards
    for i in range(5):
        objects.append(spot(f"spot_b{i}", 14.5 + 2.6 * i, H - SPOT[0] / 2, HALF_PI, i not in (1, 4)))
    xb4 = 14.5 + 2.6 * 4
    for k, dx in enumerate((-0.9, 0.0, 0.9)):
        obstacles.append({"id": f"bollard_{k}", "geometry": {"cylinder": {"radius": 0.15, "length": 1.0}},
                          "pose": {"xyz": [xb4 + dx, H - SPOT[0] - 0.3, 0.5]}})
    # bay 3 (x > 27): spots along the south wall, through both openings
    for i in range(4):
        objects.append(spot(f"spot_c{i}", 28.8 + 2.6 * i, SPOT[0] / 2, -HALF_PI, i not in (1, 2)))
    return {
        "name": "parking_2",
        "description": "Automated valet parking through narrow aisles (paper Fig. 6b in spirit).",
        "robot": car_robot(4.0, 20.0, 0.0, W, H),
        "obstacles": obstacles,
        "objects": objects,
        "planner": planner(time_limit=20.0),
        "expect": [
            {"request": "park", "interpretations": ["park:spot_a2", "park:spot_b1", "park:spot_b4", "park:spot_c1", "park:spot_c2"],
             "success_rate": 0.9, "seeds": 10, "max_iterations": 20000, "time_limit": 300.0,
             "reachable": ["spot_b1", "spot_c1", "spot_c2"]},
        ],
    }


def parking_3() -> dict:
    """A lot where feasibility for the car decides, not collisions alone (issue #17).

    Two aisles joined at the east end: the wide north aisle (7.2 m) where the car starts,
    and a narrow south aisle (3.5 m) behind a median wall. Occupied spots hold parked cars
    (the Drake world adds them). Free spots, all collision-free for the paper's sliding car:
    p0, a parallel gap 5.0 m long between two parked cars on the wide aisle: the sliding car
    slips in sideways, a car turning no tighter than 3.86 m never got in (2 seeds x 30,000
    iterations with p0 the only goal); s2 off the narrow aisle: reachable by both, but only by
    long searches (6,000-17,000 iterations as the only goal, shunting for the car); s12 at the
    junction; n4, whose mouth is half-blocked by a pillar on its west side, so a car from the
    west drives past and reverses in; n9, a plain spot.
    """
    W, H = 40.0, 22.0
    median_y, median_end = 9.0, 33.0
    north_y = 16.5  # the north row's spots start here
    objects, obstacles = [], walls(W, H)
    obstacles.append(box("median", median_end / 2, median_y + 0.15, median_end, 0.3, 1.0))
    free_south, free_north = {2, 12}, {4, 9}
    for i in range(14):
        x = 2.3 + 2.6 * i
        objects.append(spot(f"spot_s{i}", x, SPOT[0] / 2, -HALF_PI, i not in free_south))
        objects.append(spot(f"spot_n{i}", x, north_y + SPOT[0] / 2, HALF_PI, i not in free_north))
    # the pillar at n4's west mouth corner
    xn4 = 2.3 + 2.6 * 4
    obstacles.append(box("pillar_n4", xn4 - 1.6, north_y - 0.9, 0.6, 1.6, 3.0))
    # a parallel spot along the median's north face, 5.0 m between two parked cars
    y_par = median_y + 0.3 + 1.3
    obstacles.append(parked_car("car_p_west", 9.0 - 2.5 - 2.25, y_par, 0.0))
    obstacles.append(parked_car("car_p_east", 9.0 + 2.5 + 2.25, y_par, 0.0))
    objects.append({**spot("spot_p0", 9.0, y_par, 0.0, False), "geometry": {"box": [5.0, 2.6, 0.05]}})
    return {
        "name": "parking_3",
        "description": "A lot where feasibility for the car decides (issue #17): 5 free spots, all collision-free "
        "for a sliding car; a Reeds-Shepp car never gets into the parallel gap 5.0 m long, reaches one spot only by "
        "reversing in past a pillar, and the spot off the 3.5 m aisle only after long searches.",
        "robot": car_robot(3.5, (median_y + 0.3 + 2.6 + north_y) / 2, 0.0, W, H),
        "obstacles": obstacles,
        "objects": objects,
        "planner": planner(time_limit=20.0),
        "expect": [
            {"request": "park", "interpretations": ["park:spot_n4", "park:spot_n9", "park:spot_p0", "park:spot_s12", "park:spot_s2"],
             # an iteration budget, not the clock: seeds 0-9 need at most 18,335 iterations (seed 1); measured
             # 27/30 within the scene's 20 s on a loaded machine (benchmarks/RESULTS.md)
             "success_rate": 0.9, "seeds": 10, "max_iterations": 20000, "time_limit": 300.0,
             "reachable": ["spot_n4", "spot_n9", "spot_s12", "spot_s2"]},
        ],
    }


def main() -> None:
    for make in (parking_1, parking_2, parking_3):
        scene = make()
        path = ROOT / "yaml_scenes" / f"{scene['name']}.yaml"
        header = f"# Generated by tools/make_parking_scenes.py; edit that script, not this file.\n"
        path.write_text(header + yaml.safe_dump(scene, sort_keys=False, default_flow_style=None, width=120))
        print(f"wrote {path.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
