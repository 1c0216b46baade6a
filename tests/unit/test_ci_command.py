"""CI runs the README's test command exactly (.ci/run), and what that command needs is in the `test` extra."""

import re
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def readme_test_command() -> str:
    text = (ROOT / "README.md").read_text()
    block = re.search(r"Run the tests:\n\n```bash\n(.*?)\n```", text, re.S)
    assert block, "README.md: no 'Run the tests:' block"
    return block.group(1).strip()


def test_ci_runs_the_readme_test_command():
    command = readme_test_command()
    lines = [ln.strip() for ln in (ROOT / ".ci/run").read_text().splitlines() if not ln.lstrip().startswith("#")]
    assert command in lines


def test_the_test_extra_holds_what_the_command_uses():
    extra = " ".join(tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"]["test"])
    command = readme_test_command()
    assert "pip install -e '.[test]'" in command and "pytest" in extra
    if re.search(r"\s-n\s", command):  # pytest-xdist's workers
        assert "pytest-xdist" in extra
