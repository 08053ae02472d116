"""One line per run for A/B comparisons of two builds of the Python package (issue 19).

The end-to-end job of `python_vs_scipy.py` (10k scattered points -> `PsInterpolator` ->
1000 x 1000 grid) and its two halves, with SciPy's `CloughTocher2DInterpolator` on the same
arrays in the same process: medians of 9 runs (SciPy: 3) and bests of 25.

A/B against another wheel: install it beside the current one and alternate, e.g.

    pip install --target /tmp/old --no-deps OLD.whl
    for i in 1 2 3; do PYTHONPATH=/tmp/old python3 benches/python_ab.py old
                       python3 benches/python_ab.py new; done

On a shared machine compare runs that alternate, never figures from different hours.
"""

import statistics
import sys
import time

import numpy as np
from scipy.interpolate import CloughTocher2DInterpolator

import pssurf


def times(f, runs):
    out = []
    for _ in range(runs):
        t = time.perf_counter()
        f()
        out.append((time.perf_counter() - t) * 1e3)
    return out


def main():
    label = sys.argv[1] if len(sys.argv) > 1 else "run"
    rng = np.random.default_rng(2026)
    pts = rng.random((10_000, 2))
    z = np.sin(3 * pts[:, 0]) * np.cos(2 * pts[:, 1])
    axis = np.linspace(0.0, 1.0, 1000)
    X, Y = np.meshgrid(axis, axis, indexing="ij")
    e2e = times(lambda: pssurf.PsInterpolator(pts, z)(axis, axis, grid=True), 25)
    fit = times(lambda: pssurf.PsInterpolator(pts, z), 25)
    f = pssurf.PsInterpolator(pts, z)
    grid = times(lambda: f(axis, axis, grid=True), 25)
    scipy = times(lambda: CloughTocher2DInterpolator(pts, z)(X, Y), 3)
    med = statistics.median
    print(f"{label}: end to end median {med(e2e[:9]):.1f} ms (best of 25 {min(e2e):.1f}), "
          f"fit {med(fit[:9]):.1f} ({min(fit):.1f}), grid {med(grid[:9]):.1f} ({min(grid):.1f}); "
          f"SciPy median {med(scipy):.1f} ms, ratio of medians {med(scipy) / med(e2e[:9]):.2f}")


if __name__ == "__main__":
    main()
