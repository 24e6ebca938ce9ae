"""Second-order derivative jets over numpy arrays.

A :class:`Jet` carries a value together with its first and second derivatives with respect to
one scalar parameter, here the rotation angle φ of the input link (crank). Feeding a jet through
the closed-form group solvers yields the positions together with their velocity analogs
(dX/dφ) and acceleration analogs (d²X/dφ²), exactly, by forward-mode differentiation.

The functions of this module dispatch on their argument: a plain number or ndarray goes straight
to the numpy ufunc with no extra work (the fast path used by synthesis, which needs positions
only), a :class:`Jet` goes through the chain rule. Values may be real or complex (points are
complex numbers ``x + 1j*y``); all parts broadcast like numpy arrays.

Chain rule used throughout, for ``y = f(x)``::

    y'  = f'(x) · x'
    y'' = f''(x) · x'² + f'(x) · x''
"""

from __future__ import annotations

from typing import Any, overload

import numpy as np

__all__ = [
    "Jet",
    "abs",
    "arccos",
    "arctan2",
    "arg",
    "as_jet",
    "conj",
    "cross",
    "dot",
    "expi",
    "imag",
    "real",
    "sqrt",
    "unit",
    "value",
    "where",
]

ArrayLike = complex | float | np.ndarray


class Jet:
    """A value with its first and second derivatives with respect to the crank angle.

    Parameters
    ----------
    v : array_like
        Value (real or complex).
    d1 : array_like, optional
        First derivative dv/dφ (the velocity analog when ``v`` is a position). Default 0.
    d2 : array_like, optional
        Second derivative d²v/dφ² (the acceleration analog). Default 0.

    Notes
    -----
    The three parts broadcast against each other and against any operand. Arithmetic with
    numbers and ndarrays works on either side (``2 * jet``, ``array - jet``); numpy defers to
    the jet because ``__array_ufunc__`` is ``None``.

    Examples
    --------
    The crank angle itself, over 4 positions, is the independent variable:

    >>> import numpy as np
    >>> phi = Jet(np.linspace(0.0, np.pi, 4), 1.0, 0.0)
    >>> a = 0.1 * expi(phi)            # crank pin: position, velocity and acceleration analogs
    >>> bool(np.allclose(a.d2, -a.v))
    True
    """

    __slots__ = ("d1", "d2", "v")
    __array_ufunc__ = None

    def __init__(self, v: ArrayLike, d1: ArrayLike = 0.0, d2: ArrayLike = 0.0) -> None:
        self.v = np.asarray(v)
        self.d1 = np.asarray(d1)
        self.d2 = np.asarray(d2)

    def __repr__(self) -> str:
        return f"Jet(v={self.v!r}, d1={self.d1!r}, d2={self.d2!r})"

    @property
    def shape(self) -> tuple[int, ...]:
        """Broadcast shape of the value and both derivatives."""
        return np.broadcast_shapes(self.v.shape, self.d1.shape, self.d2.shape)

    def __getitem__(self, index: Any) -> Jet:
        v, d1, d2 = np.broadcast_arrays(self.v, self.d1, self.d2)
        return Jet(v[index], d1[index], d2[index])

    # --- arithmetic -----------------------------------------------------------------------

    def __neg__(self) -> Jet:
        return Jet(-self.v, -self.d1, -self.d2)

    def __add__(self, other: object) -> Jet:
        if isinstance(other, Jet):
            return Jet(self.v + other.v, self.d1 + other.d1, self.d2 + other.d2)
        return Jet(self.v + other, self.d1, self.d2)

    __radd__ = __add__

    def __sub__(self, other: object) -> Jet:
        if isinstance(other, Jet):
            return Jet(self.v - other.v, self.d1 - other.d1, self.d2 - other.d2)
        return Jet(self.v - other, self.d1, self.d2)

    def __rsub__(self, other: object) -> Jet:
        return Jet(other - self.v, -self.d1, -self.d2)

    def __mul__(self, other: object) -> Jet:
        if isinstance(other, Jet):
            return Jet(
                self.v * other.v,
                self.d1 * other.v + self.v * other.d1,
                self.d2 * other.v + 2.0 * self.d1 * other.d1 + self.v * other.d2,
            )
        return Jet(self.v * other, self.d1 * other, self.d2 * other)

    __rmul__ = __mul__

    def __truediv__(self, other: object) -> Jet:
        if not isinstance(other, Jet):
            return Jet(self.v / other, self.d1 / other, self.d2 / other)
        q = self.v / other.v
        q1 = (self.d1 - q * other.d1) / other.v
        q2 = (self.d2 - 2.0 * q1 * other.d1 - q * other.d2) / other.v
        return Jet(q, q1, q2)

    def __rtruediv__(self, other: object) -> Jet:
        return Jet(np.asarray(other)) / self

    def __pow__(self, n: int) -> Jet:
        """The jet of ``v**n`` for a whole exponent: n·vⁿ⁻¹·v′ and
        n·vⁿ⁻¹·v″ + n(n − 1)·vⁿ⁻²·v′².

        Examples
        --------
        >>> t = Jet(np.array([0.5, 2.0]), 1.0, 0.0)
        >>> square = t ** 2
        >>> square.v.tolist(), square.d1.tolist(), square.d2.tolist()
        ([0.25, 4.0], [1.0, 4.0], [2.0, 2.0])
        """
        if n == 0:
            return Jet(np.ones_like(self.v), 0.0, 0.0)
        below = self.v ** (n - 1)
        second = n * (n - 1) * self.v ** (n - 2) if n != 1 else 0.0
        return Jet(below * self.v, n * below * self.d1,
                   n * below * self.d2 + second * self.d1 * self.d1)


def _chain(x: Jet, f: np.ndarray, df: np.ndarray, ddf: np.ndarray) -> Jet:
    """Jet of ``f(x)`` from the value ``f`` and the derivatives ``df``, ``ddf`` of f at x.v."""
    return Jet(f, df * x.d1, ddf * x.d1 * x.d1 + df * x.d2)


def as_jet(x: Jet | ArrayLike) -> Jet:
    """``x`` as a jet: a plain value has zero derivatives."""
    return x if isinstance(x, Jet) else Jet(x, 0.0, 0.0)


@overload
def value(x: Jet | np.ndarray) -> np.ndarray: ...


@overload
def value(x: Jet | ArrayLike) -> np.ndarray | complex | float: ...


def value(x: Jet | ArrayLike) -> np.ndarray | complex | float:
    """The plain value of ``x`` (the ``v`` part of a jet, or ``x`` itself)."""
    return x.v if isinstance(x, Jet) else x


def real(x: Jet | ArrayLike) -> Jet | np.ndarray:
    """Real part."""
    if isinstance(x, Jet):
        return Jet(np.real(x.v), np.real(x.d1), np.real(x.d2))
    return np.asarray(np.real(x))


def imag(x: Jet | ArrayLike) -> Jet | np.ndarray:
    """Imaginary part."""
    if isinstance(x, Jet):
        return Jet(np.imag(x.v), np.imag(x.d1), np.imag(x.d2))
    return np.asarray(np.imag(x))


def conj(x: Jet | ArrayLike) -> Jet | np.ndarray:
    """Complex conjugate (the mirror image of a point in the x-axis)."""
    if isinstance(x, Jet):
        return Jet(np.conj(x.v), np.conj(x.d1), np.conj(x.d2))
    return np.conj(x)


def sqrt(x: Jet | ArrayLike) -> Jet | np.ndarray:
    """Principal square root; the derivatives are infinite at 0."""
    if not isinstance(x, Jet):
        return np.sqrt(x)
    s = np.sqrt(x.v)
    s1 = x.d1 / (2.0 * s)
    return Jet(s, s1, (x.d2 - 2.0 * s1 * s1) / (2.0 * s))


def arccos(x: Jet | ArrayLike) -> Jet | np.ndarray:
    """Inverse cosine of a real argument, in [0, π]."""
    if not isinstance(x, Jet):
        return np.arccos(x)
    k = -1.0 / np.sqrt((1.0 - x.v) * (1.0 + x.v))  # d/dx arccos x
    return _chain(x, np.arccos(x.v), k, x.v * k**3)


def arctan2(y: Jet | ArrayLike, x: Jet | ArrayLike) -> Jet | np.ndarray:
    """Polar angle of the real vector (x, y), in (−π, π]."""
    if not isinstance(y, Jet) and not isinstance(x, Jet):
        return np.arctan2(y, x)
    y, x = (t if isinstance(t, Jet) else Jet(t) for t in (y, x))
    r2 = x.v * x.v + y.v * y.v
    num1 = x.v * y.d1 - y.v * x.d1
    t1 = num1 / r2
    num2 = x.v * y.d2 - y.v * x.d2
    t2 = (num2 - 2.0 * t1 * (x.v * x.d1 + y.v * y.d1)) / r2
    return Jet(np.arctan2(y.v, x.v), t1, t2)


def arg(z: Jet | ArrayLike) -> Jet | np.ndarray:
    """Polar angle of a complex number (point or vector), in (−π, π].

    For a jet, with ``w = z'/z``: ``arg' = Im w`` and ``arg'' = Im(z''/z − w²)``.
    """
    if not isinstance(z, Jet):
        return np.arctan2(z.imag, z.real) if isinstance(z, np.ndarray) else np.asarray(np.angle(z))
    w = z.d1 / z.v
    return Jet(np.angle(z.v), np.imag(w), np.imag(z.d2 / z.v - w * w))


#: ½ as an array of shape (): a cheaper ufunc operand than the Python number (also for
#: :mod:`assur.kinematics._fast`); 1 and 2 likewise.
HALF = np.array(0.5)
_ONE, _TWO = np.array(1.0), np.array(2.0)

#: Angles along the last axis from which :func:`unit` takes the tangent of the half angle.
TANGENT_FROM = 1024


def unit(t: np.ndarray) -> np.ndarray:
    """``exp(1j*t)`` of a plain real array (a number for a 0-d array): :func:`expi`'s values.

    Rows of fewer than :data:`TANGENT_FROM` angles (the last axis: the positions of a
    mechanism's analysis, whatever the designs along the others, so that a design has the
    same unit vectors alone and in a batch) take one cosine and one sine. (The higher
    groups lay their designs along the last axis: there batches of 1,024 designs or more
    take the other form.) Longer rows take the tangent of the half angle τ = tan(t/2):
    ``cos t = 2/(1 + τ²) − 1`` and ``sin t = 2τ/(1 + τ²)``, one tangent and five arithmetic
    passes. numpy computes the tangent by vector instructions where the machine has them,
    and the cosine and the sine one number at a time, so this form costs 0.36 times the two
    over 3,600 angles; over a few hundred, its extra passes and the slower start of the
    operations after the vector tangent cost more than it saves (``docs/group_solvers.md``).
    Each part is within about 2 ε of the correctly rounded cosine and sine, whatever t
    (``tests/assur/test_jets.py``): t/2 is exact (but for subnormal t), τ is correctly
    rounded to 1 ulp, no step cancels more than an absolute ε, and near the poles of the
    tangent (t near π modulo 2π) τ² stays far from overflow (|τ| < 10²⁰ for every double).
    """
    u = np.empty(t.shape, dtype=complex)
    if not t.ndim or t.shape[-1] < TANGENT_FROM:
        np.cos(t, u.real)
        np.sin(t, u.imag)
        return u if u.ndim else u[()]
    tau = np.multiply(t, HALF)
    np.tan(tau, tau)
    g = np.multiply(tau, tau)
    g += _ONE
    np.divide(_TWO, g, g)  # 1 + cos t
    np.multiply(tau, g, u.imag)
    np.subtract(g, _ONE, u.real)
    return u


def expi(theta: Jet | ArrayLike) -> Jet | np.ndarray:
    """Unit vector ``u(θ) = exp(1j*θ)`` of a real angle θ."""
    if not isinstance(theta, Jet):
        t = theta if type(theta) is np.ndarray and theta.dtype == float else np.asarray(
            theta, dtype=float)
        return unit(t)
    u = unit(np.asarray(theta.v, dtype=float))
    ju = 1j * u
    return Jet(u, ju * theta.d1, (ju * theta.d2) - u * theta.d1 * theta.d1)


def abs(x: Jet | ArrayLike) -> Jet | np.ndarray:
    """Absolute value of a real argument, or modulus of a complex one."""
    if not isinstance(x, Jet):
        return np.abs(x)
    if not np.iscomplexobj(x.v):
        sign = np.sign(x.v)
        return Jet(np.abs(x.v), sign * x.d1, sign * x.d2)
    m = np.abs(x.v)
    m1 = np.real(np.conj(x.v) * x.d1) / m
    m2 = (np.real(np.conj(x.d1) * x.d1) + np.real(np.conj(x.v) * x.d2) - m1 * m1) / m
    return Jet(m, m1, m2)


def cross(a: Jet | ArrayLike, b: Jet | ArrayLike) -> Jet | np.ndarray:
    """Planar cross product ``a_x·b_y − a_y·b_x`` of complex vectors, ``Im(conj(a)·b)``."""
    if isinstance(a, Jet) or isinstance(b, Jet):
        return imag(conj(a) * b)
    return (np.conj(a) * b).imag


def dot(a: Jet | ArrayLike, b: Jet | ArrayLike) -> Jet | np.ndarray:
    """Planar dot product ``a_x·b_x + a_y·b_y`` of complex vectors, ``Re(conj(a)·b)``."""
    if isinstance(a, Jet) or isinstance(b, Jet):
        return real(conj(a) * b)
    return (np.conj(a) * b).real


def where(condition: np.ndarray, x: Jet | ArrayLike, y: Jet | ArrayLike) -> Jet | np.ndarray:
    """Elementwise choice between ``x`` and ``y`` (all parts of a jet follow the value).

    A plain ``x`` or ``y`` counts as a constant, with zero derivatives, except that NaN has NaN
    derivatives (so that a position blanked with NaN has no velocity either).
    """
    if not isinstance(x, Jet) and not isinstance(y, Jet):
        return np.where(condition, x, y)
    x, y = (t if isinstance(t, Jet) else Jet(t, 0.0 * t, 0.0 * t) for t in (x, y))
    return Jet(
        np.where(condition, x.v, y.v),
        np.where(condition, x.d1, y.d1),
        np.where(condition, x.d2, y.d2),
    )

