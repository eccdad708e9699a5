"""A problem with a machine's ball is reported at the key path the case file has.

Review of the session-5 diff: ``count = n`` repeats a ball entry, and the check refusing ball
friction together with a clearance (``must be 0 with a clearance``) numbered the balls after that
expansion: with ``balls = [{..., count = 2}, {..., coulomb = 0.01}]`` it pointed at ``balls[2]``,
an entry the file does not have (and could not show the value as written).
"""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from rotorlab.cli import app
from rotorlab.io import CaseError, load_case, parse_case

WRITTEN = 'balls = [{ mass = "0.5 kg", damping = "0.05 N*m*s/rad", count = 2 }]'


def _washer(balls: str) -> str:
    text = load_case("washer-knock").text  # a machine with a clearance
    assert WRITTEN in text
    return text.replace(WRITTEN, f"balls = [{balls}]")


def test_the_key_path_counts_the_entries_as_written(tmp_path):
    text = _washer('{ mass = "0.5 kg", count = 2 }, { mass = "0.5 kg", coulomb = 0.01, count = 3 }, '
                   '{ mass = "1 g", rolling = "1 mm" }')
    with pytest.raises(CaseError) as err:
        parse_case(text, origin="w.toml")
    lines = str(err.value).splitlines()[1:]
    assert [line.split(":")[0].strip() for line in lines] == ["model.races[0].balls[1].coulomb = 0.01",
                                                              'model.races[0].balls[2].rolling = "1 mm"']
    # on the command line: exit 2, no traceback
    path = tmp_path / "w.toml"
    path.write_text(text)
    result = CliRunner().invoke(app, ["validate", str(path)])
    assert result.exit_code == 2 and "Traceback" not in result.output
    assert "model.races[0].balls[1].coulomb = 0.01: must be 0 with a clearance" in result.output


def test_written_balls_undoes_count():
    race = load_case("washer-knock").model.races[0]
    assert len(race.balls) == 2 and [j for j, _ in race.written_balls()] == [0]
    two = parse_case(_washer('{ mass = "0.5 kg" }, { mass = "0.5 kg" }')).model.races[0]
    assert [j for j, _ in two.written_balls()] == [0, 1]
