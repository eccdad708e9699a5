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


# ---- terminal safety (issue 28, item 16): user text reaches the terminal only through clean_text --------------
HOSTILE = "\x1b[2J\x1b]0;pwned\x07\x1b[31m\x9b1m"


def _case_with(tmp_path, old: str, new: str) -> str:
    text = resources.files("rotorlab.cases").joinpath("autobalancer.toml").read_text(encoding="utf-8")
    assert old in text
    (tmp_path / "case.toml").write_text(text.replace(old, new, 1), encoding="utf-8")
    return str(tmp_path / "case.toml")


@pytest.mark.parametrize("kind", ["description", "unknown-key", "set-quoted-key", "set-value", "missing-path",
                                  "missing-path-no-schema", "unknown-option", "bad-count"])  # fmt: skip
def test_escape_sequences_from_a_case_or_the_command_line_never_reach_the_terminal(kind, tmp_path):
    esc = "\\u001b[2J\\u001b]0;pwned\\u0007"  # TOML escapes: the file holds the raw control characters
    argv = {
        "description": lambda: ["validate", _case_with(tmp_path, 'description = "', f'description = "{esc}washer ')],
        "unknown-key": lambda: ["validate", _case_with(tmp_path, 'frame = "fixed"', f'frame = "fixed"\n"{esc}red" = 1')],
        "set-quoted-key": lambda: ["validate", "autobalancer", "--set", f'model."{HOSTILE}red"=1'],
        "set-value": lambda: ["validate", "autobalancer", "--set", f"model.disc_mass=1 {HOSTILE}kg"],
        "missing-path": lambda: ["validate", str(tmp_path / f"{HOSTILE}x.toml")],
        "missing-path-no-schema": lambda: ["simulate", _case_with(tmp_path, "schema_version = 1\n",
                                                                  f'[model.x{esc}]\n'), "--t-end", "0.1"],
        "unknown-option": lambda: ["cases", f"--bogus{HOSTILE}"],
        "bad-count": lambda: ["basin", "autobalancer", "--workers", f"2{HOSTILE}"],
    }[kind]()
    res = runner.invoke(app, argv)
    out = res.stdout + res.stderr
    assert res.exit_code in (0, 2), out
    assert not any(c in out for c in "\x1b\x07\x9b"), repr(out)
    assert ("washer" in res.stdout) if kind == "description" else "error: " in res.stderr or "Error: " in res.stderr


def test_clean_text_is_the_one_sanitiser_show_and_every_echo_use():
    from rotorlab.cli import _output, _show

    assert _show.clean_text is _output.clean_text
    assert _output.clean_text("a" + HOSTILE + "b\tc") == "ab?c"
    assert _output.clean_text("one\x1b[2J\ntwo", lines=True) == "one\ntwo"


# ---- a full disk under rotorlab run (issue 28, item 15): the message names the file, nothing is left -------------
def test_run_on_a_full_disk_names_the_file_it_could_not_write_and_leaves_nothing(tmp_path, monkeypatch):
    import errno

    import rotorlab.io

    def full(ds, path):  # what a netCDF writer raises when the disk fills: errno without a file name
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(rotorlab.io, "save_netcdf", full)
    out = tmp_path / "report"
    res = runner.invoke(app, ["run", "pico21", "--out", str(out)])
    assert res.exit_code == 1, res.output
    assert "internal error" not in res.stderr and "Traceback" not in res.output
    assert f"error: cannot write {out / 'data-audit.nc'}: No space left on device" in res.stderr, res.stderr
    assert list(tmp_path.iterdir()) == []  # no report folder, no staging folder
