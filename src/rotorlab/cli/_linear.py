"""The linear-rotordynamics commands: ``rotorlab campbell`` and ``rotorlab modes``.

Both run on a case whose model is a linear rotor (``multibody`` or ``fe_rotor``) or is built on one
(a ``machine``: the structure it was built from), take their
defaults from the case's first analysis of the same type, and print tables, or with ``--json``
only a JSON document on stdout. Imported by :mod:`rotorlab.cli`, which registers them on the
shared :data:`~rotorlab.cli._app.app`.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Annotated, Any, Optional

import typer

from rotorlab._constants import RAD_S_PER_RPM
from rotorlab.cli._app import CaseArg, JsonOpt, SetOpt, _load, _settings, app, model_of
from rotorlab.cli._options import check_plot_path, check_speed, count_option, parse_speed_range
from rotorlab.cli._output import BadInput, emit_json, handled, info, status, stdout

__all__ = ["campbell_command", "modes_command", "linear_tables", "write_figure"]

_WHIRL = {"F": "forward", "B": "backward", "M": "mixed"}
_LINEAR_MODELS = ("multibody", "fe_rotor")


def _linear_case(source: str, command: str, sets: list[str] | None = None, settings: Any = None) -> Any:
    loaded = _load(source, sets, settings)
    if loaded.model.linear_structure() is None:
        raise BadInput(f"case {loaded.name}: its model is '{loaded.model.type}'; {command} "
                       f"needs a linear rotor model ([model] type {' or '.join(_LINEAR_MODELS)}) or a "
                       "model built on one (machine: its structure)")
    return loaded


def _first(loaded: Any, kind: str) -> Any:
    return next((a for a in loaded.analyses if a.type == kind), None)


def _check_modes(modes: int | None, n_dof: int) -> None:
    if modes is not None and not 1 <= modes <= n_dof:
        raise BadInput(f"--modes = {modes}: must be an integer from 1 to {n_dof} (the model's "
                       "number of modes)")


def write_figure(fig: Any, path: Path) -> Path:
    """Save a figure atomically (a temporary file in the same folder, then a rename)."""
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=path.suffix,
                               dir=path.absolute().parent)
    os.close(fd)
    try:
        fig.savefig(tmp, dpi=120)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


def _table(title: str, header: Sequence[str], rows: Sequence[Sequence[str]],
           right: set[int] = frozenset()) -> Any:
    from rich.table import Table

    table = Table(title=title, title_justify="left")
    for j, name in enumerate(header):
        table.add_column(name, justify="right" if j in right else "left")
    for row in rows:
        table.add_row(*row)
    return table


def _g(value: float | None, digits: int = 6) -> str:
    return "-" if value is None else f"{value:.{digits}g}"


def _other_definition(r: Mapping[str, Any]) -> str:
    """The critical speed by the other definition, where it differs by more than 3 %."""
    damped = r["definition"] == "damped crossing"
    other = r["undamped_rpm"] if damped else r["damped_crossing_rpm"]
    if other is None:
        return "none (overdamped)" if not damped else "-"
    if not r["both_shown"]:
        return "within 3 %"
    return f"{other:.4g} ({'undamped' if damped else 'damped crossing'})"


def _crossing_table(title: str, rows: Sequence[Mapping[str, Any]]) -> Any:
    """Critical speeds: those unbalance excites first; the definition of each, the other
    definition's value where they differ, the mode's damping ratio and whirl; why a mode is not
    excited by unbalance in the caption."""
    notes = list(dict.fromkeys(r["note"] for r in rows if r["note"]))
    body = [(_g(r["speed_rpm"]), r["definition"], _other_definition(r), _g(r["damping_ratio"], 3),
             f"{r['harmonic']}x", str(r.get("mode", "-")), _WHIRL[r["whirl"]],
             "yes" if r["excited_by_unbalance"] else f"no {_MARKS[notes.index(r['note'])]}")
            for r in rows]
    table = _table(title, ("speed (rpm)", "definition", "other definition (rpm)", "damping ratio",
                           "line", "branch", "whirl", "excited by unbalance"), body, {0, 3})
    if notes:
        table.caption = "; ".join(f"{_MARKS[i]} {n}" for i, n in enumerate(notes))
        table.caption_justify = "left"
    return table


_MARKS = ("*", "**", "***", "+", "++", "#", "##", "###")


def _modes_table(title: str, rows: Sequence[Mapping[str, Any]]) -> Any:
    body = [(str(r["mode"]), _g(r["frequency_hz"]), _WHIRL[r["whirl"]],
             _g(r["damping_ratio"], 4), _g(r["log_decrement"], 4)) for r in rows]
    return _table(title, ("mode", "frequency (Hz)", "whirl", "damping ratio", "log decrement"),
                  body, {1, 3, 4})


def linear_tables(results: Mapping[str, Any], tables: Mapping[str, Sequence[Mapping[str, Any]]]
                  ) -> list[Any]:
    """Return rich tables summing up the linear results of a run (one per analysis)."""
    out = []
    for name, ds in results.items():
        kind, rows = ds.attrs.get("analysis"), tables[name]
        if kind in ("campbell", "critical_speeds"):
            out.append(_crossing_table(f"{name}: critical speeds", rows))
        elif kind == "modes":
            speed = float(ds.speed_rpm.values)
            out.append(_modes_table(f"{name}: modes at {speed:.6g} rpm", rows))
        elif kind == "unbalance_response":
            body = [(r["label"], "-" if r["peak_amplitude"] is None
                     else f"{r['peak_amplitude'] * 1e3:.4g}", _g(r["peak_speed_rpm"]))
                    for r in rows]
            out.append(_table(f"{name}: largest orbit", ("node", "semi-major axis (mm)",
                                                         "at speed (rpm)"), body, {1, 2}))
            if ds.attrs.get("note"):
                from rich.text import Text

                out.append(Text(f"{name}: {ds.attrs['note']}"))
        elif kind == "identify":
            body = [(r["parameter"], _g(r["initial"]), _g(r["value"]), r["unit"],
                     "-" if r["relative_std"] is None else f"{100 * r['relative_std']:.3g} %")
                    for r in rows]
            out.append(_table(f"{name}: identified (rms residual {ds.attrs['rms']:.2e})",
                              ("parameter", "start", "identified", "unit", "std"), body,
                              {1, 2, 4}))
        elif kind == "data_audit":
            body = [(r["finding"], r["printed"], r["resolved"]) for r in rows]
            out.append(_table(f"{name}: findings", ("finding", "as printed", "resolved as"),
                              body))
    return out


@app.command("campbell")
def campbell_command(
    ctx: typer.Context,
    case: CaseArg,
    sets: SetOpt = None,
    speeds_rpm: Annotated[Optional[str], typer.Option(  # noqa: UP007
        "--speeds-rpm", metavar="START:STOP:N",
        help="N equally spaced speeds from START to STOP (rpm); default: the case's campbell "
             "analysis.")] = None,
    modes: Annotated[Optional[int], count_option(  # noqa: UP007
        "--modes", metavar="K",
        help="Number of mode branches (default: the case's, or 6).")] = None,
    harmonic: Annotated[Optional[list[int]], count_option(  # noqa: UP007
        "--harmonic", metavar="H", help="Excitation line H x for critical speeds, added to the "
                                        "case's lines (or 1x); repeatable.")] = None,
    plot: Annotated[Optional[Path], typer.Option(  # noqa: UP007
        "--plot", metavar="FILE", help="Write the Campbell diagram (.png, .pdf or .svg).")] = None,
    json_out: JsonOpt = False,
) -> None:
    """Campbell diagram of a linear rotor: natural frequencies, whirl and critical speeds.

    JSON: {"speed_rpm": [...], "frequency_hz": [[per mode] per speed], "whirl": [["F"|"B"|"M",
    ...] per speed], "critical_speeds_rpm": [...]}.
    """
    settings = _settings(ctx)
    with handled(settings):
        rng = None if speeds_rpm is None else parse_speed_range(speeds_rpm)
        if plot is not None:
            check_plot_path(plot)
        loaded = _linear_case(case, "campbell", sets, settings)
        spec = _first(loaded, "campbell")
        if rng is None and spec is None:
            raise BadInput(f"case {loaded.name} has no campbell analysis: give --speeds-rpm "
                           "START:STOP:N")
        n_dof = loaded.model.linear_structure().n_dof
        _check_modes(modes, n_dof)
        from rotorlab.io import CampbellSpec

        start, stop, n = (rng[0] * RAD_S_PER_RPM, rng[1] * RAD_S_PER_RPM, rng[2]) if rng else (
            spec.start, spec.stop, spec.n_speeds)
        n_modes = modes or (spec.n_modes if spec is not None else 6)
        analysis = CampbellSpec(
            name=spec.name if spec is not None else "campbell", start=start, stop=stop,
            n_speeds=n, n_modes=min(n_modes, n_dof),
            harmonics=tuple(dict.fromkeys((*(spec.harmonics if spec is not None else (1,)),
                                           *(harmonic or ())))))
        info(settings, f"{loaded.name}: {analysis.describe(loaded.model)} ...",
             json_mode=json_out)
        from rotorlab.analyses import campbell_summary, run_linear_analysis, summarize_linear
        from rotorlab.io._built import built_model

        with status(settings, "Computing the Campbell diagram ..."):
            with built_model(loaded.model, model_of(loaded)):
                ds = run_linear_analysis(loaded.model, analysis)
        if plot is not None:
            from rotorlab.plot import campbell_figure

            write_figure(campbell_figure(ds, title=f"Campbell diagram: {loaded.name}"), plot)
        if json_out:
            emit_json(campbell_summary(ds))
            return
        con = stdout()
        con.print(_crossing_table(f"{loaded.name}: critical speeds", summarize_linear(ds)))
        doc = campbell_summary(ds)
        first, last = doc["speed_rpm"][0], doc["speed_rpm"][-1]
        body = [(str(k), _WHIRL[doc["whirl"][0][k]], _g(doc["frequency_hz"][0][k]),
                 _WHIRL[doc["whirl"][-1][k]], _g(doc["frequency_hz"][-1][k]))
                for k in range(len(doc["frequency_hz"][0]))]
        con.print(_table(f"{loaded.name}: natural frequencies (Hz)",
                         ("branch", f"whirl at {first:.6g} rpm", f"at {first:.6g} rpm",
                          f"whirl at {last:.6g} rpm", f"at {last:.6g} rpm"), body, {2, 4}))
        if plot is not None:
            con.print(f"Wrote {plot}", markup=False)


@app.command("modes")
def modes_command(
    ctx: typer.Context,
    case: CaseArg,
    sets: SetOpt = None,
    speed_rpm: Annotated[Optional[float], typer.Option(  # noqa: UP007
        "--speed-rpm", metavar="RPM", help="Spin speed (rpm); default: the case's modes "
                                           "analysis, or 0.")] = None,
    modes: Annotated[Optional[int], count_option(  # noqa: UP007
        "--modes", metavar="K", help="Number of modes, the lowest (default: all).")] = None,
    json_out: JsonOpt = False,
) -> None:
    """Complex modes of a linear rotor at one speed: frequency, whirl, damping.

    JSON: {"speed_rpm": X, "frequency_hz": [...], "whirl": ["F"|"B"|"M", ...],
    "damping_ratio": [...], "log_decrement": [...]}.
    """
    settings = _settings(ctx)
    with handled(settings):
        if speed_rpm is not None:
            check_speed(speed_rpm)
        loaded = _linear_case(case, "modes", sets, settings)
        _check_modes(modes, loaded.model.linear_structure().n_dof)
        spec = _first(loaded, "modes")
        from rotorlab.io import ModesSpec

        speed = speed_rpm * RAD_S_PER_RPM if speed_rpm is not None else (
            spec.speed if spec is not None else 0.0)
        analysis = ModesSpec(name="modes", speed=speed,
                             n_modes=modes if modes is not None else (
                                 spec.n_modes if spec is not None else None))
        from rotorlab.analyses import modes_summary, run_linear_analysis, summarize_linear
        from rotorlab.io._built import built_model

        with built_model(loaded.model, model_of(loaded)):
            ds = run_linear_analysis(loaded.model, analysis)
        if json_out:
            emit_json(modes_summary(ds))
            return
        stdout().print(_modes_table(f"{loaded.name}: modes at {speed / RAD_S_PER_RPM:.6g} rpm",
                                    summarize_linear(ds)))
