//! The README's Rust example: load a net, tag its hard edges, evaluate,
//! snap, and mesh the limit surface. Run from a directory holding
//! `fandisk.off` (CGAL's demo mesh): `cargo run --release -p loopsurf
//! --example quickstart`.

use loopsurf::{snap, ControlNet, DVec3, Remesher, Surface};

fn main() -> loopsurf::Result<()> {
    let mut net = ControlNet::read("fandisk.off")?; // .off .obj .ply .stl .tri
    net.tag_by_angle(30.0)?; // hard edges: dihedral angle > 30°
    let surface = Surface::new(&net)?; // immutable, Send + Sync
    let e = surface.eval(17, 0.25, 0.5)?; // X, Xv, Xw, Xvv, Xvw, Xww, exact
    let k = surface.curvature(17, 0.25, 0.5)?; // k1, dir1, k2, dir2
    let s = snap::closest_point(&surface, DVec3::new(0.1, 0.2, 0.3))?; // global, certified
    println!(
        "X = {}, normal = {}, k1 = {}",
        e.x,
        e.xv.cross(e.xw).normalize(),
        k.k1
    );
    println!(
        "closest: triangle {} at ({}, {}), distance {}",
        s.tri, s.v, s.w, s.distance
    );
    let mesh = Remesher::new(&surface).adapt_curvature(true).run()?; // chord error 1e-3 × diagonal
    println!(
        "{} triangles, every vertex on the surface",
        mesh.triangles.len()
    );
    Ok(())
}
