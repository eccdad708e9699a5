"""Edge messages and security notes (issue 14, items 10 and 11)."""

from __future__ import annotations

from importlib import resources

import pytest
from typer.testing import CliRunner

from rotorlab.cli import app
from rotorlab.cli._sweep_common import executor_from_options, scheduler_is_safe

runner = CliRunner()


def test_a_case_without_schema_version_is_read_with_a_warning_naming_the_allowed_value(tmp_path):
    text = resources.files("rotorlab.cases").joinpath("autobalancer.toml").read_text(encoding="utf-8")
    (tmp_path / "old.toml").write_text(text.replace("schema_version = 1\n", ""))
    res = runner.invoke(app, ["validate", str(tmp_path / "old.toml")])
    assert res.exit_code == 0, res.output
    assert "warning: " in res.stderr and "no schema_version" in res.stderr
    assert "schema_version = 1" in res.stderr and "OK: autobalancer" in res.stdout
    res = runner.invoke(app, ["validate", "autobalancer"])
    assert "warning" not in res.stderr


@pytest.mark.parametrize("address, safe", [
    ("tcp://127.0.0.1:8786", True), ("tcp://localhost:8786", True), ("tcp://[::1]:8786", True),
    ("tls://10.0.0.5:8786", True), ("tcp://10.0.0.5:8786", False), ("tcp://cluster.example.org:8786", False),
    ("ws://192.168.1.2:8786", False),
])  # fmt: skip
def test_which_scheduler_addresses_are_local_or_tls(address, safe):
    assert scheduler_is_safe(address) is safe


def test_a_remote_scheduler_without_tls_is_warned_about(capsys):
    executor_from_options("tcp://10.0.0.5:8786", None)
    err = capsys.readouterr().err
    assert "warning: --scheduler = tcp://10.0.0.5:8786" in err and "pickles" in err and "tls://" in err
    executor_from_options("tcp://127.0.0.1:8786", None)
    executor_from_options("tls://10.0.0.5:8786", None)
    assert capsys.readouterr().err == ""
