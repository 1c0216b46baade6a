"""#31: lazyground.motion.toppra times a curve as Drake's Toppra did (joint velocity and acceleration limits)."""

import numpy as np
import pytest

pytest.importorskip("pydrake")

from pydrake.math import BsplineBasis  # noqa: E402
from pydrake.multibody.optimization import Toppra  # noqa: E402
from pydrake.multibody.plant import MultibodyPlant  # noqa: E402
from pydrake.multibody.tree import PrismaticJoint, SpatialInertia, UnitInertia  # noqa: E402
from pydrake.trajectories import BsplineTrajectory  # noqa: E402

from lazyground.motion.curve import DEGREE, blended_curve  # noqa: E402
from lazyground.motion.toppra import toppra  # noqa: E402


def point_plant(dim: int):
    """A chain of prismatic joints: positions are the path's coordinates (q̇ = v, no dynamics involved)."""
    plant = MultibodyPlant(0.0)
    parent = plant.world_body()
    for k in range(dim):
        body = plant.AddRigidBody(f"c{k}", SpatialInertia(1.0, np.zeros(3), UnitInertia(1.0, 1.0, 1.0)))
        plant.AddJoint(PrismaticJoint(f"c{k}", parent.body_frame(), body.body_frame(), [1.0, 0.0, 0.0]))
        parent = body
    plant.Finalize()
    return plant


@pytest.mark.parametrize("seed", range(8))
def test_the_duration_is_drakes(seed):
    rng = np.random.default_rng(seed)
    dim = 8
    curve = blended_curve(rng.uniform(-1.5, 1.5, (rng.integers(3, 8), dim)), float(rng.choice([0.2, 0.07, 0.02])))
    v, a = rng.uniform(0.3, 2.0, dim), rng.uniform(0.5, 3.0, dim)
    grid = curve.grid(3)
    plant = point_plant(dim)
    path = BsplineTrajectory(BsplineBasis(DEGREE + 1, list(curve.knots)), [c.reshape(-1, 1) for c in curve.control])
    drake = Toppra(path, plant, grid)
    drake.AddJointVelocityLimit(-v, v)
    drake.AddJointAccelerationLimit(-a, a)
    expected = drake.SolvePathParameterization()
    ours = toppra(grid, curve.spline(1)(grid), curve.spline(2)(grid), v, a)
    assert ours.end_time() == pytest.approx(expected.end_time(), rel=1e-6)
