"""The presentation registry: how each analysis family is shown (figures, report, console).

Each analysis type (:data:`rotorlab.analyses.ANALYSIS_TYPES`) names a ``family``; this registry
holds one :class:`Presentation` per family. ``rotorlab run`` and the report loop over results and
look their presentation up; nothing branches on a type string.

For implementers
----------------
1. Reuse a family when its figures, tables and findings already fit your analysis (e.g. a new
   basin-like analysis whose rows are :func:`rotorlab.analyses.basin_rows`). Otherwise:
2. Write the four functions (plot functions stay in :mod:`rotorlab.plot`, console tables in
   :mod:`rotorlab.cli`; name them as ``lazy("module:function")`` so that registering imports
   neither matplotlib nor the command line):

   - ``figures(ds, name) -> {file stem: Figure}``: the figures of one result (stems usually
     start with ``name``; they are shown with that analysis only);
   - ``section(ds, rows) -> str``: the HTML of its results (tables, sentences) in the report;
   - ``findings(ds, rows) -> Findings``: the verdict in words and the key numbers with units,
     shown first in the report (:mod:`rotorlab.report._findings`);
   - ``console(results, rows) -> [rich tables]``: what ``rotorlab run`` prints for all results
     of the family (``results`` and ``rows`` by analysis name); ``console_detail`` the same
     for ``-v``.

3. Optionally ``notes(results) -> str``: one report section after all analyses (shown when the
   case has an analysis of the family), e.g. the seeds' typos; and ``interactive=True`` when its
   figures are explored rather than read (the report then shows them as Plotly figures).
4. ``register_presentation(Presentation("my-family", ...))`` and give your
   :class:`rotorlab.analyses.AnalysisType` ``family="my-family"``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from rotorlab._registry import Registry, lazy
from rotorlab.report._findings import (
    Findings,
    basin_findings,
    impact_findings,
    linear_findings,
    simulation_findings,
    steady_findings,
)

__all__ = ["Presentation", "PRESENTATIONS", "register_presentation", "presentation_of"]

Rows = Sequence[Mapping[str, Any]]


def no_tables(results: Mapping[str, Any], rows: Mapping[str, Rows]) -> list[Any]:
    """A console function that prints nothing."""
    return []


@dataclass(frozen=True)
class Presentation:
    """How one analysis family is shown (see the module's "For implementers" list).

    Parameters
    ----------
    family : str
        Its key (the ``family`` of :class:`rotorlab.analyses.AnalysisType`).
    figures : callable
        ``figures(ds, name) -> dict of file stem to matplotlib Figure``.
    section : callable
        ``section(ds, rows) -> str``: HTML of one result.
    findings : callable
        ``findings(ds, rows) -> Findings``.
    console : callable
        ``console(results, rows) -> list`` of rich renderables for ``rotorlab run``.
    console_detail : callable
        The same, printed with ``-v`` only.
    notes : callable, optional
        ``notes(results) -> str``: one report section after the analyses.
    interactive : bool
        Its figures are explored rather than read (Campbell and bifurcation diagrams, basin maps,
        sweep results): the report shows each as an interactive Plotly figure
        (:func:`rotorlab.plot.to_plotly`), the PNG is still written.
    """

    family: str
    figures: Callable[[Any, str], Mapping[str, Any]]
    section: Callable[[Any, Rows], str]
    findings: Callable[[Any, Rows], Findings]
    console: Callable[[Mapping[str, Any], Mapping[str, Rows]], list[Any]] = no_tables
    console_detail: Callable[[Mapping[str, Any], Mapping[str, Rows]], list[Any]] = no_tables
    notes: Callable[[Mapping[str, Any]], str] | None = None
    interactive: bool = False


#: Presentations by family, in the order ``rotorlab run`` prints them.
PRESENTATIONS: Registry[Presentation] = Registry("presentation family")


def register_presentation(entry: Presentation, *, replace: bool = False) -> None:
    """Add a :class:`Presentation` to :data:`PRESENTATIONS` (ValueError if its family is taken)."""
    PRESENTATIONS.register(entry.family, entry, replace=replace)


def presentation_of(kind: str, model_type: str | None = None) -> Presentation:
    """The presentation of analysis type ``kind`` on a ``model_type`` model (KeyError naming what
    is registered); see :func:`rotorlab.analyses.analysis_entry`."""
    from rotorlab.analyses import analysis_entry

    return PRESENTATIONS[analysis_entry(model_type, kind).family]


# --------------------------------------------------------------------------- the built-in families


def _linear_section(ds: Any, rows: Rows) -> str:
    from rotorlab.report._linear import linear_section
    from rotorlab.report._table import table

    return linear_section(ds.attrs["analysis"], ds, rows, table)


def _basin_section(ds: Any, rows: Rows) -> str:
    from rotorlab.report._basin import basin_section
    from rotorlab.report._table import table

    return basin_section(ds, rows, table)


def _basin_notes(results: Mapping[str, Any]) -> str:
    from rotorlab.report._basin import basin_comparison_section
    from rotorlab.report._table import table

    return basin_comparison_section(results, table)


def _impact_section(ds: Any, rows: Rows) -> str:
    from rotorlab.report._impacts import impact_section

    return impact_section(ds)


def _steady_notes(results: Mapping[str, Any]) -> str:
    from rotorlab.report._steady import seed_notes_section

    return seed_notes_section()


def _impact_notes(results: Mapping[str, Any]) -> str:
    from rotorlab.report._impacts import reconstructions_section

    return reconstructions_section()


for _entry in (
    Presentation("simulate", lazy("rotorlab.plot:simulation_figures"),
                 lazy("rotorlab.report._simulate:simulation_section"), simulation_findings,
                 lazy("rotorlab.cli._output:simulation_tables"),
                 lazy("rotorlab.cli._output:simulation_detail_tables")),
    Presentation("steady", lazy("rotorlab.report._steady:steady_figures"),
                 lazy("rotorlab.report._steady:steady_section"), steady_findings,
                 lazy("rotorlab.cli._steady:steady_tables"), notes=_steady_notes),
    Presentation("basin", lazy("rotorlab.plot:basin_figures"), _basin_section, basin_findings,
                 lazy("rotorlab.cli._basin:basin_tables"), notes=_basin_notes, interactive=True),
    Presentation("basin-stability", lazy("rotorlab.plot._basin_stability:basin_stability_figures"),
                 lazy("rotorlab.report._basin_stability:basin_stability_section"),
                 lazy("rotorlab.report._basin_stability:basin_stability_findings"),
                 lazy("rotorlab.report._basin_stability:basin_stability_tables"), interactive=True),
    Presentation("impacts", lazy("rotorlab.plot:impact_figures"), _impact_section, impact_findings,
                 lazy("rotorlab.cli._impacts:impact_tables"), notes=_impact_notes),
    Presentation("linear", lazy("rotorlab.plot:linear_figures"), _linear_section, linear_findings,
                 lazy("rotorlab.cli._linear:linear_tables"), interactive=True),
    Presentation("machine", lazy("rotorlab.plot._machine:machine_figures"),
                 lazy("rotorlab.report._machine:machine_section"),
                 lazy("rotorlab.report._machine:machine_findings"),
                 lazy("rotorlab.cli._machine:machine_tables")),
    Presentation("rub", lazy("rotorlab.plot._rub:rub_figures"), lazy("rotorlab.report._rub:rub_section"),
                 lazy("rotorlab.report._rub:rub_findings"), lazy("rotorlab.cli._rub:rub_tables")),
    Presentation("rub-map", lazy("rotorlab.plot._rub:rub_map_figures"), lazy("rotorlab.report._rub:rub_map_section"),
                 lazy("rotorlab.report._rub:rub_map_findings"), lazy("rotorlab.report._rub:rub_map_tables"),
                 interactive=True),
    Presentation("continuation", lazy("rotorlab.plot._continuation:continuation_figures"),
                 lazy("rotorlab.report._continuation:continuation_section"),
                 lazy("rotorlab.report._continuation:continuation_findings"),
                 lazy("rotorlab.cli._continuation:continuation_tables"), interactive=True),
    Presentation("knock", lazy("rotorlab.report._knock:knock_figures"), lazy("rotorlab.report._knock:knock_section"),
                 lazy("rotorlab.report._knock:knock_findings"), lazy("rotorlab.report._knock:knock_tables")),
    Presentation("shock-margin", lazy("rotorlab.plot._margins:shock_margin_figures"),
                 lazy("rotorlab.report._margins:shock_margin_section"),
                 lazy("rotorlab.report._margins:shock_margin_findings"),
                 lazy("rotorlab.report._margins:shock_margin_tables")),
    Presentation("friction-margin", lazy("rotorlab.plot._margins:friction_margin_figures"),
                 lazy("rotorlab.report._margins:friction_margin_section"),
                 lazy("rotorlab.report._margins:friction_margin_findings"),
                 lazy("rotorlab.report._margins:friction_margin_tables")),
    Presentation("design", lazy("rotorlab.plot._design:design_figures"), lazy("rotorlab.report._design:design_section"),
                 lazy("rotorlab.report._design:design_findings"), lazy("rotorlab.report._design:design_tables")),
    Presentation("tolerances", lazy("rotorlab.plot._tolerances:tolerances_figures"),
                 lazy("rotorlab.report._tolerances:tolerances_section"),
                 lazy("rotorlab.report._tolerances:tolerances_findings"),
                 lazy("rotorlab.report._tolerances:tolerances_tables")),
):  # fmt: skip
    register_presentation(_entry)
