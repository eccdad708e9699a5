"""The ``rotorlab`` command line (typer): ``run``, ``simulate``, ``campbell``, ``modes``,
``validate``, ``cases``, ``impacts``, ``impacts-sweep``.

Importing this package stays light (no numpy, numba, xarray or matplotlib), so that
``rotorlab --version`` answers in well under a second.
"""

from rotorlab.cli import _basin  # noqa: F401 - registers the basin command
from rotorlab.cli import _impacts  # noqa: F401 - registers the impacts and impacts-sweep commands
from rotorlab.cli import _linear  # noqa: F401 - registers the campbell and modes commands
from rotorlab.cli import _show  # noqa: F401 - registers the show command
from rotorlab.cli import _steady  # noqa: F401 - registers the steady and stability-chart commands
from rotorlab.cli import _sweep  # noqa: F401 - registers the sweep command
from rotorlab.cli._app import app, main

__all__ = ["app", "main"]
