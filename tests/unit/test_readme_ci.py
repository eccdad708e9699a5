"""The README's Quickstart, its Python example and .ci/run agree with each other and with the code."""

from __future__ import annotations

import contextlib
import io
import os
import re
import stat
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
README = (ROOT / "README.md").read_text(encoding="utf-8")
CI = ROOT / ".ci" / "run"

INSTALL_AND_RUN = "pip install . && rotorlab run"
INSTALL_AND_TEST = "pip install '.[test]' && pytest"


def _section(title: str) -> str:
    match = re.search(rf"^## {re.escape(title)}\n(.*?)(?=^## |\Z)", README, re.S | re.M)
    assert match, f"README has no '## {title}' section"
    return match[1]


def _blocks(text: str, lang: str) -> list[str]:
    return re.findall(rf"^```{lang}\n(.*?)^```", text, re.S | re.M)


def _command_lines(script: str) -> list[str]:
    lines = [line.strip() for line in script.splitlines()]
    return [line for line in lines if line and not line.startswith("#")]


def test_quickstart_has_exactly_the_two_command_lines():
    blocks = _blocks(_section("Quickstart"), "bash")
    assert len(blocks) == 1
    assert _command_lines(blocks[0]) == [INSTALL_AND_RUN, INSTALL_AND_TEST]


def test_ci_script_runs_the_readme_test_line():
    assert CI.is_file()
    assert os.stat(CI).st_mode & stat.S_IXUSR, ".ci/run must be executable"
    text = CI.read_text(encoding="utf-8")
    assert text.startswith("#!/usr/bin/env bash\n")
    commands = _command_lines(text)
    assert commands[0] == "set -euo pipefail"
    # from the repository root; Chromium for the browser tests when it is missing (never a
    # browser download); then the test dependencies and the whole suite
    assert commands[1] == 'cd "$(dirname "$0")/.."'
    assert "apt-get install -y --no-install-recommends chromium" in text
    quickstart_test_line = _command_lines(_blocks(_section("Quickstart"), "bash")[0])[1]
    assert commands[-1] == quickstart_test_line == INSTALL_AND_TEST


def test_python_example_prints_what_the_readme_says():
    section = _section("Python")
    code = _blocks(section, "python")
    expected = _blocks(section, "text")
    assert len(code) == 1 and len(expected) == 1
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code[0], "README.md", "exec"), {})  # noqa: S102 - our own README
    assert out.getvalue() == expected[0]


def test_cli_table_names_real_commands():
    from typer.main import get_command

    from rotorlab.cli import app

    documented = set(re.findall(r"^\| `rotorlab (\w[\w-]*)", _section("Command line"), re.M))
    registered = set(get_command(app).commands)
    assert documented == registered
    assert {"run", "simulate", "validate", "cases", "campbell", "modes"} <= registered


def test_case_file_example_is_valid():
    from rotorlab.io import parse_case

    toml = _blocks(_section("Case files"), "toml")
    assert len(toml) == 1
    case = parse_case(toml[0])
    assert case.name == "my-rotor" and case.model.n_balls == 2
    assert case.analyses[0].spin_speed(case.model) == 2.0 * case.model.critical_speed()
