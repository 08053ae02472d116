//! Tests of triangulation validation, adjacency and point location.

use nalgebra::Point2;

use super::*;
use crate::test_util::meshes::{catalogue, compact};
use crate::test_util::*;

fn p(x: f64, y: f64) -> Point2<f64> {
    Point2::new(x, y)
}

#[test]
fn adjacency_is_symmetric_and_euler_holds() {
    for seed in 0..5 {
        for (name, t) in catalogue(seed) {
            for s in 0..t.triangle_count() {
                for i in 0..3 {
                    let (a, b) = t.edge_vertices(s, i);
                    if let Some(n) = t.neighbor(s, i) {
                        // The neighbour has the reversed edge and points back.
                        let j = (0..3)
                            .find(|&j| t.edge_vertices(n, j) == (b, a))
                            .expect(name);
                        assert_eq!(t.neighbor(n, j), Some(s), "{name}");
                    } else {
                        assert!(t.is_boundary_vertex(a) && t.is_boundary_vertex(b));
                    }
                }
            }
            // A planar domain with h holes has h + 1 boundary loops and V − E + T = 1 − h.
            let loops = crate::surface::Domain::from_triangulation(&t)
                .boundary()
                .len() as i64;
            let euler = t.vertex_count() as i64 - t.edge_count() as i64 + t.triangle_count() as i64;
            assert_eq!(euler, 2 - loops, "{name}");
            assert_eq!(loops, 1 + i64::from(name == "holed"), "{name}");
            let total: usize = (0..t.vertex_count()).map(|v| t.molecule_number(v)).sum();
            assert_eq!(total, 3 * t.triangle_count());
            for v in 0..t.vertex_count() {
                for &s in t.molecule(v) {
                    assert!(t.corner_of(s as usize, v).is_some());
                }
            }
        }
    }
}

#[test]
fn point_location_finds_the_containing_triangle() {
    let mut r = rng(20);
    for (name, t) in catalogue(3) {
        let (lo, hi) = t.bounds();
        let mut hint = 0;
        let mut inside = 0;
        for _ in 0..2000 {
            let q = p(uniform(&mut r, lo.x, hi.x), uniform(&mut r, lo.y, hi.y));
            let a = t.locate(q);
            let b = t.locate_from(q, hint);
            // Brute force: the truth.
            let truth =
                (0..t.triangle_count()).find(|&s| t.bary(s, q).iter().all(|&x| x >= -1e-12));
            assert_eq!(a.is_some(), truth.is_some(), "{name} {q:?}");
            assert_eq!(b.is_some(), truth.is_some(), "{name} {q:?}");
            if let (Some(a), Some(b)) = (a, b) {
                inside += 1;
                for loc in [a, b] {
                    assert!(loc.bary.iter().all(|&x| x >= -INSIDE_TOLERANCE));
                    let back = t.triangle_geometry(loc.triangle).point(loc.bary);
                    assert!((back - q).norm() < 1e-12, "{name}");
                }
                hint = b.triangle;
            }
        }
        assert!(inside > 500, "{name}: too few inside points ({inside})");
        // Vertices and edge midpoints are found (they lie on several triangles).
        for v in 0..t.vertex_count() {
            assert!(t.locate(t.vertex(v)).is_some(), "{name} vertex {v}");
        }
    }
}

#[test]
fn clockwise_input_is_reoriented() {
    let v = vec![p(0., 0.), p(1., 0.), p(0., 1.), p(1., 1.)];
    let t = Triangulation::new(v, vec![[0, 2, 1], [1, 2, 3]]);
    for s in 0..2 {
        assert!(t.triangle_geometry(s).det() > 0.0);
    }
    assert_eq!((0..3).filter(|&i| t.neighbor(0, i).is_some()).count(), 1);
}

/// Vertex 0 at the origin and `n` more on the unit circle, `step` degrees apart, with the
/// fan of triangles (0, k, k + 1) around the origin (k cyclic).
fn fan_around_origin(n: usize, step: f64) -> (Vec<Point2<f64>>, Vec<[usize; 3]>) {
    let mut v = vec![p(0., 0.)];
    for k in 0..n {
        let a = (step * k as f64).to_radians();
        v.push(p(a.cos(), a.sin()));
    }
    let fan = (0..n).map(|k| [0, 1 + k, 1 + (k + 1) % n]).collect();
    (v, fan)
}

/// Two triangles on the same side of an edge are found whichever end of the edge has the
/// smaller molecule (the one the adjacency search scans): a fan of eight triangles around
/// vertex 0 and one more triangle on edge 0 → 1, or on edge 2 → 0, running the same way.
#[test]
fn overlaps_are_found_from_either_end_of_the_edge() {
    let (mut v, fan) = fan_around_origin(8, 45.0);
    assert!(Triangulation::try_new(v.clone(), fan.clone()).is_ok());
    v.push(p(0.6, 0.2));
    for extra in [[0, 1, 9], [2, 0, 9]] {
        for first in [true, false] {
            let mut tris = fan.clone();
            if first {
                tris.insert(0, extra);
            } else {
                tris.push(extra);
            }
            let e = Triangulation::try_new(v.clone(), tris).unwrap_err();
            assert!(
                matches!(e, TriangulationError::NonConforming { .. }),
                "{extra:?}: {e}"
            );
        }
    }
}

#[test]
fn bad_triangulations_are_rejected_with_the_offending_element() {
    use TriangulationError as E;
    // An interior vertex whose fan winds twice (a pentagram of five 144° triangles).
    let (v, tris) = fan_around_origin(5, 144.0);
    let e = Triangulation::try_new(v, tris).unwrap_err();
    assert!(matches!(e, E::NonConforming { .. }), "{e}");
    assert!(e.to_string().contains("around vertex 0"), "{e}");

    // Two triangles on the same side of an edge.
    let v2 = vec![p(0., 0.), p(2., 0.), p(1., 1.), p(1., 0.5)];
    let e = Triangulation::try_new(v2, vec![[0, 1, 2], [0, 1, 3]]).unwrap_err();
    assert!(matches!(e, E::NonConforming { triangle: 1, .. }), "{e}");

    // A bow-tie: two triangles touching at vertex 0 only.
    let v3 = vec![p(0., 0.), p(1., 0.), p(1., 1.), p(-1., 0.), p(-1., -1.)];
    let e = Triangulation::try_new(v3, vec![[0, 1, 2], [0, 3, 4]]).unwrap_err();
    assert_eq!(e, E::NonManifoldVertex { vertex: 0 });

    // Separate triangles whose boundaries cross.
    let v4 = vec![
        p(0., 0.),
        p(2., 0.),
        p(1., 2.),
        p(0., 1.),
        p(2., 1.),
        p(1., -1.),
    ];
    let e = Triangulation::try_new(v4, vec![[0, 1, 2], [3, 5, 4]]).unwrap_err();
    assert!(matches!(e, E::NonConforming { .. }), "{e}");
    assert!(e.to_string().contains("cross"), "{e}");

    // An edge shared by three triangles.
    let v5 = vec![p(0., 0.), p(1., 0.), p(0.5, 1.), p(0.5, -1.), p(0.5, 2.)];
    let e = Triangulation::try_new(v5, vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]]).unwrap_err();
    assert!(
        matches!(e, E::NonConforming { .. } | E::NonManifoldEdge { .. }),
        "{e}"
    );

    // A Delaunay triangulation of collinear or coincident points.
    assert_eq!(
        Triangulation::delaunay(vec![p(0., 0.), p(1., 1.), p(2., 2.)]).unwrap_err(),
        E::CollinearPoints
    );
    assert_eq!(
        Triangulation::delaunay(vec![p(0., 0.), p(1., 0.), p(0., 1.), p(0., 0.)]).unwrap_err(),
        E::DuplicateVertex {
            first: 0,
            second: 3
        }
    );
}

#[test]
fn non_convex_domains_locate_across_the_notch() {
    // An L-shape: walking from one arm towards the other hits the boundary; the R-tree fallback
    // must still find the point.
    let v = vec![
        p(0., 0.),
        p(2., 0.),
        p(2., 1.),
        p(1., 1.),
        p(1., 2.),
        p(0., 2.),
        p(1., 0.),
        p(0., 1.),
    ];
    let t = compact(
        &v,
        &[
            [0, 6, 3],
            [6, 1, 2],
            [6, 2, 3],
            [0, 3, 7],
            [7, 3, 4],
            [7, 4, 5],
        ],
    );
    let start = t.locate(p(1.9, 0.1)).unwrap().triangle;
    let far = t.locate_from(p(0.1, 1.9), start).unwrap();
    assert!(far.bary.iter().all(|&x| x >= 0.0));
    assert!(t.locate(p(1.5, 1.5)).is_none(), "the notch is outside");
    assert!(t.locate_from(p(1.5, 1.5), start).is_none());
}

#[test]
fn delaunay_peels_zero_area_slivers_off_the_hull() {
    // A lattice has many collinear points on its hull: Delaunay slivers of zero area.
    let pts: Vec<_> = (0..60)
        .map(|k| p((k as f64 * 0.618).fract(), (k as f64 * 0.377).fract()))
        .collect();
    let t = Triangulation::delaunay(pts).unwrap();
    for s in 0..t.triangle_count() {
        assert!(!t.triangle_geometry(s).is_degenerate());
    }
    assert_eq!(t.vertex_count(), 60);
}

#[test]
fn delaunay_peels_thin_hull_slivers_without_losing_vertices_or_making_bow_ties() {
    // Row 2 lies 1e-10 inside the hull edge (0,0)–(2,0): the sliver between them is peeled.
    let (t, peeled) = Triangulation::delaunay_with_peeled(vec![
        p(0.0, 0.0),
        p(2.0, 0.0),
        p(1.0, 1e-10),
        p(1.0, 1.0),
    ])
    .unwrap();
    assert_eq!(peeled.len(), 1);
    let mut sliver = peeled[0];
    sliver.sort_unstable();
    assert_eq!(sliver, [0, 1, 2]);
    assert_eq!((t.vertex_count(), t.triangle_count()), (4, 2));
    // 1e-7 inside is thicker than PEEL_THICKNESS: kept.
    let (t, peeled) = Triangulation::delaunay_with_peeled(vec![
        p(0.0, 0.0),
        p(2.0, 0.0),
        p(1.0, 1e-7),
        p(1.0, 1.0),
    ])
    .unwrap();
    assert!(peeled.is_empty());
    assert_eq!(t.triangle_count(), 3);
    // Stacked slivers over the hull edge (0,0)–(2,0): peeling goes on layer by layer but
    // never removes a vertex's last triangle nor joins two parts at one vertex (the result
    // validates, so neither happened).
    let (t, peeled) = Triangulation::delaunay_with_peeled(vec![
        p(0.0, 0.0),
        p(2.0, 0.0),
        p(1.0, 1e-10),
        p(1.0, 2e-10),
        p(1.0, 1.0),
    ])
    .unwrap();
    assert!(!peeled.is_empty());
    assert_eq!(t.vertex_count(), 5);
    assert_eq!(t.triangle_count() + peeled.len(), 5);
}

#[test]
fn coordinates_beyond_the_supported_range_are_refused() {
    for big in [1e61, 1e151, 1e308, -9e307, 1e-43, -1e-100, 5e-324] {
        let v = vec![p(0.0, 0.0), p(big, 0.0), p(0.0, 1.0)];
        assert_eq!(
            Triangulation::try_new(v.clone(), vec![[0, 1, 2]]).unwrap_err(),
            TriangulationError::CoordinateOutOfRange(1)
        );
        assert_eq!(
            Triangulation::delaunay(v).unwrap_err(),
            TriangulationError::CoordinateOutOfRange(1)
        );
    }
    // At the limit itself, areas stay finite and the triangulation is valid.
    let v = vec![
        p(-MAX_COORDINATE, 0.0),
        p(MAX_COORDINATE, 0.0),
        p(0.0, MAX_COORDINATE),
    ];
    let t = Triangulation::try_new(v.clone(), vec![[0, 1, 2]]).unwrap();
    assert_eq!(Triangulation::delaunay(v).unwrap().triangle_count(), 1);
    let v = vec![p(0.0, 0.0), p(MIN_COORDINATE, 0.0), p(0.0, MIN_COORDINATE)];
    assert_eq!(Triangulation::delaunay(v).unwrap().triangle_count(), 1);
    assert!(t.triangle_geometry(0).det().is_finite());
}

/// Issue 13, "overlapping (folded) triangles pass validation": parts of a domain stacked on
/// one another are refused by the exact winding test of the boundary loops, whatever their
/// nesting; holes and separate parts are accepted.
#[test]
fn folded_and_stacked_triangulations_are_refused_exactly() {
    let square = vec![p(0.0, 0.0), p(4.0, 0.0), p(4.0, 4.0), p(0.0, 4.0)];
    let inner = [p(1.0, 1.0), p(2.0, 1.0), p(1.0, 2.0)];
    let mut v = square.clone();
    v.extend(inner);
    // A triangle lying inside the square, sharing nothing with it.
    let e = Triangulation::try_new(v.clone(), vec![[0, 1, 2], [0, 2, 3], [4, 5, 6]]).unwrap_err();
    assert!(
        matches!(&e, TriangulationError::NonConforming { detail, .. } if detail.contains("inside another part")),
        "{e}"
    );
    // The same triangle beside the square: two separate parts, valid.
    let beside: Vec<_> = v
        .iter()
        .enumerate()
        .map(|(k, q)| if k >= 4 { p(q.x + 10.0, q.y) } else { *q })
        .collect();
    Triangulation::try_new(beside, vec![[0, 1, 2], [0, 2, 3], [4, 5, 6]]).unwrap();
    // A square with a square hole (8 triangles around it): valid; a triangle placed in the
    // hole is a separate part, valid; one placed over the ring overlaps it.
    let mut ring = square.clone();
    ring.extend([p(1.0, 1.0), p(3.0, 1.0), p(3.0, 3.0), p(1.0, 3.0)]);
    let ring_tris = vec![
        [0, 1, 5],
        [0, 5, 4],
        [1, 2, 6],
        [1, 6, 5],
        [2, 3, 7],
        [2, 7, 6],
        [3, 0, 4],
        [3, 4, 7],
    ];
    Triangulation::try_new(ring.clone(), ring_tris.clone()).unwrap();
    let with = |a: Point2<f64>, b: Point2<f64>, c: Point2<f64>| {
        let mut v = ring.clone();
        v.extend([a, b, c]);
        let mut t = ring_tris.clone();
        t.push([8, 9, 10]);
        Triangulation::try_new(v, t)
    };
    with(p(1.5, 1.5), p(2.5, 1.5), p(1.5, 2.5)).unwrap();
    let e = with(p(0.2, 0.2), p(0.8, 0.2), p(0.2, 0.8)).unwrap_err();
    assert!(matches!(e, TriangulationError::NonConforming { .. }), "{e}");
    // A triangle touching the hole's boundary from inside at one point is refused too (a
    // vertex on a boundary edge).
    let e = with(p(2.0, 1.0), p(2.5, 1.5), p(1.5, 1.5)).unwrap_err();
    assert!(matches!(e, TriangulationError::NonConforming { .. }), "{e}");
    // A fan folded over itself at a boundary vertex: triangles around (0, 0) sweeping more
    // than a full turn (all counter-clockwise, each edge shared properly).
    let fan = vec![
        p(0.0, 0.0),
        p(1.0, 0.0),
        p(0.0, 1.0),
        p(-1.0, 0.0),
        p(0.0, -1.0),
        p(0.9, 0.1),
    ];
    let e =
        Triangulation::try_new(fan, vec![[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]]).unwrap_err();
    assert!(matches!(e, TriangulationError::NonConforming { .. }), "{e}");
}

/// Nearly but not exactly degenerate configurations are decided exactly: a vertex 1e-300
/// off a boundary edge is not on it; orientation is never misjudged near zero.
#[test]
fn boundary_contacts_are_decided_exactly() {
    // Triangle B's vertex lies exactly on A's boundary edge: a hanging node.
    let v = vec![
        p(0.0, 0.0),
        p(2.0, 0.0),
        p(0.0, 2.0),
        p(1.0, 1.0),
        p(3.0, 1.0),
        p(2.0, 3.0),
    ];
    let e = Triangulation::try_new(v.clone(), vec![[0, 1, 2], [3, 4, 5]]).unwrap_err();
    assert!(matches!(e, TriangulationError::NonConforming { .. }), "{e}");
    // Moved off the edge by the smallest step of its coordinates: separate parts (the gap is
    // tiny but real).
    let mut off = v.clone();
    off[3] = p(1.0_f64.next_up(), 1.0_f64.next_up());
    off[4] = p(3.0, 1.0_f64.next_up());
    Triangulation::try_new(off, vec![[0, 1, 2], [3, 4, 5]]).unwrap();
}

/// The Morton order sorts by the interleaved 16-bit grid codes (computed here
/// bit by bit), keeps ties in the given order, and never panics on NaN or infinite input.
#[test]
fn morton_order_sorts_by_interleaved_codes() {
    let mut r = crate::test_util::rng(77);
    let mut pts: Vec<Point2<f64>> = (0..50_000)
        .map(|_| Point2::new(uniform(&mut r, -3.0, 5.0), uniform(&mut r, 1.0, 2.0)))
        .collect();
    pts[20] = pts[10];
    let (lo, hi) = pts.iter().fold(
        (
            Point2::new(f64::MAX, f64::MAX),
            Point2::new(f64::MIN, f64::MIN),
        ),
        |(a, b), p| {
            (
                Point2::new(a.x.min(p.x), a.y.min(p.y)),
                Point2::new(b.x.max(p.x), b.y.max(p.y)),
            )
        },
    );
    let code = |i: u32| {
        let p = pts[i as usize];
        let x = ((p.x - lo.x) * (65535.0 / (hi.x - lo.x))) as u64;
        let y = ((p.y - lo.y) * (65535.0 / (hi.y - lo.y))) as u64;
        (0..16).fold(0u64, |c, b| {
            c | ((x >> b) & 1) << (2 * b) | ((y >> b) & 1) << (2 * b + 1)
        })
    };
    let got = morton_order(&pts);
    assert!(
        got.windows(2)
            .all(|w| code(w[0]) < code(w[1]) || (code(w[0]) == code(w[1]) && w[0] < w[1]))
    );
    let mut sorted = got.clone();
    sorted.sort_unstable();
    assert!(
        sorted.iter().enumerate().all(|(k, &i)| k as u32 == i),
        "a permutation"
    );
    let odd = [
        Point2::new(f64::NAN, 1.0),
        Point2::new(f64::INFINITY, 0.0),
        Point2::new(0.0, 0.0),
    ];
    assert_eq!(morton_order(&odd).len(), 3);
}

/// The radix sort of Morton keys equals a stable sort by the upper half, also when digits
/// are shared by all keys (passes skipped) and with many equal upper halves.
#[test]
fn radix_sort_by_the_upper_half_is_a_stable_sort() {
    let mut r = crate::test_util::rng(78);
    for (spread, n) in [
        (u32::MAX as f64, 10_000),
        (300.0, 20_000),
        (1.0, 5_000),
        (u32::MAX as f64, 600_000),
        (3000.0, 700_001),
    ] {
        let mut keys: Vec<u64> = (0..n)
            .map(|i| {
                let high = 0x1234_0000u64 + uniform(&mut r, 0.0, spread) as u64;
                ((high & 0xffff_ffff) << 32) | i as u64
            })
            .collect();
        let mut want = keys.clone();
        want.sort_by_key(|k| k >> 32);
        super::order::sort_by_high_half(&mut keys);
        assert_eq!(keys, want);
    }
}

/// Coordinates −0 and +0 are the same point: (−0, 1) and (0, 1) are duplicates even when
/// another point with x = −0 sorts between them by bits.
#[test]
fn duplicates_across_signed_zeros() {
    let pts = [p(-0.0, 1.0), p(-0.0, 2.0), p(0.0, 1.0), p(3.0, 4.0)];
    assert_eq!(duplicate_points(&pts), Some((0, 2)));
    assert_eq!(duplicate_points(&pts[1..]), None);
}

/// `Triangulation::delaunay` takes its neighbours from spade's half-edges and skips the
/// adjacency, fan and boundary checks of `try_new` (a Delaunay triangulation passes them by
/// construction). On random, jittered-grid, lattice, clustered and offset point sets the
/// result equals what the full validation builds from the same triangles: neighbours,
/// molecules and boundary flags.
#[test]
fn delaunay_neighbours_from_spade_equal_the_validated_ones() {
    let mut r = rng(41);
    let mut sets: Vec<Vec<Point2<f64>>> = Vec::new();
    for n in [3, 4, 10, 200, 3000] {
        sets.push(
            (0..n)
                .map(|_| p(uniform(&mut r, 0.0, 1.0), uniform(&mut r, 0.0, 1.0)))
                .collect(),
        );
    }
    for delta in [0.0, 1e-12, 1e-9, 1e-6, 1e-3] {
        let mut grid = Vec::new();
        for i in 0..25 {
            for j in 0..25 {
                // The interior moves; the hull stays a square (no slivers to peel).
                let inside = if (1..24).contains(&i) && (1..24).contains(&j) {
                    delta
                } else {
                    0.0
                };
                let dx = inside * uniform(&mut r, -1.0, 1.0);
                let dy = inside * uniform(&mut r, -1.0, 1.0);
                grid.push(p(i as f64 / 24.0 + dx, j as f64 / 24.0 + dy));
            }
        }
        sets.push(grid);
    }
    sets.push(
        (0..500)
            .map(|k| p((k as f64 * 0.618).fract(), (k as f64 * 0.377).fract()))
            .collect(),
    );
    sets.push(
        (0..400)
            .map(|k| {
                let centre = [(0.0, 0.0), (5.0, 1.0), (2.0, 7.0)][k % 3];
                p(
                    centre.0 + 1e-3 * uniform(&mut r, 0.0, 1.0),
                    centre.1 + 1e-3 * uniform(&mut r, 0.0, 1.0),
                )
            })
            .collect(),
    );
    sets.push(
        (0..400)
            .map(|_| {
                p(
                    1e6 + uniform(&mut r, 0.0, 1.0),
                    -1e6 + uniform(&mut r, 0.0, 1.0),
                )
            })
            .collect(),
    );
    let mut compared = 0;
    for points in sets {
        let (fast, peeled) = Triangulation::delaunay_with_peeled(points.clone()).unwrap();
        if !peeled.is_empty() {
            continue; // peeled domains already go through `try_new`
        }
        compared += 1;
        let tris: Vec<[usize; 3]> = (0..fast.triangle_count())
            .map(|t| fast.triangle(t))
            .collect();
        let full = Triangulation::try_new(points, tris).unwrap();
        assert_eq!(fast.neighbors(), full.neighbors());
        for v in 0..full.vertex_count() {
            assert_eq!(fast.molecule(v), full.molecule(v));
            assert_eq!(fast.is_boundary_vertex(v), full.is_boundary_vertex(v));
        }
    }
    // Only the hulls of the lattice and of the three clusters have slivers to peel.
    assert_eq!(compared, 11, "{compared} of 13 sets compared");
}

/// `validate::build_delaunay` keeps the neighbours it is given when every triangle is
/// counter-clockwise and not degenerate (that is what makes it fast: `delaunay` gives it
/// spade's), reports a degenerate triangle as `try_new` does, and hands triangles that are
/// not counter-clockwise to the full validation, which finds the neighbours itself.
#[test]
fn delaunay_build_trusts_its_neighbours_and_falls_back_to_full_validation() {
    let v = vec![p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0), p(1.0, 1.0)];
    let ccw = vec![[0, 1, 2], [1, 3, 2]];
    let none = vec![[NO_NEIGHBOR; 3]; 2];
    let full = Triangulation::try_new(v.clone(), ccw.clone()).unwrap();
    assert_ne!(full.neighbors(), &none[..]);
    // The fast path: the neighbours as given.
    let fast = validate::build_delaunay(v.clone(), ccw.clone(), none.clone()).unwrap();
    assert_eq!(fast.neighbors(), &none[..]);
    let fast = validate::build_delaunay(v.clone(), ccw, full.neighbors().to_vec()).unwrap();
    assert_eq!(fast.neighbors(), full.neighbors());
    // Clockwise triangles: the full validation orients them and finds their neighbours.
    let cw = vec![[0, 2, 1], [1, 2, 3]];
    let fallback = validate::build_delaunay(v.clone(), cw.clone(), none).unwrap();
    assert_eq!(
        fallback.neighbors(),
        Triangulation::try_new(v, cw).unwrap().neighbors()
    );
    assert_ne!(fallback.neighbors(), &[[NO_NEIGHBOR; 3]; 2][..]);
    // A degenerate triangle is named as the full validation names it.
    let flat = vec![p(0.0, 0.0), p(1.0, 0.0), p(0.5, 1e-13), p(0.5, 1.0)];
    let tris = vec![[0, 2, 3], [0, 1, 2], [1, 3, 2]];
    let e = validate::build_delaunay(flat.clone(), tris.clone(), vec![[NO_NEIGHBOR; 3]; 3]);
    assert_eq!(
        e.unwrap_err(),
        TriangulationError::DegenerateTriangle { triangle: 1 }
    );
    assert_eq!(
        Triangulation::try_new(flat, tris).unwrap_err(),
        TriangulationError::DegenerateTriangle { triangle: 1 }
    );
}
