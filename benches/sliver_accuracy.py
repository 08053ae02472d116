"""What boundary slivers cost a C¹ quadratic interpolant, whatever its gradients (issue 12).

A 20 × 20 grid of the unit square with *every* point moved by up to δ (boundary rows too):
Delaunay leaves slivers along the nearly straight hull. Max error of sin(3x) cos(2y) over a
40 × 40 grid inside the domain, for the PS interpolant with exact gradients, with the local,
global and least-jump estimates, and for SciPy's Clough–Tocher interpolant with its own gradients.

Reproduce: `pip install ./crates/pssurf-py scipy` then `python3 benches/sliver_accuracy.py`.
"""

import warnings

import numpy as np
from scipy.interpolate import CloughTocher2DInterpolator

import pssurf


def f(x, y):
    return np.sin(3 * x) * np.cos(2 * y)


def gradient(x, y):
    return np.c_[3 * np.cos(3 * x) * np.cos(2 * y), -2 * np.sin(3 * x) * np.sin(2 * y)]


def moved_grid(delta, seed=2):
    g = np.mgrid[0:20, 0:20].reshape(2, -1).T / 19.0
    return g + np.random.default_rng(seed).uniform(-delta, delta, g.shape)


def max_error(values, q):
    inside = ~np.isnan(values)
    return np.abs(values[inside] - f(q[inside, 0], q[inside, 1])).max()


def main():
    warnings.simplefilter("ignore")  # the peeled slivers' warnings
    q = np.mgrid[0:40, 0:40].reshape(2, -1).T / 39.0
    print("| δ | exact gradients | local | global | jumps | Clough–Tocher (SciPy) |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: |")
    for delta in (0.0, 1e-12, 1e-8, 1e-6, 1e-4, 1e-3):
        p = moved_grid(delta)
        z = f(p[:, 0], p[:, 1])
        row = [
            pssurf.PsInterpolator(p, z, gradients=gradient(p[:, 0], p[:, 1]))(q),
            pssurf.PsInterpolator(p, z, gradient_method="local")(q),
            pssurf.PsInterpolator(p, z, gradient_method="global")(q),
            pssurf.PsInterpolator(p, z, gradient_method="jumps")(q),
            CloughTocher2DInterpolator(p, z)(q),
        ]
        print(f"| {delta:g} | " + " | ".join(f"{max_error(v, q):.2e}" for v in row) + " |")


if __name__ == "__main__":
    main()
