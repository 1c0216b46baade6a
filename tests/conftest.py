"""Suite-wide fixtures: outcomes are driven by iteration counts and seeds, never by the clock.

IK goal sampling bounds each attempt by a time budget (``IKSettings.attempt_budget``)
as well as by restarts and solver iterations; under load (a shared CI machine) the
budget would cut attempts short and change which samples a seed yields. The suite
runs every IK goal source built without explicit settings with no time budget, so an
attempt is bounded by ``restarts`` x ``major_iterations`` alone.
"""

from __future__ import annotations

import importlib.util
from dataclasses import replace

import pytest


def bound_ik_by_counts(patch: pytest.MonkeyPatch | None = None) -> None:
    """Make IK goal sources built without settings use no time budget (idempotent).

    Args:
        patch: records the change so it can be undone; None sets it for the process
            (worker processes of a test).
    """
    from lazyground.drake import ik

    bound = replace(ik.DEFAULT_IK_SETTINGS, attempt_budget=None)
    if patch is None:
        ik.DEFAULT_IK_SETTINGS = bound
    else:
        patch.setattr(ik, "DEFAULT_IK_SETTINGS", bound)


@pytest.fixture(autouse=True, scope="session")
def iteration_bound_ik():
    """IK attempts bounded by counts only (see the module docstring); a no-op without pydrake."""
    if importlib.util.find_spec("pydrake") is None:
        yield
        return
    patch = pytest.MonkeyPatch()
    bound_ik_by_counts(patch)
    yield
    patch.undo()
