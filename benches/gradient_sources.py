#!/usr/bin/env python3
"""Issue 12: where the accuracy gap to SciPy's Clough-Tocher comes from on rough data.

Held-out RMS error of the PS-spline (`pssurf.PsInterpolator`) on matplotlib's sample DEMs
with different gradient sources, on the same Delaunay triangles as
`CloughTocher2DInterpolator`, relative to CT (all held-out points / the tenth nearest the
hull's boundary; mean of 3 seeds). Methods (comma-separated argument):
  local, global   pssurf's own estimators
  ctgrad          SciPy's estimate_gradients_2d_global (CT's own gradients)
  knnK            weighted quadratic least squares over the K nearest data points
  edges           least squared second derivative of the PS-spline's edge curves (the C1
                  quadratic analogue of Nielson's network, which CT's estimator minimises)
  oracle          the full grid's own gradients (numpy.gradient of the DEM), not available
                  from scattered data: how good the PS-spline can be with "true" gradients
  ctoracle        Clough-Tocher itself with the oracle gradients (SciPy's CT code)

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

def edge_energy(tri, pts, z, r=0.5):
    """Gradients minimising sum over edges of the integrated squared second derivative of
    the C1 quadratic edge spline with a knot at fraction r (the PS analogue of Nielson's
    network, which CT's estimator minimises for cubic edges)."""
    import scipy.sparse as sp, scipy.sparse.linalg as spl
    s = tri.simplices
    e = np.unique(np.sort(np.r_[s[:, [0, 1]], s[:, [1, 2]], s[:, [2, 0]]], axis=1), axis=0)
    i, j = e[:, 0], e[:, 1]
    d = pts[j] - pts[i]
    L = np.linalg.norm(d, axis=1)
    df = z[j] - z[i]
    # m = 2 df - r d0 - (1-r) d1, d0 = gi.d, d1 = gj.d. Residuals:
    # (m - d0)/sqrt(r L^3) = (2df - (1+r) d0 - (1-r) d1)/sqrt(r L^3)
    # (d1 - m)/sqrt((1-r) L^3) = (-2df + r d0 + (2-r) d1)/sqrt((1-r) L^3)
    n, ne = len(pts), len(e)
    rows, cols, vals, rhs = [], [], [], []
    for k, (a0, a1, c, w) in enumerate([(-(1 + r), -(1 - r), -2.0, 1 / np.sqrt(r * L**3)),
                                        (r, 2 - r, 2.0, 1 / np.sqrt((1 - r) * L**3))]):
        row = np.arange(ne) + k * ne
        for comp in range(2):
            rows += [row, row]; cols += [2 * i + comp, 2 * j + comp]
            vals += [a0 * d[:, comp] * w, a1 * d[:, comp] * w]
        rhs.append(c * df * w)
    A = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(2 * ne, 2 * n))
    b = np.concatenate(rhs)
    g = spl.spsolve((A.T @ A).tocsc(), A.T @ b)
    return g.reshape(-1, 2)

methods = sys.argv[1].split(",") if len(sys.argv) > 1 else ["local", "global", "ctgrad"]
for name, grid in datasets():
    ny, nx = grid.shape
    yy, xx = np.mgrid[0:ny, 0:nx]
    nodes = np.c_[xx.ravel(), yy.ravel()].astype(float)
    values = grid.ravel()
    gy, gx = np.gradient(grid.astype(float))
    oracle = np.c_[gx.ravel(), gy.ravel()]
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
                elif m == "edges":
                    f = pssurf.PsInterpolator(train, z, gradients=edge_energy(tri, train, z), triangles=tri.simplices)
                elif m == "oracle":
                    f = pssurf.PsInterpolator(train, z, gradients=oracle[pick], triangles=tri.simplices)
                elif m == "ctoracle":
                    ct = CloughTocher2DInterpolator(tri, z)
                    ct.grad = oracle[pick].reshape(ct.grad.shape)
                    preds[m] = ct(test)
                    continue
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
