"""The documentation site builds from the repository, warnings as errors, tutorials executed.

``python -m sphinx -W -b html docs OUT`` is what CI checks here: every tutorial (MyST notebooks
under ``docs/tutorials``) runs in a Jupyter kernel, an error in any cell or any Sphinx warning
(a broken reference, a malformed docstring in the API reference) fails the build. The checks
after the build read the executed pages: the FE rotor of the Python tutorial and of the TOML
tutorial have the same Campbell critical speeds, every built-in case has its page, and the
case-file key reference is generated from the schema.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from html import unescape
from pathlib import Path

import pytest

from rotorlab.io import builtin_cases
from rotorlab.io._reference import case_keys

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"


def _text(page: Path) -> str:
    """The text of an HTML page (tags removed, entities decoded)."""
    return unescape(re.sub(r"<[^>]+>", "", page.read_text(encoding="utf-8")))


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("docs")
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    done = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-E", "-q", "-b", "html",
         "-d", str(out / "doctrees"), str(DOCS), str(out / "html")],
        capture_output=True, text=True, env=env, timeout=600)
    messages = "\n".join(line for line in (done.stdout + done.stderr).splitlines()
                         if "IPKernelApp" not in line)
    assert done.returncode == 0, f"the docs build failed:\n{messages[-6000:]}"
    return out / "html"


def _critical_rpm(page: Path) -> list[float]:
    match = re.search(r"critical speeds[^:]*\(rpm\):\s*\[([^\]]*)\]", _text(page))
    assert match, f"{page.name} prints no critical speeds"
    return [float(v) for v in match.group(1).split()]


def test_fe_rotor_tutorials_agree(site):
    # The Python and the TOML tutorial define the same rotor: the same critical speeds on the
    # 1x line (four: the backward and forward whirl of the two lowest bending modes).
    python = _critical_rpm(site / "tutorials" / "fe-rotor-python.html")
    toml = _critical_rpm(site / "tutorials" / "fe-rotor-toml.html")
    assert len(python) == 4
    assert python == toml
    # Each tutorial shows its figures (Campbell, modes, response; basin map).
    for page, n in (("fe-rotor-python", 3), ("fe-rotor-toml", 1), ("basin-dask", 1)):
        assert (site / "tutorials" / f"{page}.html").read_text().count("<img") >= n, page


def test_basin_on_dask_is_identical(site):
    text = _text(site / "tutorials" / "basin-dask.html")
    assert "identical labels: True" in text


def test_every_builtin_case_has_a_page(site):
    for name, description in builtin_cases().items():
        page = site / "cases" / f"{name}.html"
        assert page.exists(), f"docs/cases/{name}.md is missing"
        assert description in _text(page)


def test_case_keys_page_is_the_schema(site):
    text = _text(site / "reference" / "case-keys.html")
    keys = case_keys()
    for where in ("model", "analysis"):
        for kind, rows in keys[where].items():
            assert f'type = "{kind}"' in text
            for row in rows:
                assert row.path in text, (kind, row.path)
    # One row read back: a shaft section's length is a length in m, > 0, required.
    assert re.search(r"shaft\[\]\.length\s*length \(m\)\s*> 0\s*required", text)


def test_balancer_tutorial_balances_where_the_closed_form_says(site):
    # Two equal balls of mass m on radius R cancel an unbalance U at their station at
    # +-(180 deg - arccos(U / (2 m R))) = +-120 deg for U / (2 m R) = 0.5 (the tutorial's numbers).
    page = site / "tutorials" / "balancer.html"
    text = _text(page)
    assert re.search(r"balanced ball angles \(deg\): \[240\.\s+120\.\]", text), text[:2000]
    finals = re.findall(r"final ball angles \(deg\): \[\s*([^\s,]+),?\s+([^\s,]+?)\s*\]", text)
    assert len(finals) == 3  # Python at 2500 and 1000 rpm, then rotorlab run at 2500 rpm
    fast, slow, cli = [[float(v) for v in pair] for pair in finals]
    assert cli == pytest.approx(fast, abs=0.01)
    assert sorted(fast) == pytest.approx([-120.0, 120.0], abs=0.5)  # the start-up at 2500 rpm balances
    assert abs(slow[0] - slow[1]) < 1.0 and abs(slow[0]) < 60.0  # at 1000 rpm both balls gather
    assert "same parameters: True" in text and "same stability map: True" in text
    # below the first critical speed (1261 rpm) the balanced state is unstable, at 2500 rpm stable
    stable = re.search(r"stable at \(rpm\): \[([^\]]*)\]", text).group(1).split()
    assert min(float(v) for v in stable) > 1261.0 and "2500." in stable
    # too light balls: the best state leaves U - 2 m R = 20 % of the unbalance
    partial, expected = re.search(r"vibration at disc 1: (\S+) um \(20 % of the unbalance response: (\S+) um\)",
                                  text).groups()
    assert float(partial) == pytest.approx(float(expected), rel=0.05)
    assert page.read_text().count("<img") >= 1
    assert "(exit code 2)" in text and "model.races has 1 entry" in text
    # rotorlab run on the case file of the same machine: the same stable speeds, the start-up balances
    cli = re.search(r"rotorlab run: stable at \(rpm\): \[([^\]]*)\]", text).group(1).replace(",", " ").split()
    assert [float(v) for v in cli] == [float(v) for v in stable]
    assert "rotorlab run: start-up balanced" in text


def test_api_pages_list_inherited_methods(site):
    # Every element on the rotorlab.linear page documents the whole AbstractElement contract,
    # also the matrices it inherits (Bearing's and ElasticConnection's zero M and G from one
    # massless base): the API pages are built with :inherited-members:.
    page = (site / "api" / "linear.html").read_text(encoding="utf-8")
    for cls in ("ShaftElement", "RigidBody", "Bearing", "ElasticConnection"):
        for member in ("M", "C", "K", "G"):
            assert f'id="rotorlab.linear.{cls}.{member}"' in page, f"{cls}.{member}"
    # The same for the speed profiles: each lists the time functions it shares with the others.
    page = (site / "api" / "models.html").read_text(encoding="utf-8")
    for cls in ("ConstantSpeed", "LinearRamp", "HillRunUp"):
        for member in ("spin_angle", "spin_speed", "spin_acceleration", "revolution_times"):
            assert f'id="rotorlab.models.{cls}.{member}"' in page, f"{cls}.{member}"


def test_api_models_page_opens_with_the_user_classes(site):
    # The rotorlab.models page shows the models users build (the machine and its parts first)
    # before the interfaces for implementers of a new model (issue 29: it opened with kernel
    # internals).
    page = (site / "api" / "models.html").read_text(encoding="utf-8")
    where = {name: page.index(f'id="rotorlab.models.{name}"') for name in
             ("Machine", "BallRace", "JeffcottBalls", "AbstractModel", "Kernels", "EventSpec")}
    assert max(where["Machine"], where["BallRace"], where["JeffcottBalls"]) < min(
        where["AbstractModel"], where["Kernels"], where["EventSpec"])
    assert where["Machine"] == min(where.values())


# what the landing page asks, each answered by one figure (docs/index.md)
QUESTIONS = ("1. At which speeds does my machine resonate?",
             "2. Will its automatic balancer balance it, and from which start-ups?",
             "3. Will the drum strike the cabinet while it runs up?")

_SECTIONS = """() => [...document.querySelectorAll('article section h3')].map(h => {
  const imgs = [...h.closest('section').querySelectorAll('img')];
  return [h.textContent.replace(/[#¶]$/, '').trim(), imgs.map(i => [i.naturalWidth, i.getBoundingClientRect().right])];
})"""

# code cells (their input; outputs may scroll) whose text is wider than their box
_CUT_CODE = """() => [...document.querySelectorAll('div.highlight pre')].filter(e => !e.closest('.cell_output'))
  .filter(e => e.scrollWidth > e.clientWidth + 1).map(e => e.textContent.split('\\n')[0])"""


def test_landing_page_and_code_cells_in_a_browser(site, browser_page):
    # Headless Chromium opens the site as a reader does: the landing page asks the three
    # questions rotorlab answers, each with its figure (drawn by the executed page, decoded,
    # inside the page); the theme (Furo, docs/_static/rotorlab.css) shows every code cell whole,
    # without scrolling, at 1280 px (alabaster cut them off at the right edge).
    page = browser_page.open(site / "index.html")
    assert browser_page.errors == [] and browser_page.requests == []
    sections = dict(page.evaluate(_SECTIONS))
    width = page.evaluate("document.documentElement.clientWidth")
    for question in QUESTIONS:
        (figure,) = sections[question]  # one figure each
        assert figure[0] > 300 and figure[1] <= width, (question, figure, width)
    assert page.evaluate(_CUT_CODE) == []
    for tutorial in sorted((site / "tutorials").glob("*.html")):
        browser_page.open(tutorial)
        assert page.evaluate(_CUT_CODE) == [], tutorial.name
