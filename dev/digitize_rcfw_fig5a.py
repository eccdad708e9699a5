"""Read the stability boundaries of Fig. 5(a) of Rodrigues et al. (2008) from its vector graphics.

Usage: ``python dev/digitize_rcfw_fig5a.py abbspecialissue.pdf`` (panels (a) and (d)) (the authors' preprint of
"Automatic two-plane balancing for rigid rotors", University of Bristol, hdl 1983/946; also in
the public repository github.com/djr41/thesis). Needs ``pypdf`` and matplotlib (not rotorlab
dependencies: this is a one-off helper, its output is ``FIG5A_BOUNDARIES`` in
``tests/validation/test_rcfw_reference.py``).

The figure is drawn as PDF paths: panel (a) is the frame from (109.3, 604.9) to (499.0, 750.3)
points on page 14, which maps to 0 <= Omega <= 6 and 0 <= m <= 0.04 (its tick labels; the
horizontal line m = m_c lands at m = 0.0025, a check of the mapping). The shaded stable regions
are fills in grey (0.702), painted in order over a white background; a horizontal line
m = const is sampled every 0.01 in Omega against those polygons (even-odd rule) and the speeds
where it enters or leaves the shade are printed.
"""

from __future__ import annotations

import sys

import numpy as np

PAGE = 13  # zero-based: the page holding Fig. 5
FRAME = (109.3, 499.0, 604.9, 750.3)  # x0, x1, y0, y1 of panel (a) in points
AXES = (6.0, 0.04)  # Omega and m at the frame's right and top edges
# Panel (d), the enlargement 2 <= Omega <= 4.5, 0.002 <= m <= 0.007 (its tick labels; the ticks
# 0.001 apart are 28.9 points apart, the frame 5 of them high): x0, x1, y0, y1 and the axes' ranges.
FRAME_D = (109.5, 281.3, 228.6, 373.1)
AXES_D = ((2.0, 4.5), (0.002, 0.007))


def _fills(path: str):
    import pypdf
    from pypdf.generic import ContentStream

    reader = pypdf.PdfReader(path)
    page = reader.pages[PAGE]
    ctm, stack, fill, cur, sub, fills = [1, 0, 0, 1, 0, 0], [], None, [], [], []

    def mul(a, b):
        A = np.array([[a[0], a[1], 0], [a[2], a[3], 0], [a[4], a[5], 1]])
        B = np.array([[b[0], b[1], 0], [b[2], b[3], 0], [b[4], b[5], 1]])
        C = A @ B
        return [C[0, 0], C[0, 1], C[1, 0], C[1, 1], C[2, 0], C[2, 1]]

    def tr(x, y):
        return ctm[0] * x + ctm[2] * y + ctm[4], ctm[1] * x + ctm[3] * y + ctm[5]

    for ops, op in ContentStream(page.get_contents(), reader).operations:
        op = op.decode() if isinstance(op, bytes) else op
        if op == "q":
            stack.append((ctm, fill))
        elif op == "Q":
            ctm, fill = stack.pop()
        elif op == "cm":
            ctm = mul([float(v) for v in ops], ctm)
        elif op == "g":
            fill = float(ops[0])
        elif op in ("rg", "k"):
            fill = None
        elif op == "m":
            if sub:
                cur.append(sub)
            sub = [tr(float(ops[0]), float(ops[1]))]
        elif op == "l":
            sub.append(tr(float(ops[0]), float(ops[1])))
        elif op == "c":
            sub.append(tr(float(ops[4]), float(ops[5])))
        elif op == "re":
            x, y, w, h = map(float, ops)
            if sub:
                cur.append(sub)
            sub = [tr(x, y), tr(x + w, y), tr(x + w, y + h), tr(x, y + h)]
        elif op in ("f", "f*", "F", "B", "b", "S", "s", "n", "B*", "b*"):
            if sub:
                cur.append(sub)
            if op in ("f", "f*", "F", "B", "b", "B*", "b*") and fill is not None:
                fills.append((fill, cur))
            cur, sub = [], []
    return fills


def boundaries(path: str, masses=(0.005, 0.01, 0.015, 0.02, 0.025, 0.03), *, frame=FRAME,
               axes=((0.0, AXES[0]), (0.0, AXES[1])), step=0.01):
    from matplotlib.path import Path

    x0, x1, y0, y1 = frame
    (oa, ob), (ma, mb) = axes
    fills = _fills(path)
    oms = np.arange(oa, ob + 1e-9, step)
    out = {}
    for m in masses:
        pts = np.column_stack([x0 + (x1 - x0) * (oms - oa) / (ob - oa),
                               np.full(oms.size, y0 + (y1 - y0) * (m - ma) / (mb - ma))])
        shade = np.zeros(oms.size, bool)
        for grey, subs in fills:
            inside = np.zeros(oms.size, bool)
            for s in subs:
                if len(s) > 2:
                    inside ^= Path(np.array(s)).contains_points(pts)
            shade[inside] = grey < 0.9
        edges = np.flatnonzero(np.diff(shade.astype(int)))
        out[m] = [(round(float(oms[i]), 3), round(float(oms[i + 1]), 3), 1 if shade[i + 1] else -1)
                  for i in edges]
    return out


if __name__ == "__main__":
    for m, b in boundaries(sys.argv[1]).items():
        print("(a)", m, b)
    masses_d = np.round(np.arange(0.0026, 0.00701, 0.0002), 5)
    for m, b in boundaries(sys.argv[1], masses_d, frame=FRAME_D, axes=AXES_D, step=0.005).items():
        print("(d)", m, b)
