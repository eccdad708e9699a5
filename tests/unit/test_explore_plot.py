"""Basin, fraction and restoring-force figures render from small Datasets."""

from __future__ import annotations

import io
import math

import numpy as np
import xarray as xr

from rotorlab.explore import basin_fractions
from rotorlab.models._toroidal_ball import strautmanis_torus
from rotorlab.plot._basin import basin_figure, fractions_figure, label_colors, restoring_force_figure


def _fake_basin():
    rng = np.random.default_rng(1)
    lab = rng.integers(0, 3, size=(4, 5, 2)).astype(np.int16)
    attrs = {"labels": ["working", "spare", "other"], "units": "1"}
    return xr.Dataset(
        {"label": (("dpsi", "psi", "horizon"), lab, attrs)},
        coords={"psi": ("psi", np.linspace(0, 6, 5), {"units": "rad"}),
                "dpsi": ("dpsi", np.linspace(-280, 140, 4), {"units": "rad/s"}),
                "horizon": ("horizon", [10.0, 20.0], {"units": "s"})},
        attrs={"fixed_alpha": 0.0},
    )  # fmt: skip


def _png(fig) -> bytes:
    buf = io.BytesIO()
    fig.savefig(buf, format="png")
    return buf.getvalue()


def test_basin_figure():
    ds = _fake_basin()
    fig = basin_figure(ds)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "ψ₀ (rad)" and ax.get_ylabel() == "ψ̇₀ (rad/s)"
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    frac = (ds.label.isel(horizon=-1).values == 0).mean()
    assert texts[0] == f"working ({frac:.1%})"
    assert "after 20 s" in ax.get_title() and "α₀ = 0" in ax.get_title()
    assert "after 10 s" in basin_figure(ds, horizon=10.0).axes[0].get_title()
    assert _png(fig)[:4] == b"\x89PNG"


def test_fractions_figure():
    fr = basin_fractions(_fake_basin())
    fig = fractions_figure({"k = 1e-5 m": fr, "k = 1e-4 m": fr})
    assert len(fig.axes[0].lines) == 6 and _png(fig)[:4] == b"\x89PNG"


def test_restoring_force_figure():
    ds = strautmanis_torus(1e-4).restoring_force(np.linspace(0.0, 2 * math.pi, 41))
    fig = restoring_force_figure(ds)
    assert fig.axes[0].get_xlabel() == "ring angle ψ (rad)" and _png(fig)[:4] == b"\x89PNG"


def test_colors():
    c = label_colors(["balanced", "side (0°, 0°)", "non-synchronous", "other"])
    assert len(set(c.values())) == 4 and c["other"] == "#bcbcbc"
