"""Compile-time constants in a machine's generated kernel module (``Layout.fixed``).

A preset (:mod:`rotorlab.models._rub_machine`) may know that some packed entries keep one value
for every value of its named parameters: the zeros of a diagonal structure's matrices, a station
matrix ``B = I``, a centred clearance, a stator that is rigid by construction. The generic
kernel multiplies and adds them at every call, in every lane. :func:`fold_fixed` rewrites the
generated source with those entries as literals and removes the arithmetic they make trivial,
so that the compiled kernel is the one a hand-written kernel of that preset would be.

Only rewrites that give the same floating-point result for finite operands are made (the
kernel's states are finite wherever the integrator accepts a step): ``x * 0 -> 0``, ``x * 1 -> x``,
``x + 0 -> x``, ``x - 0 -> x``, ``0 - x -> -x``, ``-(0) -> 0``, comparisons and ``not`` of
literals, a conditional expression with a literal test or the same literal either way; a name the function assigns once,
to a literal, is replaced by it where it is read. The only possible difference is the sign of a
zero result (``0 - 0`` is ``+0``, ``-(0)`` is ``-0``), which no later operation of the kernels
turns into a different number (they do not divide by a zero they compute, nor take its sign).
"""

from __future__ import annotations

import ast
import operator

__all__ = ["fold_fixed"]

_COMPARE = {ast.Gt: operator.gt, ast.GtE: operator.ge, ast.Lt: operator.lt, ast.LtE: operator.le,
            ast.Eq: operator.eq, ast.NotEq: operator.ne}


def _literal(node, value=None) -> bool:
    """True if ``node`` is a float or bool literal (equal to ``value`` when given)."""
    if not isinstance(node, ast.Constant) or not isinstance(node.value, (float, bool)):
        return False
    return value is None or (isinstance(node.value, float) and node.value == value)


class _Fold(ast.NodeTransformer):
    def __init__(self, fixed: dict[int, float]):
        self.fixed = fixed
        self.known: dict[str, ast.Constant] = {}

    def visit_FunctionDef(self, node):
        # names assigned exactly once in the function, to a literal (after folding): constants
        self.known = {}
        node = self.generic_visit(node)
        once = _assigned_once(node)
        consts = {name: value for name, value in once.items() if _literal(value)}
        if consts:
            self.known = consts
            node = self.generic_visit(node)
        self.known = {}
        return node

    def visit_Name(self, node):
        if isinstance(node.ctx, ast.Load) and node.id in self.known:
            return ast.Constant(self.known[node.id].value)
        return node

    def visit_Subscript(self, node):
        node = self.generic_visit(node)
        if (isinstance(node.value, ast.Name) and node.value.id == "p" and isinstance(node.ctx, ast.Load)
                and isinstance(node.slice, ast.Constant) and node.slice.value in self.fixed):
            return ast.Constant(float(self.fixed[node.slice.value]))
        return node

    def visit_BinOp(self, node):
        node = self.generic_visit(node)
        a, b, op = node.left, node.right, node.op
        if isinstance(op, ast.Mult):
            if _literal(a, 0.0) or _literal(b, 0.0):
                return ast.Constant(0.0)
            if _literal(a, 1.0):
                return b
            if _literal(b, 1.0):
                return a
        elif isinstance(op, (ast.Add, ast.Sub)) and _literal(b, 0.0):
            return a
        elif isinstance(op, ast.Add) and _literal(a, 0.0):
            return b
        elif isinstance(op, ast.Sub) and _literal(a, 0.0):
            return ast.UnaryOp(ast.USub(), b)
        return node

    def visit_UnaryOp(self, node):
        node = self.generic_visit(node)
        if isinstance(node.op, ast.USub) and _literal(node.operand, 0.0):
            return ast.Constant(0.0)
        if isinstance(node.op, ast.Not) and _literal(node.operand):
            return ast.Constant(not node.operand.value)
        return node

    def visit_Compare(self, node):
        node = self.generic_visit(node)
        if (len(node.ops) == 1 and type(node.ops[0]) in _COMPARE and _literal(node.left)
                and _literal(node.comparators[0])):
            return ast.Constant(_COMPARE[type(node.ops[0])](node.left.value, node.comparators[0].value))
        return node

    def visit_IfExp(self, node):
        node = self.generic_visit(node)
        if _literal(node.test) and isinstance(node.test.value, bool):
            return node.body if node.test.value else node.orelse
        if _literal(node.body) and _literal(node.orelse) and node.body.value == node.orelse.value:
            return node.body  # the same literal either way (a zero damping's term)
        return node


def _assigned_once(func: ast.FunctionDef) -> dict[str, ast.expr]:
    """The names ``func`` assigns exactly once (a plain ``name = value``), with that value; names
    assigned more than once, by augmented assignment, in a tuple or as arguments are left out."""
    count: dict[str, int] = {a.arg: 2 for a in func.args.args}
    value: dict[str, ast.expr] = {}
    for node in ast.walk(func):
        targets = []
        if isinstance(node, ast.Assign):
            targets = node.targets
            if len(targets) == 1 and isinstance(targets[0], ast.Name):
                value[targets[0].id] = node.value
        elif isinstance(node, (ast.AugAssign, ast.AnnAssign, ast.For)):
            targets = [node.target]
        for t in targets:
            for n in ast.walk(t):
                if isinstance(n, ast.Name):
                    count[n.id] = count.get(n.id, 0) + 1
    return {name: v for name, v in value.items() if count.get(name) == 1}


def fold_fixed(source: str, fixed: dict[int, float]) -> str:
    """Return ``source`` (a generated kernel module) with the packed entries ``p[k]``, ``k`` in
    ``fixed``, replaced by their values and the arithmetic they make trivial removed (see the
    module docstring).

    Examples
    --------
    >>> print(fold_fixed("def f(p, x):\\n    d = 0.0\\n    return p[0] * x + p[1] * x - d * x\\n", {1: 0.0}), end="")
    def f(p, x):
        d = 0.0
        return p[0] * x
    """
    tree = _Fold(dict(fixed)).visit(ast.parse(source))
    return ast.unparse(ast.fix_missing_locations(tree)) + "\n"
