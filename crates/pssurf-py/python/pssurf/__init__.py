"""Powell–Sabin splines for Python: scattered-data interpolation and smoothing in SciPy's
idiom, and the surfaces of the pssurf library (UPS subdivision, wavelets, sampling).

>>> import numpy as np, pssurf
>>> pts = np.random.default_rng(0).random((1000, 2))
>>> f = pssurf.PsInterpolator(pts, np.sin(3 * pts[:, 0]) * pts[:, 1])
>>> z = f(np.linspace(0.2, 0.8, 50), np.linspace(0.2, 0.8, 40), grid=True)   # (50, 40)
>>> zx = f(0.5, 0.5, dx=1)

Every loop runs in Rust with the GIL released; errors are ``ValueError`` (bad input or file
contents), ``OSError`` (the system refused) or ``MemoryError`` (a request beyond the memory
budget, refused before allocating).
"""

from __future__ import annotations

import numpy as np

from . import _core
from ._core import Surface, Wavelet, load, ups

__all__ = [
    "PsInterpolator",
    "fit_smooth",
    "Surface",
    "Wavelet",
    "load",
    "ups",
]


def _float_array(a, name):
    """``a`` as a C-contiguous float64 array (float32, lists, read-only and strided views are
    converted); complex or non-numeric input is refused."""
    try:
        arr = np.asarray(a)
    except Exception as e:  # e.g. ragged lists
        raise ValueError(f"{name} must be an array of numbers: {e}") from None
    if arr.dtype.kind not in "fiub":
        raise ValueError(f"{name} must be real numbers, not {arr.dtype}")
    # (np.ascontiguousarray would turn a 0-d array into a 1-d one.)
    arr = np.asarray(arr, dtype=np.float64)
    return arr if arr.flags.c_contiguous else arr.copy(order="C")


def _points(points, name="points"):
    """(n, 2) float64 points from an (n, 2) array or a tuple (x, y) of 1-D arrays."""
    if isinstance(points, tuple) and len(points) == 2:
        x = _float_array(points[0], name + "[0]").ravel()
        y = _float_array(points[1], name + "[1]").ravel()
        if x.shape != y.shape:
            raise ValueError(f"{name}: x has {x.size} entries but y has {y.size}")
        return np.ascontiguousarray(np.stack([x, y], axis=1))
    p = _float_array(points, name)
    if p.ndim != 2 or p.shape[1] != 2:
        raise ValueError(f"{name} must have shape (n, 2), not {p.shape}")
    return p


def _triangles(triangles):
    if triangles is None:
        return None
    t = np.asarray(triangles)
    if t.dtype.kind not in "iu":
        raise ValueError(f"triangles must be integer indices, not {t.dtype}")
    if t.ndim != 2 or t.shape[1] != 3:
        raise ValueError(f"triangles must have shape (m, 3), not {t.shape}")
    if t.dtype.kind == "u" and t.size and t.max() > np.iinfo(np.int64).max:
        # Unsigned indices beyond int64 would wrap to negative numbers in the cast below.
        row = int(np.argmax(t.max(axis=1) > np.iinfo(np.int64).max))
        raise ValueError(
            f"triangle {row} refers to point {int(t[row].max())}, beyond any number of points"
        )
    return np.ascontiguousarray(t, dtype=np.int64)


def _order(d, name):
    if isinstance(d, (bool, np.bool_)) or not isinstance(d, (int, np.integer)) or d < 0:
        raise ValueError(f"{name} must be an integer ≥ 0, not {d!r}")
    # Any order is accepted: those above 2 are zero on the quadratic pieces, so 3 stands
    # for all of them.
    return min(int(d), 3)


class PsInterpolator:
    """The C¹ piecewise-quadratic Powell–Sabin interpolant of scattered data (x, y, z).

    Parameters
    ----------
    points : (n, 2) array or tuple (x, y) of 1-D arrays
        The data sites; distinct.
    values : (n,) array
        The data values.
    gradients : (n, 2) array, optional
        The partial derivatives (z_x, z_y) at the sites; estimated when omitted.
    triangles : (m, 3) integer array, optional
        A triangulation of the sites (indices into ``points``); Delaunay when omitted.
    gradient_method : "local", "global" or "jumps"
        How gradients are estimated: local weighted quadratic least squares (default,
        the fastest); the least curvature of the edge network beyond the locally fitted
        one over the whole triangulation (Clough–Tocher's choice made exact on
        quadratics; 2-3x more accurate on smooth scattered data); or the least
        Hessian-jump energy (the least-energy interpolant: the most accurate on smooth
        gridded data, the least on rough real data, and the slowest).
    split : "incenter" or "centroid"
        The split point of each triangle of the Powell–Sabin refinement.
    fill_value : float
        The value outside the convex hull of the sites (NaN by default), as SciPy's
        ``CloughTocher2DInterpolator``.
    extrapolate : None or "error"
        ``"error"`` raises ``ValueError`` at the first point outside instead of filling.

    Evaluate with ``f(x, y)`` (broadcast), ``f(xi)`` with ``xi`` of shape (..., 2), or
    ``f(x, y, grid=True)`` on the grid x × y (shape (len(x), len(y))); ``dx``, ``dy`` give
    partial derivatives, as SciPy's bivariate splines.
    """

    def __init__(
        self,
        points,
        values,
        gradients=None,
        triangles=None,
        gradient_method="local",
        split="incenter",
        fill_value=np.nan,
        extrapolate=None,
    ):
        pts = _points(points)
        vals = _float_array(values, "values")
        if vals.ndim != 1:
            raise ValueError(
                f"values must have shape (n,), not {vals.shape} (fit one interpolant per column)"
            )
        grads = None if gradients is None else _points(gradients, "gradients")
        if extrapolate not in (None, "error"):
            raise ValueError(f'extrapolate must be None or "error", not {extrapolate!r}')
        self.fill_value = float(fill_value)
        self.extrapolate = extrapolate
        self._core = _core.Interpolant(
            pts, vals, grads, _triangles(triangles), gradient_method, split
        )

    @classmethod
    def _wrap(cls, core, fill_value=np.nan, extrapolate=None):
        self = cls.__new__(cls)
        self._core = core
        self.fill_value = float(fill_value)
        self.extrapolate = extrapolate
        return self

    @property
    def _fill(self):
        return None if self.extrapolate == "error" else self.fill_value

    def _xy(self, x, y):
        """Broadcast query coordinates: (flat x, flat y, result shape)."""
        if y is None and isinstance(x, tuple) and len(x) == 1:
            x = x[0]
        if y is None and isinstance(x, tuple) and len(x) == 2:
            # As SciPy's interpolators: a tuple is the coordinate arrays (x, y), broadcast
            # together, not two points.
            x, y = x
        if y is None:
            xi = _float_array(x, "xi")
            if xi.ndim == 1 and xi.size % 2 == 0:
                # As SciPy's interpolators: a flat xi holds points one after another, so
                # f([x, y]) is one point of shape (1,).
                xi = xi.reshape(-1, 2)
            if xi.ndim == 0 or xi.shape[-1] != 2:
                raise ValueError(f"xi must have shape (..., 2), not {xi.shape}")
            shape = xi.shape[:-1]
            xi = xi.reshape(-1, 2)
            return np.ascontiguousarray(xi[:, 0]), np.ascontiguousarray(xi[:, 1]), shape
        xa, ya = np.broadcast_arrays(_float_array(x, "x"), _float_array(y, "y"))
        shape = xa.shape
        return (
            np.ascontiguousarray(xa.reshape(-1)),
            np.ascontiguousarray(ya.reshape(-1)),
            shape,
        )

    def __call__(self, x, y=None, dx=0, dy=0, grid=False):
        """Values (or the partial derivative ∂^(dx+dy)/∂x^dx∂y^dy) at the points."""
        dx, dy = _order(dx, "dx"), _order(dy, "dy")
        if grid:
            if y is None:
                raise ValueError("grid=True needs x and y")
            xa = _float_array(x, "x").ravel()
            ya = _float_array(y, "y").ravel()
            out = self._core.evaluate_grid(xa, ya, dx, dy, self._fill)
            return out.reshape(xa.size, ya.size)
        xf, yf, shape = self._xy(x, y)
        return self._core.evaluate(xf, yf, dx, dy, self._fill).reshape(shape)

    def gradient(self, x, y=None):
        """(z_x, z_y) at the points: shape (..., 2)."""
        xf, yf, shape = self._xy(x, y)
        return self._core.jets(xf, yf, self._fill)[:, 1:3].reshape(shape + (2,))

    def hessian(self, x, y=None):
        """[[z_xx, z_xy], [z_xy, z_yy]] at the points: shape (..., 2, 2). On the edges of the
        Powell–Sabin refinement the second derivatives jump; there the value of one of the
        adjacent pieces is returned."""
        xf, yf, shape = self._xy(x, y)
        j = self._core.jets(xf, yf, self._fill)
        h = np.stack([j[:, 3], j[:, 4], j[:, 4], j[:, 5]], axis=1)
        return h.reshape(shape + (2, 2))

    def curvature(self, x, y=None):
        """Curvature of the graph z = f(x, y): a dict of arrays "K" (Gaussian), "H" (mean),
        "k1" ≥ "k2" (principal), each of the points' shape."""
        xf, yf, shape = self._xy(x, y)
        c = self._core.curvature(xf, yf, self._fill)
        return {k: c[:, i].reshape(shape) for i, k in enumerate(("K", "H", "k1", "k2"))}

    @property
    def vertices(self):
        """The triangulation's vertices, (n, 2) (Morton-ordered for memory locality)."""
        return self._core.vertices()

    @property
    def triangles(self):
        """The triangulation's triangles, (m, 3) indices into ``vertices``."""
        return self._core.triangles()

    def surface(self):
        """The interpolant as a :class:`Surface` (to save, sample or measure)."""
        return self._core.surface()

    def save(self, path):
        """Writes the interpolant as a functional PS surface file."""
        self._core.surface().save(path)


def fit_smooth(
    points,
    values,
    vertices=None,
    triangles=None,
    smooth="gcv",
    energy="hessian_jumps",
    fill_value=np.nan,
):
    """A smoothing Powell–Sabin spline: minimises Σ (s(p_k) − z_k)² + λ·energy(s) over the
    splines on a coarse triangulation.

    ``vertices`` is a count M (a grid of about M vertices over the data; default
    min(n, 1000)) or an (m, 2) array (then ``triangles`` optionally); ``smooth`` is λ ≥ 0
    or "gcv" (generalised cross-validation); ``energy`` "hessian_jumps" (smooths towards
    a quadratic) or "thin_plate" (towards a plane). Returns (interpolator, report) with
    report keys "smooth" (λ), "rms_residual", "effective_dof", "dof_estimated", "gcv".
    """
    pts = _points(points)
    vals = _float_array(values, "values")
    if vals.ndim != 1:
        raise ValueError(f"values must have shape (n,), not {vals.shape}")
    if len(pts) == 0:
        raise ValueError("no data points to fit")
    if vertices is None:
        vertices = min(len(pts), 1000)
    if not isinstance(vertices, (int, np.integer)):
        vertices = _points(vertices, "vertices")
    elif isinstance(vertices, (bool, np.bool_)) or vertices < 0:
        raise ValueError(f"vertices must be a count ≥ 3 or an (m, 2) array, not {vertices!r}")
    else:
        vertices = int(vertices)
    if not isinstance(smooth, str):
        smooth = float(smooth)
    core, report = _core.fit_smooth(
        pts, vals, vertices, _triangles(triangles), smooth, energy
    )
    return PsInterpolator._wrap(core, fill_value), report
