"""The output folder of a run: one self-contained HTML report plus NetCDF results and PNGs.

The report has no network dependencies: CSS is inline and figures are embedded as base64
``data:`` URIs, or, for the figures people explore (Campbell and bifurcation diagrams, basin maps,
sweeps), as interactive Plotly twins with plotly.js inlined once, so the single ``report.html``
can be mailed or archived on its own. How each
analysis family is shown (figures, section, findings, console tables) is registered in
:data:`PRESENTATIONS` (see :mod:`rotorlab.report._presentations`).
"""

from rotorlab.report._findings import Findings
from rotorlab.report._presentations import PRESENTATIONS, Presentation, presentation_of, register_presentation
from rotorlab.report._impacts import impact_section, reconstructions_section
from rotorlab.report._html import parameter_rows, render_report, versions
from rotorlab.report._steady import seed_notes_section, steady_figures, steady_section
from rotorlab.report._write import MANIFEST_NAME, REPORT_NAME, check_output_dir, write_report

__all__ = [
    "Findings",
    "PRESENTATIONS",
    "Presentation",
    "presentation_of",
    "register_presentation",
    "MANIFEST_NAME",
    "REPORT_NAME",
    "check_output_dir",
    "impact_section",
    "reconstructions_section",
    "parameter_rows",
    "render_report",
    "seed_notes_section",
    "steady_figures",
    "steady_section",
    "versions",
    "write_report",
]
