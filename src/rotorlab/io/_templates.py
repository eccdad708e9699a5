"""Commented case files to start from (``rotorlab new``), and writing them without overwriting.

Each template is a TOML file in ``rotorlab/templates/`` whose comments give every key's meaning
and unit; it validates and runs as written. :data:`TEMPLATES` lists them with the built-in case
each is based on.
"""

from __future__ import annotations

import os
from importlib import resources
from pathlib import Path
from typing import Any

from rotorlab.io._errors import CaseError

__all__ = ["TEMPLATES", "template_text", "write_case_text", "ross_case_text"]

#: Template name -> one-line description (the file is ``templates/<name>.toml``).
TEMPLATES: dict[str, str] = {
    "centrifuge": "housing on rubber feet, rotor on a spindle, a two-ball balancer (from pico21-balancer)",
    "washer": "front loader: horizontal drum, gravity, balancer, motor, cabinet clearance "
              "(from washer-horizontal, washer-knock)",
    "fe-rotor": "finite-element shaft with two discs on damped bearings (from friswell-rotor)",
    "two-plane": "rigid rotor with two ball races against static and couple unbalance "
                 "(from rcfw-two-plane)",
}


def template_text(name: str) -> str:
    """Return the text of a template.

    Parameters
    ----------
    name : str
        One of :data:`TEMPLATES`.

    Raises
    ------
    CaseError
        An unknown name (the message lists the allowed ones).

    Examples
    --------
    >>> "center_at_rest = true" in template_text("washer")
    True
    """
    if name not in TEMPLATES:
        raise CaseError(f"template = {name!r}: unknown; allowed: {', '.join(TEMPLATES)}")
    return resources.files("rotorlab").joinpath("templates", f"{name}.toml").read_text("utf-8")


def write_case_text(text: str, path: str | Path, *, force: bool = False) -> Path:
    """Write a case file, refusing to replace an existing file unless ``force``.

    The text goes to a temporary file in the same folder that is then renamed, so a failed write
    leaves nothing behind.

    Parameters
    ----------
    text : str
    path : str or pathlib.Path
        Must end in ``.toml``; its folder must exist.
    force : bool
        Replace an existing file.

    Raises
    ------
    CaseError
        The path exists (without ``force``), is a folder, lacks ``.toml`` or its folder is
        missing.
    """
    path = Path(path)
    if path.suffix != ".toml":
        raise CaseError(f"NAME = {str(path)!r}: a case file must end in .toml")
    if path.is_dir():
        raise CaseError(f"NAME = {str(path)!r}: is a folder")
    if path.exists() and not force:
        raise CaseError(f"NAME = {str(path)!r}: the file exists; give --force to replace it")
    if not path.absolute().parent.is_dir():
        raise CaseError(f"NAME = {str(path)!r}: folder {path.absolute().parent} does not exist")
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        tmp.write_text(text, encoding="utf-8")
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)
    return path


def ross_case_text(doc: dict[str, Any], source: str | Path) -> str:
    """Return the TOML text of a case imported from ROSS (:func:`rotorlab.io.import_ross`)."""
    import tomli_w

    header = (
        f"# A rotor imported from {Path(source).name}, a file saved by ROSS (Rotor.save), by\n"
        "# `rotorlab new --from-ross`. Quantities carry their units; positions are ROSS's node\n"
        "# numbers (node = 0 at the left end of the shaft). ROSS's axial and torsional DOFs have no\n"
        "# counterpart here (rotorlab's shaft is lateral only). Add analyses below, e.g. a Campbell\n"
        "# diagram:\n"
        "#   [[analysis]]\n"
        '#   type = "campbell"\n'
        '#   stop = "5000 rpm"\n'
        "# Check it with `rotorlab validate NAME.toml`.\n\n"
    )
    return header + tomli_w.dumps(doc)
