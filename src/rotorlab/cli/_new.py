"""``rotorlab new``: write a commented case file to start from (a template, or a ROSS rotor).

Imported by :mod:`rotorlab.cli`, which registers it on the shared :data:`~rotorlab.cli._app.app`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Optional

import typer

from rotorlab.cli._app import _settings, app
from rotorlab.cli._output import BadInput, handled, info

__all__ = ["new_command"]


@app.command("new")
def new_command(
    ctx: typer.Context,
    words: Annotated[Optional[list[str]], typer.Argument(  # noqa: UP007
        metavar="TEMPLATE NAME.toml",
        help="A template (centrifuge, washer, fe-rotor, two-plane) and the file to write; with "
             "--from-ross only NAME.toml.", show_default=False)] = None,
    from_ross: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--from-ross", metavar="ROTOR.toml",
        help="Import a rotor saved by ROSS (Rotor.save) as an fe_rotor case instead.")] = None,
    force: Annotated[bool, typer.Option("--force", help="Replace NAME.toml if it exists.")] = False,
) -> None:
    """Write a commented case file to start from: validates as written; edit it, then run it.

    Examples: rotorlab new washer my-washer.toml; rotorlab new --from-ross rotor.toml mine.toml.
    """
    settings = _settings(ctx)
    with handled(settings):
        from rotorlab.io import TEMPLATES, import_ross, ross_case_text, template_text, write_case_text

        words = list(words or ())
        allowed = ", ".join(TEMPLATES)
        if from_ross is not None:
            if len(words) != 1:
                raise BadInput(f"new --from-ross ROTOR.toml NAME.toml: give one NAME.toml, got "
                               f"{len(words)} argument(s) {words!r}")
            text, what = ross_case_text(import_ross(from_ross), from_ross), f"ROSS rotor {from_ross}"
        else:
            if len(words) != 2:
                raise BadInput(f"new TEMPLATE NAME.toml: give a template ({allowed}) and a file "
                               f"name, got {len(words)} argument(s) {words!r}")
            if words[0] not in TEMPLATES:
                raise BadInput(f"TEMPLATE = {words[0]!r}: unknown; allowed: {allowed}")
            text, what = template_text(words[0]), f"template {words[0]}"
        path = write_case_text(text, words[-1], force=force)
        info(settings, f"Wrote {path} ({what}); check it with: rotorlab validate {path}")
