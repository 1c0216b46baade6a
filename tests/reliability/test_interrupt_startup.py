"""Ctrl-C while Python and Drake import (#20): one line, exit 130, never a traceback.

The signal is sent by the child itself at a chosen import (numpy, a pydrake submodule, ...),
so where it lands is fixed by the import order, not by a clock.
"""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from tests.reliability.conftest import REPO, needs_drake
from tests.reliability.test_interrupt import with_ctrl_c

CHILD = """\
import builtins, os, signal, sys
target, argv = sys.argv[1], sys.argv[2:]
real_import, sent = builtins.__import__, []

def importing(name, *args, **kwargs):
    if name == target and not sent:  # press Ctrl-C as this module starts importing
        sent.append(True)
        os.kill(os.getpid(), signal.SIGINT)
    return real_import(name, *args, **kwargs)

builtins.__import__ = importing
sys.argv = ["lazyground"] + argv
import runpy
runpy.run_module("lazyground", run_name="__main__")
"""


def _run(target: str, argv: list[str]) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(REPO))
    return subprocess.run([sys.executable, "-c", CHILD, target, *argv], cwd=REPO, capture_output=True, text=True,
                          timeout=120, env=env, preexec_fn=with_ctrl_c)


PLAN = ["plan", "yaml_scenes/parking_1.yaml", "park", "--time-limit", "30"]


@needs_drake
@pytest.mark.parametrize("target", ["lazyground.cli", "lazyground.settings", "numpy", "yaml", "lazyground.report",
                                    "pydrake.multibody.plant", "pydrake.planning"])
def test_ctrl_c_during_imports_is_one_line_and_exit_130(target):
    proc = _run(target, PLAN)
    lines = proc.stderr.strip().splitlines()
    assert proc.returncode == 130, proc.stderr[-2000:]
    assert lines == ["interrupted"], proc.stderr[-2000:]
    assert proc.stdout == ""


def test_the_child_really_presses_ctrl_c():
    """Without the entry point's handler the same child dies with a traceback: the test above can fail."""
    child = CHILD.replace('runpy.run_module("lazyground", run_name="__main__")', "import lazyground.cli")
    env = dict(os.environ, PYTHONPATH=str(REPO))
    proc = subprocess.run([sys.executable, "-c", child, "lazyground.settings"], cwd=REPO, capture_output=True, text=True,
                          timeout=120, env=env, preexec_fn=with_ctrl_c)
    assert proc.returncode != 0 and "KeyboardInterrupt" in proc.stderr
