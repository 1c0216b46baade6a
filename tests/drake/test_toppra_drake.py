"""lazyground.motion.toppra gives Drake's Toppra's timing (same discretisation, exact two-variable LPs)."""

import numpy as np
import pytest
from pydrake.math import BsplineBasis
from pydrake.multibody.optimization import Toppra
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import PrismaticJoint, SpatialInertia, UnitInertia
from pydrake.trajectories import BsplineTrajectory

from lazyground.motion.curve import DEGREE, blended_curve
from lazyground.motion.toppra import toppra
from lazyground.motion.trajectory import _toppra_grid


def point_plant(dim):
    """dim prismatic joints in a chain: positions are the path's coordinates, q' = v."""
    plant = MultibodyPlant(0.0)
    parent = plant.world_body()
    for k in range(dim):
        body = plant.AddRigidBody(f"c{k}", SpatialInertia(1.0, np.zeros(3), UnitInertia(1.0, 1.0, 1.0)))
        plant.AddJoint(PrismaticJoint(f"c{k}", parent.body_frame(), body.body_frame(), [1.0, 0.0, 0.0]))
        parent = body
    plant.Finalize()
    return plant


@pytest.mark.parametrize("seed", range(6))
def test_it_times_blended_curves_as_drake_does(seed):
    rng = np.random.default_rng(seed)
    dim = 7
    path = np.cumsum(rng.uniform(-1.0, 1.0, (int(rng.integers(3, 7)), dim)), axis=0)
    velocity, acceleration = rng.uniform(0.5, 2.0, dim), rng.uniform(0.5, 3.0, dim)
    curve = blended_curve(path, 0.2)
    plant = point_plant(dim)
    spline = BsplineTrajectory(BsplineBasis(DEGREE + 1, list(curve.knots)), [c.reshape(-1, 1) for c in curve.control])
    for per_span in (3, 6):
        grid = _toppra_grid(curve, per_span)
        drake = Toppra(spline, plant, grid)
        drake.AddJointVelocityLimit(-velocity, velocity)
        drake.AddJointAccelerationLimit(-acceleration, acceleration)
        expected = drake.SolvePathParameterization()
        ours = toppra(curve.spline(1)(grid), curve.spline(2)(grid), grid, velocity, acceleration)
        assert ours.end_time() == pytest.approx(expected.end_time(), rel=1e-6)
        t = np.linspace(0.0, ours.end_time(), 300)
        s, sd, _ = ours.evaluate(t)
        assert np.allclose(s, expected.vector_values(t)[0], atol=1e-6)
        assert np.allclose(sd, expected.derivative(1).vector_values(t)[0], atol=1e-5 * np.max(sd))
