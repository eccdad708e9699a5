"""Interruptions leave nothing behind and print no traceback (issue 14, item 9).

Each test runs the command line in a subprocess with this worktree's ``src`` first on the path.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import rotorlab

SRC = str(Path(rotorlab.__file__).resolve().parents[1])
ENV = {**os.environ, "PYTHONPATH": SRC + os.pathsep + os.environ.get("PYTHONPATH", "")}

TINY = textwrap.dedent('''
    schema_version = 1
    name = "tiny"
    [model]
    type = "jeffcott_balls"
    disc_mass = "1 kg"
    eccentricity = "1.5 mm"
    stiffness = "16.74 kN/m"
    damping = "13.32 N*s/m"
    [[model.balls]]
    mass = "30 g"
    radius = "50 mm"
    damping = "2e-3 N*m*s"
    count = 2
    [[analysis]]
    type = "simulate"
    name = "short"
    speed_ratio = 2.0
    initial_ball_angles = [["0 deg", "90 deg"]]
    t_end = "0.2 s"
    n_save = 20
''')


def test_sigterm_while_run_writes_its_output_leaves_no_temporary_folder(tmp_path):
    """SIGTERM arrives while ``run`` is writing the staging folder (sent from inside the writer,
    so the moment is exact): the command exits 143, and neither the output nor ``.OUT.tmp-*``
    remains."""
    (tmp_path / "tiny.toml").write_text(TINY)
    script = textwrap.dedent(f'''
        import os, signal, sys
        import rotorlab.report._write as w
        original = w._png
        def png(fig, dpi):
            data = original(fig, dpi)
            os.kill(os.getpid(), signal.SIGTERM)
            return data
        w._png = png
        sys.argv = ["rotorlab", "run", {str(tmp_path / "tiny.toml")!r}, "--out", {str(tmp_path / "out")!r}]
        from rotorlab.cli import main
        main()
    ''')
    done = subprocess.run([sys.executable, "-c", script], env=ENV, capture_output=True, text=True, timeout=600,
                          cwd=tmp_path)  # fmt: skip
    assert done.returncode == 143, done.stderr
    assert "Traceback" not in done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["tiny.toml"]


def _as_in_a_terminal() -> None:
    """SIGINT acts as in a terminal: a test runner started in the background inherits it ignored
    (and Python then leaves it ignored)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def test_ctrl_c_in_the_first_second_prints_no_traceback(tmp_path):
    """SIGINT 0.02, 0.2 and 0.6 s after the entry point is reached (while the command line
    imports typer, numpy and the commands, loads the case, or runs): exit 130, ``interrupted``,
    no traceback, no output folder.

    The entry point is what the ``rotorlab`` console script calls (``rotorlab.cli:main``); the
    script says ``ready`` just before calling it. Beyond any program's reach: a signal during the
    interpreter's own start-up (its ``site`` imports) or in the instant between the call and the
    first statement of ``main`` (a few bytecodes).
    """
    (tmp_path / "tiny.toml").write_text(TINY)
    procs = []
    for k, delay in enumerate((0.02, 0.2, 0.6)):
        out = tmp_path / f"out{k}"
        script = (f"import sys\nsys.argv = ['rotorlab', 'run', {str(tmp_path / 'tiny.toml')!r}, '--out', {str(out)!r}]\n"
                  "from rotorlab.cli import main\nsys.stderr.write('ready\\n')\nsys.stderr.flush()\nmain()\n")
        p = subprocess.Popen([sys.executable, "-c", script], env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True, cwd=tmp_path, preexec_fn=_as_in_a_terminal)  # fmt: skip
        assert p.stderr.readline() == "ready\n"
        time.sleep(delay)
        p.send_signal(signal.SIGINT)
        procs.append((p, delay, out))
    for p, delay, out in procs:
        _, err = p.communicate(timeout=600)
        assert p.returncode == 130, (delay, p.returncode, err)
        assert "Traceback" not in err and "interrupted" in err, (delay, err)
        assert not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["tiny.toml"]


def test_a_full_disk_while_run_writes_names_the_path_and_leaves_nothing(tmp_path, monkeypatch):
    """ENOSPC from the NetCDF writer (fault injected): exit 1 with the path and the reason, not an
    internal error; no output folder and no ``.OUT.tmp-*``."""
    import errno

    from typer.testing import CliRunner

    import rotorlab.io
    from rotorlab.cli import app

    (tmp_path / "tiny.toml").write_text(TINY)

    def full(ds, path):
        raise OSError(errno.ENOSPC, "No space left on device", str(path))

    monkeypatch.setattr(rotorlab.io, "save_netcdf", full)  # the report writer imports it when called
    res = CliRunner().invoke(app, ["run", str(tmp_path / "tiny.toml"), "--out", str(tmp_path / "out")])
    assert res.exit_code == 1, res.output
    assert "internal error" not in res.stderr and "Traceback" not in res.output
    assert "cannot write " in res.stderr and "short.nc: No space left on device" in res.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["tiny.toml"]


def _stop_latency(tmp_path, sig: int) -> tuple[float, subprocess.CompletedProcess, Path]:
    """Send ``sig`` to a basin running into a store, half a second into a chunk of a few seconds
    (after the first chunk is stored: the integrator is compiled), and return the seconds until
    the process ended, its result and the store."""
    from rotorlab.sweep import store_info

    store = tmp_path / "basin.zarr"
    cmd = [sys.executable, "-m", "rotorlab.cli", "basin", "autobalancer", "--x", "psi_1=0:360deg:60",
           "--y", "psi_2=0:360deg:60", "--t-end", "2000", "--chunk", "256", "--store", str(store)]
    proc = subprocess.Popen(cmd, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=tmp_path,
                            preexec_fn=_as_in_a_terminal)  # fmt: skip
    deadline = time.monotonic() + 500
    while proc.poll() is None and time.monotonic() < deadline:
        if (store / "zarr.json").exists() and store_info(store)["chunks_done"] >= 1:
            break
        time.sleep(0.05)
    assert proc.poll() is None, proc.communicate()[1]
    time.sleep(0.5)
    sent = time.monotonic()
    proc.send_signal(sig)
    out, err = proc.communicate(timeout=120)
    return time.monotonic() - sent, subprocess.CompletedProcess(cmd, proc.returncode, out, err), store


def test_sigterm_and_ctrl_c_stop_a_basin_within_a_second_and_keep_its_chunks(tmp_path):
    """A basin's chunk is one compiled call of seconds (of days' worth of starts, on the user's
    machine: SIGTERM took 20-45 s, issue 29). The chunk runs in a worker thread, the command line
    reacts in its main thread and leaves without the interpreter's teardown: SIGTERM and Ctrl-C
    act within a second, and the finished chunks stay in the store, ready for --resume."""
    from rotorlab.sweep import store_info

    for sig, code in ((signal.SIGTERM, 143), (signal.SIGINT, 130)):
        folder = tmp_path / signal.Signals(sig).name
        folder.mkdir()
        seconds, done, store = _stop_latency(folder, sig)
        assert done.returncode == code, done.stderr
        assert seconds < 1.5, f"{signal.Signals(sig).name} took {seconds:.2f} s to stop the basin"
        assert "Traceback" not in done.stderr
        meta = store_info(store)
        assert 1 <= meta["chunks_done"] < meta["n_chunks"] == 15  # 3600 starts in chunks of 256
        if sig == signal.SIGINT:
            assert f"{meta['chunks_done']} of 15 chunks are kept in {store}" in done.stderr
