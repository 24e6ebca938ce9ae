"""Laws of motion written as formulas of the crank angle φ (the course's (2.22)).

A class-4 task may give the required motion of the tracing point as parametric equations
``x(φ)``, ``y(φ)`` instead of a table; a class-1 or class-2 task its law ``ψ(φ)`` or
``S(φ)``.  A formula is parsed once by :func:`parse_law` into a :class:`Law`, which is
then evaluated on arrays of angles.  The parser reads Python's own expression grammar
(:func:`ast.parse` in ``eval`` mode) and accepts a tree only when every node is on a short
whitelist; nothing is ever executed by Python itself.  The evaluator walks the tree with
NumPy functions.

Accepted:

* numbers (``2``, ``0.5``, ``1e-3``), the angle ``phi`` (or ``φ``) in **degrees**, and
  the constant ``pi``;
* ``+ - * / **`` and unary ``-`` / ``+``, parentheses;
* the functions ``sin cos tan`` (of an angle in radians), ``sqrt exp log abs``, and
  ``radians degrees`` (the conversions; ``sin(radians(phi))`` is the sine of φ).

Everything else (names, attribute access, calls of other functions, comparisons,
subscripts, keyword arguments, …) is refused with the reason.

Examples
--------
>>> import numpy as np
>>> law = parse_law("50 + 20*cos(radians(phi))")
>>> law(np.array([0.0, 90.0, 180.0])).round(12).tolist()
[70.0, 50.0, 30.0]
>>> parse_law("__import__('os')")
Traceback (most recent call last):
...
synthesis.expressions.LawError: a function other than sin, cos, tan, sqrt, exp, log, \
abs, radians, degrees
"""

from __future__ import annotations

import ast
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from assur.typing import FloatArray

__all__ = ["FUNCTIONS", "Law", "LawError", "parse_law"]

#: The functions a law may call, by name.
FUNCTIONS: dict[str, Callable[[FloatArray], FloatArray]] = {
    "sin": np.sin, "cos": np.cos, "tan": np.tan, "sqrt": np.sqrt, "exp": np.exp,
    "log": np.log, "abs": np.abs, "radians": np.radians, "degrees": np.degrees,
}
#: The names of the angle φ.
ANGLE = ("phi", "φ")
_BINARY: dict[type[ast.operator], Callable[[FloatArray, FloatArray], FloatArray]] = {
    ast.Add: np.add, ast.Sub: np.subtract, ast.Mult: np.multiply, ast.Div: np.divide,
    ast.Pow: np.power,
}
#: Longest formula accepted (characters).
MAX_LENGTH = 500


class LawError(ValueError):
    """A text that is not a formula of φ; the message says why (in English, for logs;
    the problem reader tells it through its catalogue code and :attr:`reason`)."""

    def __init__(self, reason: str, detail: str = "") -> None:
        super().__init__(_REASONS[reason] + (f" {detail}" if detail else ""))
        #: A key of the catalogue's ``law.reason.*`` sentences.
        self.reason = reason
        #: What was found (a name, an operator), or "".
        self.detail = detail


_REASONS = {
    "syntax": "not a formula",
    "too_long": f"longer than {MAX_LENGTH} characters",
    "name": "an unknown name:",
    "function": ("a function other than " + ", ".join(FUNCTIONS)),
    "node": "a construction that is not allowed:",
    "no_angle": "does not depend on phi",
    "big_number": "a number too large for a float",
}


@dataclass(frozen=True)
class Law:
    """A checked formula of φ.

    Attributes
    ----------
    text : str
        The formula as written.
    tree : ast.expr
        Its checked syntax tree.
    """

    text: str
    tree: ast.expr

    def __call__(self, phi: FloatArray) -> FloatArray:
        """The law at the angles φ (degrees), shape of ``phi``."""
        phi = np.asarray(phi, dtype=float)
        with np.errstate(all="ignore"):
            out = np.broadcast_to(_value(self.tree, phi), phi.shape)
        return np.array(out, dtype=float)


def parse_law(text: str) -> Law:
    """Parse and check a formula of φ.

    Parameters
    ----------
    text : str
        The formula (see the module's description for what it may contain).

    Returns
    -------
    Law

    Raises
    ------
    LawError
        When the text is not a formula of φ made of the accepted parts, or does not depend
        on φ.
    """
    if len(text) > MAX_LENGTH:
        raise LawError("too_long")
    try:
        tree = ast.parse(text.strip(), mode="eval").body
    except (SyntaxError, ValueError):
        raise LawError("syntax") from None
    if not _check(tree):
        raise LawError("no_angle")
    return Law(text, tree)


def _check(node: ast.expr) -> bool:
    """Refuse a node off the whitelist; returns whether the subtree depends on φ."""
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) \
            and not isinstance(node.value, bool):
        try:
            float(node.value)  # (an int too large for a float)
        except OverflowError:
            raise LawError("big_number") from None
        return False
    if isinstance(node, ast.Name):
        if node.id in ANGLE:
            return True
        if node.id == "pi":
            return False
        raise LawError("name", node.id)
    if isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
        left, right = _check(node.left), _check(node.right)
        return left or right
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        return _check(node.operand)
    if isinstance(node, ast.Call):
        if not (isinstance(node.func, ast.Name) and node.func.id in FUNCTIONS
                and len(node.args) == 1 and not node.keywords):
            raise LawError("function")
        return _check(node.args[0])
    raise LawError("node", type(node).__name__)


def _value(node: ast.expr, phi: FloatArray) -> FloatArray:
    """The value of a checked subtree at the angles φ."""
    if isinstance(node, ast.Constant):
        assert isinstance(node.value, (int, float))  # (checked)
        return np.asarray(float(node.value))
    if isinstance(node, ast.Name):
        return phi if node.id in ANGLE else np.asarray(np.pi)
    if isinstance(node, ast.BinOp):
        return _BINARY[type(node.op)](_value(node.left, phi), _value(node.right, phi))
    if isinstance(node, ast.UnaryOp):
        inner = _value(node.operand, phi)
        return -inner if isinstance(node.op, ast.USub) else inner
    assert isinstance(node, ast.Call) and isinstance(node.func, ast.Name)  # (checked)
    return FUNCTIONS[node.func.id](_value(node.args[0], phi))
