//! The local projection: from a neighbour's guess, points near the surface
//! land on a stationary point of the distance — almost always the certified
//! global answer — and the returned point is the surface at its parameters.

mod common;

use common::{cgal_mesh, example};
use loopsurf::{ControlNet, DVec3, Surface};

struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Queries within 1e-3 of the diagonal from the surface, each with the
/// parameters of a surface point about 5e-4 of the diagonal away as guess.
fn check(name: &str, net: &ControlNet, queries: usize) {
    let surface = Surface::new(net).unwrap();
    let diagonal = net.bbox_diagonal();
    let mut rng = Lcg(17);
    let mut agree = 0;
    for i in 0..queries {
        let t = (rng.next() * net.triangles().len() as f64) as usize;
        let (v, w) = (0.05 + 0.4 * rng.next(), 0.05 + 0.4 * rng.next());
        let e = surface.eval(t, v, w).unwrap();
        let n = e.xv.cross(e.xw).normalize();
        let along = e.xv * (rng.next() - 0.5) + e.xw * (rng.next() - 0.5);
        let p = e.x
            + along * (5e-4 * diagonal / along.length())
            + (rng.next() - 0.5) * 2e-3 * diagonal * n;
        let what = format!("{name}: query {i} {p:?}");
        let s = surface.project(p, t, v, w).unwrap();
        assert_eq!(s.lower_bound, 0.0, "{what}");
        let at = surface.eval(s.tri, s.v, s.w).unwrap();
        assert_eq!(at.x, s.point, "{what}");
        assert!(((s.point - p).length() - s.distance).abs() <= 1e-15 * diagonal);
        assert!(
            s.distance <= (e.x - p).length() + 1e-15 * diagonal,
            "{what}: worse than the guess"
        );
        // A stationary point: the residual normal to the surface (to 1e-6:
        // Newton stops once its step is below 1e-7 of the parameter domain,
        // which leaves the distance exact to round-off), unless the
        // point rests on a triangle's side or corner (where a hard edge or a
        // boundary may hold a constrained minimum).
        let inside = s.v > 1e-6 && s.w > 1e-6 && s.v + s.w < 1.0 - 1e-6;
        let r = p - s.point;
        if inside && !at.at_special_vertex && r.length() > 1e-9 * diagonal {
            for d in [at.xv, at.xw] {
                let cosine = r.dot(d) / (r.length() * d.length());
                assert!(
                    cosine.abs() < 1e-6,
                    "{what}: residual not normal ({cosine:e})"
                );
            }
        }
        let global = surface.closest_point(p).unwrap();
        assert!(global.distance <= s.distance + 1e-15 * diagonal, "{what}");
        if s.distance - global.distance <= 1e-12 * diagonal {
            agree += 1;
        }
    }
    // Local, not global: a guess may lie in another basin, but rarely here.
    assert!(
        agree * 100 >= queries * 98,
        "{name}: only {agree} of {queries} global"
    );
}

#[test]
fn neighbours_guesses_land_on_the_surface() {
    check("viking 30°", &example("viking", Some(30.0)), 300);
    check("cube 30°", &example("cube", Some(30.0)), 300);
    if let Some(path) = cgal_mesh("pig.off") {
        check("pig", &ControlNet::read(path).unwrap(), 500);
    }
}

#[test]
fn bad_input_is_an_error() {
    let surface = Surface::new(&example("torus", None)).unwrap();
    let p = DVec3::new(0.1, 0.2, 0.3);
    assert!(surface
        .project(DVec3::new(f64::NAN, 0.0, 0.0), 0, 0.2, 0.2)
        .is_err());
    assert!(surface.project(p, 99999, 0.2, 0.2).is_err());
    assert!(surface.project(p, 0, 0.9, 0.9).is_err());
    assert!(surface.project(p, 0, f64::NAN, 0.2).is_err());
    assert!(surface.project(p, 0, 0.2, 0.2).is_ok());
}
