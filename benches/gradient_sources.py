#!/usr/bin/env python3
"""Issue 12: where the accuracy gap to SciPy's Clough-Tocher comes from on rough data.

Held-out RMS error of the PS-spline (`pssurf.PsInterpolator`) on matplotlib's sample DEMs
with different gradient sources, on the same Delaunay triangles as
`CloughTocher2DInterpolator`, relative to CT (all held-out points / the tenth nearest the
hull's boundary; mean of 3 seeds). Methods (comma-separated argument):
  local, global   pssurf's own estimators
  ctgrad          SciPy's estimate_gradients_2d_global (CT's own gradients)
  knnK            weighted quadratic least squares over the K nearest data points

Usage: pip install ./crates/pssurf-py scipy matplotlib
       python3 benches/gradient_sources.py local,global,ctgrad,knn14
"""
import sys, numpy as np
from scipy.interpolate import CloughTocher2DInterpolator
from scipy.interpolate._interpnd import estimate_gradients_2d_global
from scipy.spatial import Delaunay, cKDTree
import pssurf

# The data sets and the hull distance of the accuracy benchmark (this script's folder).
from accuracy_real_data import datasets, hull_distance


def knn_quad(train, z, k, w_pow=1.0):
    tree = cKDTree(train)
    d, idx = tree.query(train, k + 1)
    g = np.zeros((len(train), 2))
    for i in range(len(train)):
        nb = idx[i, 1:]
        D = train[nb] - train[i]
        h = np.max(np.abs(D))
        D = D / h
        A = np.c_[D, 0.5 * D[:, 0]**2, D[:, 0]*D[:, 1], 0.5*D[:, 1]**2]
        w = 1 / np.linalg.norm(D, axis=1)**w_pow
        sol = np.linalg.lstsq(A * w[:, None], (z[nb] - z[i]) * w, rcond=None)[0]
        g[i] = sol[:2] / h
    return g

methods = sys.argv[1].split(",") if len(sys.argv) > 1 else ["local", "global", "ctgrad"]
for name, grid in datasets():
    ny, nx = grid.shape
    yy, xx = np.mgrid[0:ny, 0:nx]
    nodes = np.c_[xx.ravel(), yy.ravel()].astype(float)
    values = grid.ravel()
    for density in [0.02, 0.05, 0.2]:
        acc = {}
        for seed in range(3):
            rng = np.random.default_rng(seed)
            pick = rng.random(len(nodes)) < density
            train, z = nodes[pick], values[pick]
            rest = nodes[~pick]
            dist = hull_distance(train, rest)
            inside = dist > 1e-9
            test, truth, dist = rest[inside], values[~pick][inside], dist[inside]
            near = dist <= np.quantile(dist, 0.1)
            tri = Delaunay(train)
            preds = {"ct": CloughTocher2DInterpolator(tri, z)(test)}
            for m in methods:
                if m in ("local", "global"):
                    f = pssurf.PsInterpolator(train, z, gradient_method=m, triangles=tri.simplices)
                elif m == "ctgrad":
                    gr = estimate_gradients_2d_global(tri, z.reshape(-1, 1)).reshape(-1, 2)
                    f = pssurf.PsInterpolator(train, z, gradients=gr, triangles=tri.simplices)
                elif m.startswith("knn"):
                    k = int(m[3:])
                    f = pssurf.PsInterpolator(train, z, gradients=knn_quad(train, z, k), triangles=tri.simplices)
                preds[m] = f(test)
            for k, p in preds.items():
                err = p - truth
                acc.setdefault(k, []).append(np.sqrt(np.nanmean(err ** 2)))
                acc.setdefault(k + "_b", []).append(np.sqrt(np.nanmean(err[near] ** 2)))
        m = {k: np.mean(v) for k, v in acc.items()}
        line = f"{name} {density:.0%} CT {m['ct']:.3f}/{m['ct_b']:.3f}"
        for k in methods:
            line += f" | {k} {m[k]/m['ct']:.3f}/{m[k+'_b']/m['ct_b']:.3f}"
        print(line, flush=True)
