"""PsInterpolator: exactness, SciPy's conventions, agreement with the CLI, errors."""

import subprocess
import threading

import numpy as np
import pytest

import pssurf
from conftest import quadratic


def inner_points(rng, n, lo=0.2, hi=0.8):
    return lo + (hi - lo) * rng.random((n, 2))


def inradius_at(pts, triangles, q):
    """The inradius of the (Delaunay or given) triangle containing each query point."""
    from scipy.spatial import Delaunay

    tri = Delaunay(pts)
    t = tri.simplices if triangles is None else np.asarray(triangles)
    if triangles is None:
        which = tri.find_simplex(q)
    else:
        which = Delaunay(pts).find_simplex(q)
        assert np.array_equal(t, tri.simplices)
    a, b, c = (pts[t[:, k]] for k in range(3))
    u, v = b - a, c - a
    area = 0.5 * np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])
    perimeter = sum(np.linalg.norm(u - v, axis=1) for u, v in ((a, b), (b, c), (c, a)))
    r = 2 * area / perimeter
    assert (which >= 0).all()
    return r[which]


@pytest.mark.parametrize(
    "kwargs",
    [
        {},
        {"gradient_method": "global"},
        {"gradient_method": "jumps"},
        {"split": "centroid"},
        {"gradients": "exact"},
        {"triangles": "given"},
    ],
    ids=["local", "global", "jumps", "centroid", "given-gradients", "given-triangles"],
)
def test_quadratics_are_reproduced(rng, kwargs):
    n = 400
    pts = rng.random((n, 2))
    if kwargs.get("split") == "centroid":
        # The centroid split is valid on a regular grid (not on every Delaunay
        # triangulation of random points: that case must raise, below).
        g = np.stack(np.meshgrid(np.linspace(0, 1, 20), np.linspace(0, 1, 20)), -1)
        pts = g.reshape(-1, 2)
    z, zx, zy, zxx, zxy, zyy = quadratic(pts[:, 0], pts[:, 1])
    kwargs = dict(kwargs)
    if kwargs.get("gradients") == "exact":
        kwargs["gradients"] = np.stack([zx, zy], axis=1)
    if kwargs.get("triangles") == "given":
        from scipy.spatial import Delaunay

        kwargs["triangles"] = Delaunay(pts).simplices
    f = pssurf.PsInterpolator(pts, z, **kwargs)
    q = inner_points(rng, 2000)
    want = quadratic(q[:, 0], q[:, 1])
    scale = np.abs(want[0]).max()
    assert np.abs(f(q) - want[0]).max() <= 1e-10 * scale
    # Rounding errors ε in the control values become ε/r in first and ε/r² in second
    # derivatives on a triangle of inradius r (random points make thin triangles).
    h_mesh = inradius_at(pts, kwargs.get("triangles"), q)
    g = f.gradient(q)
    assert (np.abs(g[:, 0] - want[1]) <= 1e-10 * scale / h_mesh).all()
    assert (np.abs(g[:, 1] - want[2]) <= 1e-10 * scale / h_mesh).all()
    h = f.hessian(q)
    for got, exact in ((h[:, 0, 0], zxx), (h[:, 0, 1], zxy), (h[:, 1, 1], zyy)):
        assert (np.abs(got - exact) <= 1e-10 * scale / h_mesh**2).all()
    # Derivatives through __call__ agree with gradient()/hessian().
    assert np.array_equal(f(q, dx=1), g[:, 0])
    assert np.array_equal(f(q[:, 0], q[:, 1], dy=1), g[:, 1])
    assert (np.abs(f(q, dx=1, dy=1) - zxy) <= 1e-10 * scale / h_mesh**2).all()
    assert np.all(f(q, dx=2, dy=1) == 0.0)


def test_centroid_split_is_refused_where_invalid(rng):
    pts = rng.random((400, 2))
    with pytest.raises(ValueError, match="misses their common edge.*use the incentre split"):
        pssurf.PsInterpolator(pts, pts[:, 0], split="centroid")


def test_curvature_of_a_paraboloid(rng):
    pts = rng.random((300, 2))
    z = pts[:, 0] ** 2 + pts[:, 1] ** 2
    grads = 2 * pts
    f = pssurf.PsInterpolator(pts, z, gradients=grads)
    q = inner_points(rng, 500)
    c = f.curvature(q[:, 0], q[:, 1])
    r2 = (q**2).sum(axis=1)
    # z = x² + y²: K = 4 / (1 + 4r²)², H = (2 + 4r²) / (1 + 4r²)^(3/2) (upward normal).
    assert np.allclose(c["K"], 4 / (1 + 4 * r2) ** 2, rtol=1e-10, atol=0)
    assert np.allclose(np.abs(c["H"]), (2 + 4 * r2) / (1 + 4 * r2) ** 1.5, rtol=1e-10, atol=0)
    assert np.all(c["k1"] >= c["k2"])
    assert np.allclose(c["k1"] * c["k2"], c["K"], rtol=1e-10, atol=0)


def test_shapes_follow_scipy(rng):
    from scipy.interpolate import CloughTocher2DInterpolator

    pts = rng.random((200, 2))
    z = np.sin(3 * pts[:, 0]) + pts[:, 1]
    f = pssurf.PsInterpolator(pts, z)
    ct = CloughTocher2DInterpolator(pts, z)
    cases = [
        ((0.5, 0.5), {}),
        (([0.3, 0.4], [0.5, 0.6]), {}),
        ((np.full((3, 4), 0.5), np.full((3, 4), 0.4)), {}),
        ((np.full((3, 1), 0.5), np.full((1, 5), 0.4)), {}),
        ((np.full((2, 3, 2), 0.45),), {}),
        ((np.array([[0.5, 0.5]]),), {}),
        (([0.5, 0.5],), {}),
        ((np.array([0.3, 0.4, 0.5, 0.6]),), {}),
    ]
    for args, kw in cases:
        assert f(*args, **kw).shape == ct(*args, **kw).shape, args
    # A tuple is the coordinate arrays, as in SciPy: f((x, y)) == f(x, y). With two points
    # it was read as the points (x0, x1), (y0, y1), silently.
    x, y = np.array([0.3, 0.6]), np.array([0.4, 0.5])
    for xi in [(x, y), (list(x), list(y)), (0.3, 0.4)]:
        assert f(xi).shape == ct(xi).shape, xi
        assert np.allclose(f(xi), ct(xi), rtol=0, atol=1e-2), xi
    assert np.array_equal(f((x, y)), f(x, y))
    assert np.array_equal(f.gradient((x, y)), f.gradient(x, y))
    assert np.array_equal(f.hessian((x, y)), f.hessian(x, y))
    # grid=True: rows along x, columns along y, as SciPy's bivariate splines.
    x = np.linspace(0.3, 0.7, 7)
    y = np.linspace(0.35, 0.65, 5)
    g = f(x, y, grid=True)
    assert g.shape == (7, 5)
    X, Y = np.meshgrid(x, y, indexing="ij")
    assert np.array_equal(g, f(X, Y))
    assert np.array_equal(f(x, y, dx=1, grid=True), f(X, Y, dx=1))


def test_outside_the_hull_is_nan_like_scipy(rng):
    from scipy.interpolate import CloughTocher2DInterpolator

    pts = rng.random((300, 2))
    z = pts[:, 0] * pts[:, 1]
    f = pssurf.PsInterpolator(pts, z)
    ct = CloughTocher2DInterpolator(pts, z)
    q = rng.uniform(-0.5, 1.5, (5000, 2))
    ours, theirs = np.isnan(f(q)), np.isnan(ct(q))
    # Both decide by the same hull; a point within rounding of the hull may differ.
    assert (ours != theirs).sum() <= 2
    assert ours.sum() > 1000
    assert np.isnan(f(np.nan, 0.5))
    g = pssurf.PsInterpolator(pts, z, fill_value=-7.0)
    assert g(5.0, 5.0) == -7.0
    h = pssurf.PsInterpolator(pts, z, extrapolate="error")
    with pytest.raises(ValueError, match="outside"):
        h(5.0, 5.0)


def test_agrees_with_the_cli(rng, cli, tmp_path):
    pts = rng.random((500, 2))
    z = np.exp(-pts[:, 0]) * np.cos(4 * pts[:, 1])
    data = tmp_path / "data.csv"
    np.savetxt(data, np.c_[pts, z], delimiter=",", header="x,y,z", comments="", fmt="%.17g")
    q = inner_points(rng, 300)
    at = tmp_path / "at.csv"
    np.savetxt(at, q, delimiter=",", header="u,v", comments="", fmt="%.17g")
    for method in ("local", "global", "jumps"):
        surf = tmp_path / f"{method}.json"
        out = tmp_path / f"{method}.csv"
        subprocess.run([cli, "fit", str(data), "-o", str(surf), "--gradients", method],
                       check=True, capture_output=True)
        subprocess.run([cli, "eval", str(surf), "--at", str(at), "-o", str(out)],
                       check=True, capture_output=True)
        table = np.genfromtxt(out, delimiter=",", names=True)
        f = pssurf.PsInterpolator(pts, z, gradient_method=method)
        assert np.abs(f(q) - table["z"]).max() <= 1e-12
        # The CLI's file loads in Python and evaluates identically.
        s = pssurf.load(surf)
        assert s.kind == "functional"
        assert np.abs(s.evaluate(q)[:, 2] - table["z"]).max() == 0.0


def test_inputs_are_converted(rng):
    pts = rng.random((300, 2))
    z = pts[:, 0] - pts[:, 1] ** 2
    f = pssurf.PsInterpolator(pts, z)
    q = inner_points(rng, 100)
    want = f(q)
    ro = q.copy()
    ro.setflags(write=False)
    assert np.array_equal(f(ro), want)
    assert np.array_equal(f(np.asfortranarray(q)), want)
    wide = np.zeros((100, 4))
    wide[:, ::2] = q
    assert np.array_equal(f(wide[:, ::2]), want)
    assert np.array_equal(f(q[:, 0].tolist(), q[:, 1].tolist()), want)
    f32 = pssurf.PsInterpolator(pts.astype(np.float32), z.astype(np.float32))
    assert np.isfinite(f32(q)).all()
    # Points as a tuple (x, y), as SciPy accepts.
    same = pssurf.PsInterpolator((pts[:, 0], pts[:, 1]), z)
    assert np.array_equal(same(q), want)


@pytest.mark.parametrize(
    "points, values, kwargs, message",
    [
        (np.zeros((5, 3)), np.zeros(5), {}, "shape"),
        (np.random.default_rng(1).random((5, 2)), np.zeros(4), {}, "5 points but 4 values"),
        (np.array([[0, 0], [1, 0], [0, 1], [1, 1.0]]), np.array([0, 1, np.nan, 2]), {}, "value of point 2 is not a finite number"),
        (np.array([[0, 0], [1, 0], [0, 1], [0, 1.0]]), np.zeros(4), {}, "same"),
        (np.array([[0, 0], [1, 1], [2, 2], [3, 3.0]]), np.zeros(4), {}, "collinear"),
        (np.array([[0, 0], [1, 0], [0, 1.0]]), np.zeros(3), {"gradient_method": "magic"}, "gradient_method"),
        (np.array([[0, 0], [1, 0], [0, 1.0]]), np.zeros(3), {"split": "middle"}, "split"),
        (np.array([[0, 0], [1, 0], [0, 1.0]]), np.zeros(3), {"triangles": [[0, 1, 3]]}, "refers to point 3"),
        (np.array([[0, 0], [1, 0], [0, 1.0]]), np.zeros(3), {"triangles": [[0.0, 1, 2]]}, "integer"),
        # Unsigned indices beyond int64 were named as negative points ("point -1").
        (np.array([[0, 0], [1, 0], [0, 1.0]]), np.zeros(3), {"triangles": np.array([[0, 1, 2**64 - 1]], dtype=np.uint64)}, "refers to point 18446744073709551615"),
        (np.array([[0, 0], [1, 0], [0, 1e308]]), np.zeros(3), {}, "range"),
        (np.array([[0, 0], [1, 0], [0, np.inf]]), np.zeros(3), {}, "finite"),
        # Bad coordinates and repeated points named as the caller's points, on every path.
        (np.where(np.arange(20).reshape(10, 2) == 15, 1e308, np.random.default_rng(2).random((10, 2))), np.zeros(10), {}, "^point 7 has a coordinate outside"),
        (np.where(np.arange(20).reshape(10, 2) == 15, np.nan, np.random.default_rng(2).random((10, 2))), np.zeros(10), {"gradients": np.zeros((10, 2))}, "^point 7 has a coordinate that is not"),
        (np.random.default_rng(2).random((10, 2))[[0, 1, 2, 3, 4, 5, 6, 7, 8, 3]], np.zeros(10), {}, "^points 3 and 9 have the same"),
        (np.random.default_rng(2).random((10, 2))[[0, 1, 2, 3, 4, 5, 6, 7, 8, 3]], np.zeros(10), {"gradients": np.zeros((10, 2))}, "^points 3 and 9 have the same"),
        (np.array([[0, 0], [1, 0], [0, 1.0]]), np.zeros((3, 2)), {}, "values must have shape"),
        (np.array([[0, 0], [1, 0], [0, 1.0]]), ["a", "b", "c"], {}, "real numbers"),
        # Values beyond ±1e60 named by the caller's row, with or without gradients.
        (np.random.default_rng(2).random((10, 2)), np.where(np.arange(10) == 7, 1e308, 0.0), {}, "value of point 7"),
        (np.random.default_rng(2).random((10, 2)), np.where(np.arange(10) == 7, 1e308, 0.0), {"gradients": np.zeros((10, 2))}, "value of point 7"),
        # Gradients: one per point, finite, named by the caller's row.
        (np.random.default_rng(2).random((10, 2)), np.zeros(10), {"gradients": np.zeros((9, 2))}, "10 points but 9 gradients"),
        (np.random.default_rng(2).random((10, 2)), np.zeros(10), {"gradients": np.zeros((11, 2))}, "10 points but 11 gradients"),
        (np.random.default_rng(2).random((10, 2)), np.zeros(10), {"gradients": np.where(np.arange(20).reshape(10, 2) == 7, np.nan, 0.0)}, "gradient of point 3 is not finite"),
    ],
)
def test_bad_input_raises_value_error(points, values, kwargs, message):
    with pytest.raises(ValueError, match=message):
        pssurf.PsInterpolator(points, values, **kwargs)


def test_smoothing_names_bad_points():
    pts = np.random.default_rng(3).random((50, 2))
    pts[17, 1] = 1e308
    with pytest.raises(ValueError, match="^point 17 has a coordinate outside"):
        pssurf.fit_smooth(pts, np.zeros(50))


def test_bad_queries_raise_value_error(rng):
    pts = rng.random((50, 2))
    f = pssurf.PsInterpolator(pts, pts[:, 0])
    with pytest.raises(ValueError, match="shape"):
        f(np.zeros((4, 3)))
    with pytest.raises(ValueError):
        f(np.zeros(3), np.zeros(4))
    with pytest.raises(ValueError, match="dx"):
        f(0.5, 0.5, dx=-1)
    with pytest.raises(ValueError, match="grid"):
        f(np.zeros((3, 2)), grid=True)


def test_the_gil_is_released(rng):
    pts = rng.random((2000, 2))
    f = pssurf.PsInterpolator(pts, pts[:, 0] * pts[:, 1])
    q = rng.random((3_000_000, 2))
    count = [0]
    running = threading.Event()
    stop = threading.Event()

    def spin():
        running.set()
        while not stop.is_set():
            count[0] += 1

    t = threading.Thread(target=spin)
    t.start()
    running.wait()
    before = count[0]
    f(q)
    during = count[0] - before
    stop.set()
    t.join()
    # With the GIL held for the whole call, the other thread could not run at all.
    assert during > 1000


def test_vertices_and_triangles(rng):
    pts = rng.random((100, 2))
    f = pssurf.PsInterpolator(pts, pts[:, 0])
    v, t = f.vertices, f.triangles
    assert v.shape == (100, 2) and t.shape[1] == 3
    assert sorted(map(tuple, v)) == sorted(map(tuple, pts))
    assert t.min() == 0 and t.max() == 99


def test_derivatives_of_any_order(rng):
    pts = rng.random((50, 2))
    f = pssurf.PsInterpolator(pts, pts[:, 0] ** 2)
    inside = f.vertices.mean(axis=0)
    for d in (3, 65, 2**40):
        assert f(*inside, dx=d) == 0.0
        assert f(*inside, dx=1, dy=d) == 0.0


def test_nearly_coincident_points_are_merged_with_a_warning(rng):
    pts = rng.random((30, 2))
    pts = np.r_[pts, pts[[4]] + 1e-15]
    z = np.r_[rng.random(30), 5.0]
    with pytest.warns(UserWarning, match="points 4, 30 are nearly coincident"):
        f = pssurf.PsInterpolator(pts, z)
    assert f(*pts[4]) == pytest.approx((z[4] + 5.0) / 2, abs=1e-9)


@pytest.mark.parametrize(
    "options", [{}, {"split": "centroid"}, {"gradients": np.c_[np.ones(5), np.zeros(5)]}]
)
def test_boundary_slivers_left_out_are_named_in_a_warning(options):
    # Points 0, 1, 2 lie on a nearly straight boundary: the Delaunay sliver between them is
    # left out of the domain, as the CLI warns, whatever the path taken.
    pts = np.array([[0.0, 0.0], [1.0, 1e-12], [2.0, 0.0], [1.0, 1.0], [0.5, 0.6]])
    with pytest.warns(UserWarning, match="points 1, 0 and 2 are nearly collinear on the boundary"):
        f = pssurf.PsInterpolator(pts, pts[:, 0], **options)
    assert len(f.triangles) == 3


def test_gradients_too_large_are_named_by_the_callers_point():
    pts = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0], [0.4, 0.6]])
    g = np.zeros((5, 2))
    g[2, 0] = 1e300
    with pytest.raises(ValueError, match="gradient of point 2 give control values that are not finite"):
        pssurf.PsInterpolator(pts, np.zeros(5), gradients=g)


@pytest.mark.parametrize("options", [{"gradients": True}, {}])
def test_nearly_coincident_points_are_merged_as_the_cli_merges_them(rng, cli, tmp_path, options):
    # With values only or given gradients (the path that also serves the centroid split)
    # alike: the same merged vertices, named in a warning, and the same file as `pssurf fit`
    # writes (it merges rows, gradient columns included, the same way).
    pts = rng.random((64, 2))
    pts = np.r_[pts, pts[[7]] + 1e-15, pts[[20]] - 2e-15]
    z = np.sin(3 * pts[:, 0]) * pts[:, 1] + 0.1 * np.arange(len(pts)) / len(pts)
    g = np.c_[np.cos(pts[:, 0]), np.sin(pts[:, 1])]
    kw = dict(options)
    columns, table = "x,y,z", np.c_[pts, z]
    if kw.pop("gradients", False):
        kw["gradients"] = g
        columns, table = "x,y,z,zx,zy", np.c_[pts, z, g]
    with pytest.warns(UserWarning) as record:
        f = pssurf.PsInterpolator(pts, z, **kw)
    messages = " | ".join(str(w.message) for w in record)
    assert "points 7, 64 are nearly coincident" in messages
    assert ("mean value and gradient" in messages) == ("gradients" in kw)
    assert "points 20, 65 are nearly coincident" in messages
    assert len(f.vertices) == 64
    data = tmp_path / "data.csv"
    np.savetxt(data, table, delimiter=",", header=columns, comments="", fmt="%.17g")
    ours, theirs = tmp_path / "py.json", tmp_path / "cli.json"
    subprocess.run([cli, "fit", str(data), "-o", str(theirs)], check=True, capture_output=True)
    f.save(ours)
    assert ours.read_bytes() == theirs.read_bytes()


def test_a_centroid_split_that_misses_an_edge_names_the_points():
    # The centroids of these two neighbours lie above their short common edge.
    pts = np.array([[0.0, 0.0], [0.0, 0.1], [-5.0, 1.0], [5.0, 1.0]])
    tris = np.array([[0, 1, 2], [1, 0, 3]])
    with pytest.raises(ValueError, match="triangles at points 0, 1, 2 and at points 1, 0, 3"):
        pssurf.PsInterpolator(pts, np.zeros(4), triangles=tris, split="centroid")
    pssurf.PsInterpolator(pts, np.zeros(4), triangles=tris)  # the incentres fit


def test_grid_points_within_rounding_of_the_hull_agree_with_pointwise():
    # Lines 1e-17 and one ulp left of the hull: pointwise evaluation (and SciPy) takes their
    # points as inside; grid=True gave NaN there, and with extrapolate="error" returned
    # that NaN without raising.
    g = np.linspace(0, 1, 11)
    X, Y = np.meshgrid(g, g)
    pts = np.c_[X.ravel(), Y.ravel()]
    x = np.array([-1e-17, np.nextafter(0.0, -1.0), 0.5, 1.0, np.nextafter(1.0, 2.0)])
    y = np.linspace(0, 1, 20)
    for kw in [{}, {"extrapolate": "error"}]:
        f = pssurf.PsInterpolator(pts, pts[:, 0] * pts[:, 1], **kw)
        grid = f(x, y, grid=True)
        assert not np.isnan(grid).any()
        # (The grid scan and pointwise evaluation differ by rounding.)
        pointwise = f(*np.meshgrid(x, y, indexing="ij"))
        assert np.allclose(grid, pointwise, rtol=1e-14, atol=1e-15)
    f = pssurf.PsInterpolator(pts, pts[:, 0] * pts[:, 1], extrapolate="error")
    with pytest.raises(ValueError, match="outside"):
        f(np.array([-1e-9, 0.5]), y, grid=True)
    with pytest.raises(ValueError, match="outside"):
        f(np.array([-1e-9, 0.5]), y, grid=True, dx=1)


def test_derivative_grids_hold_little_beside_their_output():
    # The derivative path held every grid point and an optional result per point besides
    # the output: 5 times the output's size at its peak (a grid within the budget could
    # then exhaust memory). It works in chunks now.
    script = """
import resource, numpy as np, pssurf
r = np.random.default_rng(0)
p = r.random((500, 2))
f = pssurf.PsInterpolator(p, p[:, 0] * p[:, 1])
x = np.linspace(0, 1, 3000)
f(x[:10], x[:10], grid=True, dx=1)
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
g = f(x, x, grid=True, dx=1)
after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
print((after - before) * 1024 / g.nbytes)
"""
    import sys

    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True)
    assert float(out.stdout) < 1.5, out.stdout
