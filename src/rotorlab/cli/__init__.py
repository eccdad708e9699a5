"""The ``rotorlab`` command line (typer): ``run``, ``simulate``, ``campbell``, ``modes``,
``validate``, ``cases``, ``impacts``, ``impacts-sweep``, ``basin``, ``basin-stability``, ``design``, ``sweep``, ``show``,
``steady``, ``stability-chart``.

Importing this package is instant (the commands load on first use of :data:`app` or in
:func:`main`), so that :func:`main` guards the whole start-up: Ctrl-C while the command line is
still importing prints ``interrupted`` and exits 130 without a traceback, and SIGTERM unwinds
like an exception (temporary output folders are removed; exit 143).
"""

from __future__ import annotations

from typing import Any

__all__ = ["app", "main"]

#: Exit code after SIGTERM (128 + 15, the shell convention).
EXIT_TERMINATED = 143


def _load_app() -> Any:
    """Import every command module (each registers its commands on the app) and return the app."""
    from rotorlab.cli import _basin  # noqa: F401 - registers the basin command
    from rotorlab.cli import _basin_stability  # noqa: F401 - registers the basin-stability command
    from rotorlab.cli import _continuation  # noqa: F401 - registers the continue command
    from rotorlab.cli import _design  # noqa: F401 - registers the design command
    from rotorlab.cli import _impacts  # noqa: F401 - registers the impacts and impacts-sweep commands
    from rotorlab.cli import _linear  # noqa: F401 - registers the campbell and modes commands
    from rotorlab.cli import _margins  # noqa: F401 - registers the shock-margin and friction-margin commands
    from rotorlab.cli import _new  # noqa: F401 - registers the new command
    from rotorlab.cli import _run_up_design  # noqa: F401 - registers the run-up-design command
    from rotorlab.cli import _show  # noqa: F401 - registers the show command
    from rotorlab.cli import _steady  # noqa: F401 - registers the steady and stability-chart commands
    from rotorlab.cli import _sweep  # noqa: F401 - registers the sweep command
    from rotorlab.cli import _tolerances  # noqa: F401 - registers the tolerances command
    from rotorlab.cli._app import app

    return app


def __getattr__(name: str) -> Any:
    if name == "app":
        return _load_app()
    raise AttributeError(f"module 'rotorlab.cli' has no attribute {name!r}")


def _terminated(signum: int, frame: Any) -> None:
    raise SystemExit(EXIT_TERMINATED)


def main() -> None:
    """Run the ``rotorlab`` command line (the console-script entry point).

    Exit codes: 0 success, 1 internal error (or the system refused a write: the message names
    the path), 2 bad input, 3 ran but some results failed, 130 interrupted (Ctrl-C), 143
    terminated (SIGTERM).
    """
    import signal
    import sys
    import threading

    from rotorlab import _interrupt

    try:
        if threading.current_thread() is threading.main_thread():
            signal.signal(signal.SIGTERM, _terminated)
            signal.signal(signal.SIGINT, _interrupt.handler)
        app = _load_app()
        _interrupt.check()  # a Ctrl-C during the imports that Python swallowed
        app(prog_name="rotorlab")
    except KeyboardInterrupt:
        sys.stderr.write("interrupted\n")
        _stop(130)
    except SystemExit as exc:
        # typer turns a Ctrl-C outside a command's error handling (option parsing) into a silent
        # exit 130: say it
        from rotorlab.cli import _output

        if exc.code == 130 and not _output._interrupt_reported:
            sys.stderr.write("interrupted\n")
        if exc.code in (130, EXIT_TERMINATED):
            _stop(exc.code)
        raise


def _stop(code: int) -> None:
    """Exit with ``code`` at once after an interrupt (Ctrl-C, SIGTERM).

    Everything the command keeps is in place by now (the finished chunks of a sweep are in its
    store, temporary folders are removed while the exception unwinds); the interpreter's own
    teardown would take seconds more (garbage collection of the compiled integrator, a sweep
    chunk's parallel region still running in its worker thread: 2-5 s measured after SIGTERM),
    so the process leaves without it.
    """
    import os
    import sys

    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)
