//! The local projection: from a neighbour's guess, points near the surface
//! land on a stationary point of the distance that is no farther than the
//! guess — almost always the certified global answer — and the returned
//! point is the surface at its parameters, bit for bit. Two kinds of
//! guesses, as a mesher has them: a point's own parameters before it was
//! moved, and the previous answer along a walk.

mod common;

use common::{cgal_mesh, example, Lcg};
use loopsurf::snap;
use loopsurf::{ControlNet, DVec3, Error, Snap, Surface};

/// What the checks of one surface found.
#[derive(Default)]
struct Tally {
    queries: usize,
    /// Answers at the global minimum (to 1e-12 of the diagonal).
    global: usize,
    /// Answers whose stationarity was checked (inside a triangle or on a
    /// smooth edge, away from the corners).
    stationary: usize,
}

struct Checker<'a> {
    name: &'a str,
    net: &'a ControlNet,
    surface: Surface,
    diagonal: f64,
    tally: Tally,
}

impl<'a> Checker<'a> {
    fn new(name: &'a str, net: &'a ControlNet) -> Self {
        Checker {
            name,
            net,
            surface: Surface::new(net).unwrap(),
            diagonal: net.bbox_diagonal(),
            tally: Tally::default(),
        }
    }

    /// Projects `p` from `guess` and checks the answer.
    fn project(&mut self, p: DVec3, guess: (usize, f64, f64), what: &str) -> Snap {
        let (surface, diagonal) = (&self.surface, self.diagonal);
        let what = format!("{}: {what}: p {p:?}, guess {guess:?}", self.name);
        let s = snap::project(surface, p, guess.0, guess.1, guess.2).unwrap();
        assert_eq!(s.lower_bound, 0.0, "{what}: a local answer proves nothing");
        let at = surface.eval(s.tri, s.v, s.w).unwrap();
        assert_eq!(at.x, s.point, "{what}: the point is the surface's");
        assert_eq!(s.distance, (s.point - p).length(), "{what}");
        // Never worse than the guess (but for the round-off of comparing
        // distances: the last step is kept unless it loses more).
        let start = (surface.point(guess.0, guess.1, guess.2).unwrap() - p).length();
        assert!(
            s.distance <= start + 1e-14 * diagonal,
            "{what}: {} farther than the guess ({start})",
            s.distance
        );
        // A stationary point: the residual normal to the surface, to 1e-9
        // of its length (and the round-off of the points). Not checked on
        // a hard edge or boundary, where a minimum may be constrained, nor
        // next to a triangle's corners, where the parametrisation of an
        // irregular vertex or a corner is singular.
        let weights = [1.0 - s.v - s.w, s.v, s.w];
        let near_corner = weights.iter().any(|&b| b > 1.0 - 1e-6);
        let on_hard_side = (0..3).any(|k| {
            // Local edge k joins corners k and k + 1: weight k + 2 is 0 on it.
            let edge = self.net.topology().triangle_edges()[s.tri][k] as usize;
            weights[(k + 2) % 3] <= 1e-12 && self.net.features().is_hard_edge(edge)
        });
        if !near_corner && !on_hard_side && !at.at_special_vertex {
            let r = p - s.point;
            for d in [at.xv, at.xw] {
                let tangential = r.dot(d).abs() / d.length();
                assert!(
                    tangential <= 1e-9 * r.length() + 1e-13 * diagonal,
                    "{what}: residual {r:?} not normal, tangential part {tangential:e}"
                );
            }
            self.tally.stationary += 1;
        }
        // The certified global answer is never farther (by more than its
        // tolerance); usually it is the same point.
        let global = snap::closest_point(surface, p).unwrap();
        assert!(
            global.distance <= s.distance + 1e-12 * diagonal,
            "{what}: the certified snap is farther ({global:?})"
        );
        self.tally.queries += 1;
        if s.distance - global.distance <= 1e-12 * diagonal {
            self.tally.global += 1;
        }
        s
    }

    /// Random surface points each moved 5e-4 of the diagonal along the
    /// surface and up to 1e-3 off it, guessed from the unmoved point.
    fn moved_points(&mut self, queries: usize, rng: &mut Lcg) {
        for i in 0..queries {
            let t = (rng.next() * self.net.triangles().len() as f64) as usize;
            let (v, w) = (0.05 + 0.4 * rng.next(), 0.05 + 0.4 * rng.next());
            let e = self.surface.eval(t, v, w).unwrap();
            let n = e.normal().expect("a tangent plane inside the triangle");
            let along = e.xv * (rng.next() - 0.5) + e.xw * (rng.next() - 0.5);
            let p = e.x
                + along * (5e-4 * self.diagonal / along.length())
                + (rng.next() - 0.5) * 2e-3 * self.diagonal * n;
            self.project(p, (t, v, w), &format!("moved point {i}"));
        }
    }

    /// Walks of steps of 1e-3 of the diagonal over the surface (each step
    /// the certified closest point of a step along the tangent plane), the
    /// points moved up to 1e-3 of the diagonal off the surface; each query
    /// is guessed from the answer to the one before.
    fn walks(&mut self, walks: usize, steps: usize, rng: &mut Lcg) {
        for k in 0..walks {
            let t = (rng.next() * self.net.triangles().len() as f64) as usize;
            let (v, w) = (0.1 + 0.3 * rng.next(), 0.1 + 0.3 * rng.next());
            let mut here =
                snap::closest_point(&self.surface, self.surface.point(t, v, w).unwrap()).unwrap();
            let mut guess = (here.tri, here.v, here.w);
            let mut heading = rng.direction();
            for i in 0..steps {
                let n = self
                    .surface
                    .normal(here.tri, here.v, here.w)
                    .unwrap_or(DVec3::Z);
                let p = here.point + (rng.next() - 0.5) * 2e-3 * self.diagonal * n;
                let s = self.project(p, guess, &format!("walk {k}, step {i}"));
                guess = (s.tri, s.v, s.w);
                heading = (heading + 0.3 * rng.direction())
                    .reject_from(n)
                    .normalize_or(n.any_orthonormal_vector());
                here =
                    snap::closest_point(&self.surface, here.point + 1e-3 * self.diagonal * heading)
                        .unwrap();
            }
        }
    }

    /// Local, not global: a guess may lie in another basin, but rarely
    /// this close to the surface.
    fn finish(self, least_global: f64) {
        let Tally {
            queries,
            global,
            stationary,
        } = self.tally;
        eprintln!(
            "{}: {global} of {queries} answers global, {stationary} checked stationary",
            self.name
        );
        assert!(
            global as f64 >= least_global * queries as f64,
            "{}: only {global} of {queries} answers global",
            self.name
        );
        assert!(
            stationary * 10 >= queries * 8,
            "{}: too few checked",
            self.name
        );
    }
}

#[test]
fn viking_from_neighbours() {
    let net = example("viking", Some(30.0));
    let mut check = Checker::new("viking 30°", &net);
    let mut rng = Lcg(17);
    check.moved_points(400, &mut rng);
    check.walks(4, 100, &mut rng);
    check.finish(0.98);
}

#[test]
fn cube_with_creases_from_neighbours() {
    let net = example("cube", Some(30.0));
    let mut check = Checker::new("cube 30°", &net);
    let mut rng = Lcg(5);
    check.moved_points(300, &mut rng);
    check.walks(3, 100, &mut rng);
    check.finish(0.98);
}

#[test]
fn pig_from_neighbours() {
    let Some(path) = cgal_mesh("pig.off") else {
        return;
    };
    let net = ControlNet::read(path).unwrap();
    let mut check = Checker::new("pig", &net);
    let mut rng = Lcg(29);
    check.moved_points(600, &mut rng);
    check.walks(6, 100, &mut rng);
    check.finish(0.98);
}

#[test]
fn bad_input_is_an_error() {
    let surface = Surface::new(&example("torus", None)).unwrap();
    let p = DVec3::new(0.1, 0.2, 0.3);
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert!(matches!(
            snap::project(&surface, DVec3::new(0.0, bad, 0.0), 0, 0.2, 0.2),
            Err(Error::InvalidArgument(_))
        ));
    }
    let triangles = surface.net().triangles().len();
    assert!(matches!(
        snap::project(&surface, p, triangles, 0.2, 0.2),
        Err(Error::InvalidArgument(_))
    ));
    for (v, w) in [
        (0.9, 0.9),
        (-0.1, 0.2),
        (0.2, -0.1),
        (f64::NAN, 0.2),
        (0.2, f64::INFINITY),
    ] {
        assert!(
            matches!(
                snap::project(&surface, p, 0, v, w),
                Err(Error::BadParameter { .. })
            ),
            "({v}, {w})"
        );
    }
    // Round-off outside the triangle is clamped, as for every query; the
    // corners themselves are guesses like any other.
    for (v, w) in [
        (-1e-14, 0.3),
        (0.5 + 1e-14, 0.5),
        (0.0, 0.0),
        (1.0, 0.0),
        (0.0, 1.0),
    ] {
        let s = snap::project(&surface, p, 0, v, w).unwrap();
        assert!(
            s.v >= 0.0 && s.w >= 0.0 && s.v + s.w <= 1.0,
            "({v}, {w}): {s:?}"
        );
    }
}
