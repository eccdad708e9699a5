"""Matplotlib figures of rotorlab results (Datasets in, ``Figure`` objects out).

Numerics never import this package. Figures are made without pyplot (Agg canvas), so importing
or using it changes no global matplotlib state.
"""

from rotorlab.plot._absorber import absorber_response_figure
from rotorlab.plot._basin import basin_figure, basin_figures, fractions_figure, restoring_force_figure, sweep_figures
from rotorlab.plot._continuation import bifurcation_figure, continuation_figures, two_parameter_figure
from rotorlab.plot._campbell import WHIRL_STYLES, campbell_figure
from rotorlab.plot._impacts import impact_figures, impact_sweep_figure, p_trajectory_figure
from rotorlab.plot._linear import linear_figures, mode_shapes_figure, unbalance_response_figure
from rotorlab.plot._machine import machine_figures, shown_stations
from rotorlab.plot._plotly import plotly_script, to_plotly
from rotorlab.plot._stability import run_up_figure, stability_chart_figure, verify_figure
from rotorlab.plot._simulate import (
    amplitude_figure,
    ball_angle_figure,
    configuration_label,
    final_positions_figure,
    orbit_figure,
    simulation_figures,
    speed_label,
)

__all__ = [
    "WHIRL_STYLES",
    "absorber_response_figure",
    "amplitude_figure",
    "ball_angle_figure",
    "basin_figure",
    "basin_figures",
    "bifurcation_figure",
    "campbell_figure",
    "continuation_figures",
    "configuration_label",
    "final_positions_figure",
    "fractions_figure",
    "impact_figures",
    "impact_sweep_figure",
    "p_trajectory_figure",
    "plotly_script",
    "linear_figures",
    "machine_figures",
    "mode_shapes_figure",
    "orbit_figure",
    "restoring_force_figure",
    "run_up_figure",
    "simulation_figures",
    "speed_label",
    "stability_chart_figure",
    "shown_stations",
    "sweep_figures",
    "to_plotly",
    "two_parameter_figure",
    "unbalance_response_figure",
    "verify_figure",
]
