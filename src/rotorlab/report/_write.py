"""Write the output folder of a run: report.html, one NetCDF per analysis, one PNG per figure."""

from __future__ import annotations

import contextlib
import io
import os
import shutil
import tempfile
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from rotorlab.report._html import render_report

if TYPE_CHECKING:
    import xarray
    from matplotlib.figure import Figure

    from rotorlab.io import Case

__all__ = ["write_report", "check_output_dir", "REPORT_NAME", "MANIFEST_NAME"]

#: File name of the HTML report inside the output folder.
REPORT_NAME = "report.html"

#: Hidden file listing the files a run wrote; the next run into the same folder removes those it
#: does not write again (and never touches any other file).
MANIFEST_NAME = ".rotorlab-files"


def _manifest(folder: Path) -> list[str]:
    try:
        lines = (folder / MANIFEST_NAME).read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError):
        return []
    return [n for n in lines if n and Path(n).name == n and not n.startswith(".")]


def check_output_dir(out_dir: str | os.PathLike[str]) -> Path:
    """Check that ``out_dir`` can be used as an output folder, without creating anything.

    Parameters
    ----------
    out_dir : str or os.PathLike

    Returns
    -------
    pathlib.Path

    Raises
    ------
    ValueError
        ``out_dir`` exists but is not a folder, or the nearest existing parent is not a folder
        or not writable.
    """
    target = Path(out_dir)
    if target.exists() and not target.is_dir():
        raise ValueError(f"--out {os.fspath(out_dir)}: exists and is not a folder")
    parent = target.absolute().parent
    while not parent.exists():
        parent = parent.parent
    if not parent.is_dir():
        raise ValueError(f"--out {os.fspath(out_dir)}: {parent} is not a folder")
    probe = target if target.is_dir() else parent
    if not os.access(probe, os.W_OK | os.X_OK):
        raise ValueError(f"--out {os.fspath(out_dir)}: {probe} is not writable")
    return target


def _apply_umask(staging: Path, names: Sequence[str]) -> None:
    """Give the staged folder and files the permissions a plain mkdir/open would have."""
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(staging, 0o777 & ~umask)
    for name in [*names, MANIFEST_NAME]:
        os.chmod(staging / name, 0o666 & ~umask)


def _png(fig: Figure, dpi: int) -> bytes:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    return buf.getvalue()


def _interactive(case: Case, figures: Mapping[str, Mapping[str, Figure]]) -> dict[str, dict[str, Any]]:
    """The Plotly twins of the figures of the analyses whose family is explored (``interactive``)."""
    from rotorlab.plot import to_plotly
    from rotorlab.report._presentations import presentation_of

    kinds = {a.name: a.type for a in case.analyses}
    return {name: {stem: to_plotly(fig) for stem, fig in by_stem.items()} for name, by_stem in figures.items()
            if name in kinds and presentation_of(kinds[name], case.model.type).interactive}


def write_report(
    out_dir: str | os.PathLike[str],
    case: Case,
    results: Mapping[str, xarray.Dataset],
    figures: Mapping[str, Mapping[str, Figure]],
    summary_tables: Mapping[str, Sequence[Mapping[str, Any]]],
    *,
    dpi: int = 100,
) -> Path:
    """Write a run's results, figures and a self-contained HTML report into a folder.

    Everything is first written into a temporary folder next to ``out_dir`` and moved into
    place only when all of it succeeded, so a failure leaves no partial output: a new
    ``out_dir`` is created by one rename; into an existing ``out_dir`` each finished file is
    moved with an atomic replace, then the files an earlier run wrote there (listed in
    :data:`MANIFEST_NAME`) and this one did not are removed; other files are left alone.

    Parameters
    ----------
    out_dir : str or os.PathLike
        Output folder (created with its parents if missing).
    case : rotorlab.io.Case
        The case that was run.
    results : mapping of str to xarray.Dataset
        By analysis name; each is saved as ``<name>.nc`` (:func:`rotorlab.io.save_netcdf`).
    figures : mapping of str to mapping of str to matplotlib.figure.Figure
        By analysis name, then by file stem (what the presentation's ``figures(ds, name)``
        returns); each is saved as ``<stem>.png`` and embedded in that analysis' section (as an
        interactive Plotly figure where the analysis' presentation is ``interactive``).
    summary_tables : mapping of str to list of dict
        By analysis name, rows of :func:`rotorlab.analyses.summarize`.
    dpi : int
        Resolution of the PNGs.

    Returns
    -------
    pathlib.Path
        Path of ``report.html``.

    Raises
    ------
    ValueError
        ``out_dir`` is not usable (see :func:`check_output_dir`), or a name would not make a
        plain file name.
    OSError
        The system refused a write (a full disk, permissions): its ``filename`` is the file of
        ``out_dir`` being written (nothing is left behind).
    """
    from rotorlab import _interrupt
    from rotorlab.io import dump_case, save_netcdf

    target = check_output_dir(out_dir)
    stems = [k for by_stem in figures.values() for k in by_stem]
    names = [f"{n}.nc" for n in results] + [f"{k}.png" for k in stems] + [REPORT_NAME]
    for name in names:
        if Path(name).name != name or name.startswith("."):
            raise ValueError(f"cannot write {name!r}: result and figure names must be plain file names")
    if len(set(names)) != len(names):
        raise ValueError(f"duplicate output file names: {sorted(names)}")
    parent = target.absolute().parent
    parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{target.name}.tmp-", dir=parent))
    writing = target  # the file being written, as the user will find it: named when the system refuses
    try:
        for name, ds in results.items():
            writing = target / f"{name}.nc"
            save_netcdf(ds, staging / f"{name}.nc")
        pngs: dict[str, dict[str, bytes]] = {}
        for name, by_stem in figures.items():
            for key, fig in by_stem.items():
                writing = target / f"{key}.png"
                pngs.setdefault(name, {})[key] = _png(fig, dpi)
                (staging / f"{key}.png").write_bytes(pngs[name][key])
        text = case.text or dump_case(case)
        page = render_report(case, results, pngs, summary_tables, names[:-1], text,
                             interactive=_interactive(case, figures))
        writing = target / REPORT_NAME
        (staging / REPORT_NAME).write_text(page, encoding="utf-8")
        writing = target / MANIFEST_NAME
        (staging / MANIFEST_NAME).write_text("".join(f"{n}\n" for n in names), encoding="utf-8")
        _apply_umask(staging, names)
        _interrupt.check()  # a Ctrl-C that Python swallowed: nothing is put in place
        writing = target
        if not target.exists():
            os.rename(staging, target)
        else:
            stale = set(_manifest(target)) - set(names)
            for name in [*names, MANIFEST_NAME]:
                os.replace(staging / name, target / name)
            staging.rmdir()
            for name in stale:
                with contextlib.suppress(FileNotFoundError):
                    (target / name).unlink()
    except OSError as exc:
        shutil.rmtree(staging, ignore_errors=True)
        if exc.filename is None or str(exc.filename).startswith(str(staging)):
            # a refused write (a full disk) says which file, as the user will look for it
            raise OSError(exc.errno, exc.strerror or str(exc), str(writing)) from exc
        raise
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    return target / REPORT_NAME
