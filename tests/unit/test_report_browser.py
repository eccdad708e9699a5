"""The report of a machine case, opened as its reader opens it: in a real browser, offline.

The case is the README's "Put a balancer on your own rotor" (a disc on soft mounts with a
two-ball balancer: stability over speed and two start-ups) with a Campbell diagram added, run by
``rotorlab run``. Headless Chromium (the Debian package; ``tests/conftest.py``) opens the single
``report.html`` with every network request refused and checks what a reader relies on: the
verdict opens the page; the interactive Campbell diagram is drawn by the inlined plotly.js (no
network), its legend names
what is drawn, the value under the pointer is shown, a click on a legend entry hides its curve;
the machine's figures load, fit the page, and say in their legends what they draw.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from rotorlab.cli import app

ROOT = Path(__file__).resolve().parents[2]


def _readme_case(tmp_path: Path) -> Path:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    sec = re.search(r"^## Put a balancer on your own rotor\n(.*?)(?=^## )", readme, re.S | re.M)[1]
    (toml,) = re.findall(r"^```toml\n(.*?)^```", sec, re.S | re.M)
    toml += ('\n[[analysis]]\ntype = "campbell"\nname = "campbell"\nstop = "6000 rpm"\nn_speeds = 31\n'
             "n_modes = 4\n")
    path = tmp_path / "my-rotor.toml"
    path.write_text(toml, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def report(tmp_path_factory) -> Path:
    tmp = tmp_path_factory.mktemp("browser-report")
    result = CliRunner().invoke(app, ["-q", "run", str(_readme_case(tmp)), "--out", str(tmp / "out")])
    assert result.exit_code == 0, result.output
    return tmp / "out"


_CAMPBELL = """() => {
  const g = document.querySelector('figure.interactive[data-stem="campbell_campbell"] .js-plotly-plot');
  return {legend: [...g.querySelectorAll('.legend .legendtext')].map(e => e.textContent),
          names: g.data.map(t => t.name), xtitle: g.layout.xaxis.title.text,
          ytitle: g.layout.yaxis.title.text,
          critical: g.data.filter(t => t.name === 'critical speed').map(t => t.x)[0]};
}"""


def test_machine_report_in_a_browser(report, browser_page):
    import xarray as xr

    from rotorlab.plot import plotly_script

    html = (report / "report.html").read_text(encoding="utf-8")
    assert html.count(plotly_script()[:300]) == 1  # plotly.js inlined once, nothing fetched
    page = browser_page.open(report / "report.html")
    page.wait_for_function("document.querySelectorAll('figure.interactive .js-plotly-plot .main-svg').length > 0",
                           timeout=20_000)
    assert browser_page.requests == [], "the report fetched from the network"
    assert browser_page.errors == [], browser_page.errors
    # the verdict opens the page (report/_verdict.py), above every figure
    verdict = page.locator("section#verdict")
    assert verdict.is_visible() and page.locator("section#verdict .verdict-line").count() >= 1
    assert verdict.bounding_box()["y"] < page.locator("figure").first.bounding_box()["y"]
    # one interactive figure (the Campbell diagram); the machine's figures are images
    assert page.locator("figure.interactive").count() == 1
    stems = page.eval_on_selector_all("figure img", "els => els.map(e => e.alt)")
    assert sorted(stems) == ["stability-stability", "start-up-vibration"]

    # the Campbell diagram: its axes, its legend, and the critical speeds of the result
    fig = page.evaluate(_CAMPBELL)
    assert fig["xtitle"] == "spin speed (rev/min)" and fig["ytitle"] == "natural frequency (Hz)"
    assert set(fig["legend"]) == {"forward", "backward", "critical speed"}
    ds = xr.load_dataset(report / "campbell.nc")
    on_1x = ds.critical_speed_rpm.values[ds.critical_harmonic.values == 1]
    np.testing.assert_allclose(sorted(fig["critical"]), sorted(on_1x), rtol=1e-12)
    assert 1400 < min(on_1x) < 1600  # the disc on its mounts: sqrt(200 kN/m / 8 kg) = 158 rad/s = 1510 rpm

    # interactive: the pointer on the first critical speed shows its value; a legend click hides it
    graph = page.locator('figure.interactive[data-stem="campbell_campbell"] .js-plotly-plot')
    graph.scroll_into_view_if_needed()
    x, y = page.evaluate("""() => {
      const g = document.querySelector('figure.interactive .js-plotly-plot');
      const t = g.data.find(t => t.name === 'critical speed'), L = g._fullLayout;
      const r = g.querySelector('.nsewdrag').getBoundingClientRect();
      return [r.left + L.xaxis.l2p(t.x[0]), r.top + L.yaxis.l2p(t.y[0])];
    }""")
    page.mouse.move(x, y)
    page.wait_for_function("(document.querySelector('.hoverlayer') || {}).textContent?.includes('critical speed')",
                           timeout=5_000)
    hover = page.eval_on_selector(".hoverlayer", "e => e.textContent")
    assert f"{min(on_1x):.1f}"[:4] in hover.replace(",", ""), hover
    graph.locator(".legend .traces", has_text="critical speed").click()
    page.wait_for_function("""() => document.querySelector('figure.interactive .js-plotly-plot')
                              .data.find(t => t.name === 'critical speed').visible === 'legendonly'""",
                           timeout=5_000)  # a legend click acts after plotly's double-click delay

    # every figure is decoded and fits in the page (no horizontal scrolling)
    sizes = page.eval_on_selector_all(
        "figure img, figure.interactive .js-plotly-plot",
        "els => els.map(e => [e.naturalWidth ?? 1, e.getBoundingClientRect().right])")
    width = page.evaluate("document.documentElement.clientWidth")
    assert all(n > 0 and right <= width for n, right in sizes), (sizes, width)
