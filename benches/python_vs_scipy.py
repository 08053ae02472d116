"""pssurf's Python package against SciPy, in one process on the same arrays (issue 19).

Reproduce: `pip install ./crates/pssurf-py scipy` then `python3 benches/python_vs_scipy.py`.
Prints one table: medians of 7 runs (3 for SciPy's slow cases), wall time on all cores.
"""

import os
import statistics
import time

import numpy as np
from scipy.interpolate import CloughTocher2DInterpolator

import pssurf


def median_time(f, runs):
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def main():
    rng = np.random.default_rng(2026)
    pts = rng.random((10_000, 2))
    z = np.sin(3 * pts[:, 0]) * np.cos(2 * pts[:, 1])
    axis = np.linspace(0.0, 1.0, 1000)
    X, Y = np.meshgrid(axis, axis, indexing="ij")
    print(f"cores: {os.cpu_count()}, numpy {np.__version__}")

    def ours():
        return pssurf.PsInterpolator(pts, z)(axis, axis, grid=True)

    def theirs():
        return CloughTocher2DInterpolator(pts, z)(X, Y)

    a, b = ours(), theirs()
    both = ~np.isnan(a) & ~np.isnan(b)
    t_ours, t_theirs = median_time(ours, 7), median_time(theirs, 3)
    print(f"10k points -> 1000x1000 grid: pssurf {t_ours * 1e3:.1f} ms, "
          f"SciPy CT {t_theirs * 1e3:.1f} ms, ratio {t_theirs / t_ours:.1f}x "
          f"(values agree to {np.abs(a[both] - b[both]).max():.1e}, "
          f"NaN patterns differ at {(np.isnan(a) != np.isnan(b)).sum()} points)")
    f = pssurf.PsInterpolator(pts, z)
    t_fit = median_time(lambda: pssurf.PsInterpolator(pts, z), 7)
    t_grid = median_time(lambda: f(axis, axis, grid=True), 7)
    print(f"  of which fit {t_fit * 1e3:.1f} ms, grid evaluation {t_grid * 1e3:.1f} ms "
          f"= {1 / t_grid:.0f} M points/s")
    q = rng.random((1_000_000, 2))
    for n in (10_000, 1_000_000):
        p = rng.random((n, 2))
        g = pssurf.PsInterpolator(p, np.sin(3 * p[:, 0]) * np.cos(2 * p[:, 1]))
        t = median_time(lambda: g(q), 5)
        print(f"1M random queries on {n} vertices: {t * 1e3:.1f} ms = {1 / t:.1f} M points/s")


if __name__ == "__main__":
    main()
