"""Compile-time constants folded into a generated kernel (:mod:`rotorlab._kernels.machine_fold`):
only rewrites that keep the value of every finite expression, and names assigned once."""

import math

import pytest

from rotorlab._kernels.machine_fold import fold_fixed


def run(src, *args):
    ns = {}
    exec(src, ns)  # noqa: S102 - the test's own source
    return ns["f"](*args)


SRC = '''def f(p, x, y):
    d = 0.0
    e = p[2] > 0.0
    s = 1.0
    s = s * x
    u, w = 0.0, 1.0
    a = p[0] * x + p[1] * y - d * x
    b = p[3] - p[1] * x
    c = p[4] * x if not e else p[1] * y
    g = p[0] * y if p[1] == 0.0 else 1.0
    h = 2.0 if x > 0.0 else 2.0
    return a, b, c, g, h, s + p[1] * u, -(p[1])
'''


def test_fold_removes_the_arithmetic_of_fixed_entries_and_keeps_every_value():
    fixed = {1: 0.0, 2: 0.0, 4: 1.0}
    out = fold_fixed(SRC, fixed)
    body = out.split("\n")
    assert "    a = p[0] * x" in body  # p[1] * y and d * x (d assigned once, to 0) are gone
    assert "    b = p[3]" in body  # x - 0
    assert "    c = x" in body  # not (0 > 0) -> the first arm, 1 * x
    assert "    g = p[0] * y" in body  # p[1] == 0 -> the first arm
    assert "    h = 2.0" in body  # the same literal either way
    assert "    s = s * x" in body and "u, w = (0.0, 1.0)" in out  # assigned twice / in a tuple: kept
    assert "p[1]" not in out and "p[2]" not in out and "p[4]" not in out
    for x, y in ((1.5, -2.0), (-0.25, 3.0), (0.0, 0.0)):
        p = [0.7, 0.0, 0.0, 0.3, 1.0]
        assert run(out, p, x, y) == run(SRC, p, x, y)
    assert math.copysign(1.0, run(out, [0.7, 0.0, 0.0, 0.3, 1.0], 1.0, 1.0)[-1]) == 1.0  # -(0) -> +0


@pytest.mark.parametrize("src", ["def f(p, x):\n    return p[0] / x\n", "def f(p, x):\n    return p[1] * x\n"])
def test_fold_leaves_entries_that_are_not_fixed(src):
    assert fold_fixed(src, {5: 0.0}).strip() == src.strip()
