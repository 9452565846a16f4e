//! The model (docs/design.md, "The model"): corners, curves and faces of the
//! hard features with stable 0-based ids, and the exact limit curves —
//! evaluation, arc length, the surface points of a curve point on each
//! side, local projection and the certified closest point. What a mesh
//! generator walks: corners, then curves, then faces.
//!
//! Counts are `size_t`, ids `int32_t` (-1 for "none"). A curve's
//! parameter t runs over [0, n] for its n control edges, one unit per edge;
//! at integer t it is the limit point of that chain vertex.

use crate::closest::point;
use crate::status::{input, output, run, Fail};
use crate::status::{
    LS_ERR_INDEX_OUT_OF_RANGE, LS_ERR_INTERNAL, LS_ERR_NOT_FINITE, LS_ERR_NULL_POINTER,
    LS_ERR_PARAMETER_OUT_OF_RANGE,
};
use crate::surface::ls_surface;
use loopsurf::model::{Curve, Face};
use loopsurf::{Error, LimitCurve, Surface};
use std::ffi::c_int;

/// An id of one of `count` things, or an out-of-range error naming the
/// id and the count (`what` is e.g. "curve", `of` e.g. "the model").
fn id(index: i32, count: usize, what: &str, plural: &str, of: &str) -> Result<usize, Fail> {
    usize::try_from(index)
        .ok()
        .filter(|&i| i < count)
        .ok_or_else(|| {
            Fail::new(
                LS_ERR_INDEX_OUT_OF_RANGE,
                format!("{what} {index}: out of range ({of} has {count} {plural})"),
            )
        })
}

fn curve_id(surface: &Surface, curve: i32) -> Result<(usize, &Curve), Fail> {
    let curves = surface.model().curves();
    let c = id(curve, curves.len(), "curve", "curves", "the model")?;
    Ok((c, &curves[c]))
}

fn face_id(surface: &Surface, face: i32) -> Result<&Face, Fail> {
    let faces = surface.model().faces();
    Ok(&faces[id(face, faces.len(), "face", "faces", "the model")?])
}

/// A curve parameter: finite, and in [0, n] up to the library's round-off
/// slack (which it clamps).
fn parameter(t: f64, curve: i32, c: &Curve, what: &str) -> Result<f64, Fail> {
    let n = c.len() as f64;
    if !t.is_finite() {
        return Err(Fail::new(
            LS_ERR_NOT_FINITE,
            format!("{what} = {t} of curve {curve}: not a finite number"),
        ));
    }
    let slack = loopsurf::surface::PARAMETER_TOLERANCE * n.max(1.0);
    if t < -slack || t > n + slack {
        return Err(Fail::new(
            LS_ERR_PARAMETER_OUT_OF_RANGE,
            format!("{what} = {t} of curve {curve}: outside [0, {n}]"),
        ));
    }
    Ok(t)
}

/// A model id as C's `int32_t`, -1 for none.
fn c_id(id: Option<u32>) -> i32 {
    id.map_or(-1, |i| i as i32)
}

/// Writes the numbers of faces, curves and corners of the model (the hard
/// features of the surface's net: see docs/design.md, "The model"); each output
/// may be NULL. Valid ids are 0 to count − 1, in file order.
#[no_mangle]
pub unsafe extern "C" fn ls_model_counts(
    surface: *const ls_surface,
    nfaces: *mut usize,
    ncurves: *mut usize,
    ncorners: *mut usize,
) -> c_int {
    run("ls_model_counts", || {
        let model = input(surface, "surface")?.0.model();
        let counts = [
            model.faces().len(),
            model.curves().len(),
            model.corners().len(),
        ];
        for (p, n) in [nfaces, ncurves, ncorners].into_iter().zip(counts) {
            if !p.is_null() {
                *p = n;
            }
        }
        Ok(())
    })
}

/// Corner `corner` of the model: its control vertex (0-based, into the
/// net's vertices) and its limit point `xyz` (3 doubles), where the curves
/// ending at it end. Corners are tagged vertices and vertices with other
/// than two hard edges (crease junctions, boundary corners, dart tips), in
/// vertex order.
#[no_mangle]
pub unsafe extern "C" fn ls_model_corner(
    surface: *const ls_surface,
    corner: i32,
    vertex: *mut i32,
    xyz: *mut f64,
) -> c_int {
    run("ls_model_corner", || {
        let surface = &input(surface, "surface")?.0;
        let (vertex, xyz) = (output(vertex, "vertex")?, output(xyz, "xyz")?);
        let corners = surface.model().corners();
        let v = corners[id(corner, corners.len(), "corner", "corners", "the model")?];
        // The surface at a triangle's corner is its vertex's exact limit;
        // a corner of the model is a vertex of some triangle.
        let p =
            loopsurf::parameters::vertex_point(surface.net().topology(), v).ok_or_else(|| {
                Fail::new(
                    LS_ERR_INTERNAL,
                    format!("corner vertex {v} is in no triangle"),
                )
            })?;
        let x = surface.eval(p.tri as usize, p.v, p.w)?.x;
        *vertex = v as i32;
        std::ptr::copy_nonoverlapping(x.to_array().as_ptr(), xyz, 3);
        Ok(())
    })
}

/// Curve `curve` of the model (a maximal chain of hard edges between
/// corners, or a closed loop): its number of control edges `n_edges` (its
/// parameter runs over [0, n_edges]; its chain has n_edges + 1 vertices),
/// its `corners` at t = 0 and t = n_edges (2 ids, both -1 for a closed
/// loop), and its `faces` (2 ids): on its left, whose triangles run the
/// chain forward, and on its right (-1 where there is none: a boundary). A
/// dart's crease is a slit with the same face on both sides.
#[no_mangle]
pub unsafe extern "C" fn ls_model_curve(
    surface: *const ls_surface,
    curve: i32,
    n_edges: *mut usize,
    corners: *mut i32,
    faces: *mut i32,
) -> c_int {
    run("ls_model_curve", || {
        let surface = &input(surface, "surface")?.0;
        let outs = (
            output(n_edges, "n_edges")?,
            output(corners, "corners")?,
            output(faces, "faces")?,
        );
        let (_, c) = curve_id(surface, curve)?;
        let ends = c.corners.map_or([-1, -1], |e| e.map(|i| i as i32));
        *outs.0 = c.len();
        std::ptr::copy_nonoverlapping(ends.as_ptr(), outs.1, 2);
        std::ptr::copy_nonoverlapping(c.faces.map(c_id).as_ptr(), outs.2, 2);
        Ok(())
    })
}

/// The control vertices of curve `curve` in parameter order (0-based):
/// `chain` must hold n_edges + 1 entries (n_edges from `ls_model_curve`),
/// chain[k] being the vertex at t = k. A closed loop repeats its first
/// vertex at the end.
#[no_mangle]
pub unsafe extern "C" fn ls_model_curve_chain(
    surface: *const ls_surface,
    curve: i32,
    chain: *mut i32,
) -> c_int {
    run("ls_model_curve_chain", || {
        let surface = &input(surface, "surface")?.0;
        let chain = output(chain, "chain")?;
        let (_, c) = curve_id(surface, curve)?;
        for (k, &v) in c.chain.iter().enumerate() {
            *chain.add(k) = v as i32;
        }
        Ok(())
    })
}

/// Face `face` of the model (a maximal set of control triangles connected
/// across soft edges): its number of triangles and of bounding loops (0 for
/// a closed surface without hard edges). Faces are numbered by their first
/// triangle.
#[no_mangle]
pub unsafe extern "C" fn ls_model_face(
    surface: *const ls_surface,
    face: i32,
    ntriangles: *mut usize,
    nloops: *mut usize,
) -> c_int {
    run("ls_model_face", || {
        let surface = &input(surface, "surface")?.0;
        let outs = (output(ntriangles, "ntriangles")?, output(nloops, "nloops")?);
        let f = face_id(surface, face)?;
        *outs.0 = f.triangles.len();
        *outs.1 = f.loops.len();
        Ok(())
    })
}

/// The control triangles of face `face`, ascending (0-based): `tris` must
/// hold ntriangles entries (from `ls_model_face`).
#[no_mangle]
pub unsafe extern "C" fn ls_model_face_triangles(
    surface: *const ls_surface,
    face: i32,
    tris: *mut i32,
) -> c_int {
    run("ls_model_face_triangles", || {
        let surface = &input(surface, "surface")?.0;
        let tris = output(tris, "tris")?;
        let f = face_id(surface, face)?;
        for (i, &t) in f.triangles.iter().enumerate() {
            *tris.add(i) = t as i32;
        }
        Ok(())
    })
}

/// Loop `loop_index` (0 to nloops − 1) of face `face`: its `n` curves in
/// the order the face's triangles run its boundary (counter-clockwise seen
/// from outside), and for each whether it is run in its own direction
/// (`forward[i]` = 1, from t = 0 to n_edges) or backward (0). Each curve
/// ends where the next one begins, the last where the first begins.
/// Two calls: with `curves` and `forward` both NULL only `n` is written;
/// then pass two arrays of n entries each.
#[no_mangle]
pub unsafe extern "C" fn ls_model_face_loop(
    surface: *const ls_surface,
    face: i32,
    loop_index: i32,
    n: *mut usize,
    curves: *mut i32,
    forward: *mut i32,
) -> c_int {
    run("ls_model_face_loop", || {
        let surface = &input(surface, "surface")?.0;
        let n = output(n, "n")?;
        let arrays = match (curves.is_null(), forward.is_null()) {
            (true, true) => None,
            (false, false) => Some((curves, forward)),
            (true, false) | (false, true) => {
                let (null, given) = if curves.is_null() {
                    ("curves", "forward")
                } else {
                    ("forward", "curves")
                };
                return Err(Fail::new(
                    LS_ERR_NULL_POINTER,
                    format!(
                        "{null} is NULL but {given} is not (pass both, or both NULL to query n)"
                    ),
                ));
            }
        };
        let f = face_id(surface, face)?;
        let loops = &f.loops;
        let l = id(
            loop_index,
            loops.len(),
            "loop",
            "loops",
            &format!("face {face}"),
        )?;
        let lp = &loops[l];
        if let Some((curves, forward)) = arrays {
            for (i, &(c, fwd)) in lp.iter().enumerate() {
                *curves.add(i) = c as i32;
                *forward.add(i) = i32::from(fwd);
            }
        }
        *n = lp.len();
        Ok(())
    })
}

/// The face of control triangle `tri` (0-based), e.g. of a snapped point.
#[no_mangle]
pub unsafe extern "C" fn ls_model_triangle_face(
    surface: *const ls_surface,
    tri: i32,
    face: *mut i32,
) -> c_int {
    run("ls_model_triangle_face", || {
        let surface = &input(surface, "surface")?.0;
        let face = output(face, "face")?;
        let of = surface.model().face_of_triangle();
        let t = id(tri, of.len(), "triangle", "triangles", "the net")?;
        *face = of[t] as i32;
        Ok(())
    })
}

/// The exact limit curve `curve` at parameter t ∈ [0, n_edges]: 9 doubles
/// X, X′, X″ (derivatives with respect to t). At integer t, X is the limit
/// point of chain vertex t, and at a corner the curve's end is the corner's
/// point. Exactly at a dart tip the parameterisation is singular: X is
/// exact and the derivatives are 0. Statuses: LS_ERR_INDEX_OUT_OF_RANGE
/// (curve), LS_ERR_PARAMETER_OUT_OF_RANGE (t outside [0, n_edges] beyond
/// 1e-12 n_edges), LS_ERR_NOT_FINITE (t NaN or infinite).
#[no_mangle]
pub unsafe extern "C" fn ls_curve_evaluate(
    surface: *const ls_surface,
    curve: i32,
    t: f64,
    result: *mut f64,
) -> c_int {
    run("ls_curve_evaluate", || {
        let surface = &input(surface, "surface")?.0;
        let result = output(result, "result")?;
        let (c, cv) = curve_id(surface, curve)?;
        let t = parameter(t, curve, cv, "t")?;
        let record = LimitCurve::new(surface, c)?.eval(t)?.record();
        std::ptr::copy_nonoverlapping(record.as_ptr(), result, 9);
        Ok(())
    })
}

/// The arc length of curve `curve` from t0 to t1 (both in [0, n_edges];
/// negative when t1 < t0), by adaptive Gauss–Legendre quadrature to 1e-13
/// relative. Statuses as `ls_curve_evaluate`'s.
#[no_mangle]
pub unsafe extern "C" fn ls_curve_length(
    surface: *const ls_surface,
    curve: i32,
    t0: f64,
    t1: f64,
    length: *mut f64,
) -> c_int {
    run("ls_curve_length", || {
        let surface = &input(surface, "surface")?.0;
        let length = output(length, "length")?;
        let (c, cv) = curve_id(surface, curve)?;
        let (t0, t1) = (
            parameter(t0, curve, cv, "t0")?,
            parameter(t1, curve, cv, "t1")?,
        );
        *length = LimitCurve::new(surface, c)?.length(t0, t1)?;
        Ok(())
    })
}

/// The parameter t of curve `curve` at arc length `s` from t = 0, for
/// 0 ≤ s ≤ the curve's length (`ls_curve_length` from 0 to n_edges): to
/// place points at equal spacing along a curve. s outside that range gives
/// LS_ERR_PARAMETER_OUT_OF_RANGE, NaN LS_ERR_NOT_FINITE.
#[no_mangle]
pub unsafe extern "C" fn ls_curve_param_at_length(
    surface: *const ls_surface,
    curve: i32,
    s: f64,
    t: *mut f64,
) -> c_int {
    run("ls_curve_param_at_length", || {
        let surface = &input(surface, "surface")?.0;
        let t = output(t, "t")?;
        let (c, _) = curve_id(surface, curve)?;
        if !s.is_finite() {
            return Err(Fail::new(
                LS_ERR_NOT_FINITE,
                format!("arc length {s} along curve {curve}: not a finite number"),
            ));
        }
        // With the curve and s checked, the one argument error left is s
        // beyond the curve's length.
        *t = LimitCurve::new(surface, c)
            .and_then(|c| c.param_at_length(s))
            .map_err(|e| match e.root() {
                Error::InvalidArgument(_) => {
                    Fail::new(LS_ERR_PARAMETER_OUT_OF_RANGE, e.to_string())
                }
                _ => Fail::from(e),
            })?;
        Ok(())
    })
}

/// Where the point of curve `curve` at parameter t lies on the surface,
/// one entry per side: `n` (1 for a boundary curve, else 2), and for entry
/// i its face `faces[i]`, control triangle `tris[i]` and (v, w) =
/// (`vw[2i]`, `vw[2i+1]`), on the control edge under the curve, so that
/// `ls_evaluate(tris[i], vw[2i], vw[2i+1])` is the curve point to
/// round-off. With n = 2 the entries follow `ls_model_curve`'s faces (left,
/// right); an unused entry gets -1, -1 and NaN. `faces` and `tris` hold 2
/// entries, `vw` 4. Statuses as `ls_curve_evaluate`'s.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn ls_curve_surface_points(
    surface: *const ls_surface,
    curve: i32,
    t: f64,
    n: *mut usize,
    faces: *mut i32,
    tris: *mut i32,
    vw: *mut f64,
) -> c_int {
    run("ls_curve_surface_points", || {
        let surface = &input(surface, "surface")?.0;
        let outs = (
            output(n, "n")?,
            output(faces, "faces")?,
            output(tris, "tris")?,
            output(vw, "vw")?,
        );
        let (c, cv) = curve_id(surface, curve)?;
        let t = parameter(t, curve, cv, "t")?;
        let sides = LimitCurve::new(surface, c)?.surface_points(t)?;
        let (mut f, mut tr, mut p) = ([-1i32; 2], [-1i32; 2], [f64::NAN; 4]);
        for (i, (face, sp)) in sides.iter().take(2).enumerate() {
            f[i] = *face as i32;
            tr[i] = sp.tri as i32;
            p[2 * i] = sp.v;
            p[2 * i + 1] = sp.w;
        }
        *outs.0 = sides.len().min(2);
        std::ptr::copy_nonoverlapping(f.as_ptr(), outs.1, 2);
        std::ptr::copy_nonoverlapping(tr.as_ptr(), outs.2, 2);
        std::ptr::copy_nonoverlapping(p.as_ptr(), outs.3, 4);
        Ok(())
    })
}

/// The nearest LOCAL minimum of the distance from `xyz` to curve `curve`,
/// by Newton's method from the guess `t_guess` (across segments, and
/// around a closed loop): its parameter `t`, point `xyz_out` (3 doubles,
/// the curve at t bit for bit) and `distance`. Fast, for points moved a
/// little along a curve; no global search (`ls_curve_snap` is global).
/// Statuses as `ls_curve_evaluate`'s for `t_guess`; LS_ERR_NOT_FINITE for
/// a NaN or infinite `xyz`.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn ls_curve_project(
    surface: *const ls_surface,
    curve: i32,
    xyz: *const f64,
    t_guess: f64,
    t: *mut f64,
    xyz_out: *mut f64,
    distance: *mut f64,
) -> c_int {
    run("ls_curve_project", || {
        let surface = &input(surface, "surface")?.0;
        let p = point(xyz)?;
        let outs = (
            output(t, "t")?,
            output(xyz_out, "xyz_out")?,
            output(distance, "distance")?,
        );
        let (c, cv) = curve_id(surface, curve)?;
        let guess = parameter(t_guess, curve, cv, "t_guess")?;
        let snap = LimitCurve::new(surface, c)?.project(p, guess)?;
        *outs.0 = snap.t;
        std::ptr::copy_nonoverlapping(snap.point.to_array().as_ptr(), outs.1, 3);
        *outs.2 = snap.distance;
        Ok(())
    })
}

/// The closest point of curve `curve` to `xyz` — the global minimum of the
/// distance over the whole curve — with a proven lower bound on that
/// distance (the certificate): `distance` − `lower_bound` ≤ `tolerance` ×
/// the control net's bounding-box diagonal. `tolerance` 0 means the default
/// (1e-12); otherwise it must be positive. Writes the parameter `t`, the
/// point `xyz_out` (3 doubles, the curve at t bit for bit), `distance` and
/// `lower_bound`. LS_ERR_INVALID_ARGUMENT for a negative tolerance.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn ls_curve_snap(
    surface: *const ls_surface,
    curve: i32,
    xyz: *const f64,
    tolerance: f64,
    t: *mut f64,
    xyz_out: *mut f64,
    distance: *mut f64,
    lower_bound: *mut f64,
) -> c_int {
    run("ls_curve_snap", || {
        let surface = &input(surface, "surface")?.0;
        let p = point(xyz)?;
        let outs = (
            output(t, "t")?,
            output(xyz_out, "xyz_out")?,
            output(distance, "distance")?,
            output(lower_bound, "lower_bound")?,
        );
        let (c, _) = curve_id(surface, curve)?;
        if !tolerance.is_finite() {
            return Err(Fail::new(
                LS_ERR_NOT_FINITE,
                format!("tolerance {tolerance}: not a finite number"),
            ));
        }
        let tolerance = if tolerance == 0.0 {
            loopsurf::snap::DEFAULT_TOLERANCE
        } else {
            tolerance
        };
        let snap = LimitCurve::new(surface, c)?.closest_point_within(p, tolerance)?;
        *outs.0 = snap.t;
        std::ptr::copy_nonoverlapping(snap.point.to_array().as_ptr(), outs.1, 3);
        *outs.2 = snap.distance;
        *outs.3 = snap.lower_bound;
        Ok(())
    })
}
