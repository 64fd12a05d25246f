//! The 5-point Laplacian on unpadded row-major arrays, written directly from the ghost rules
//! (independently of the solver's padded kernels, which the tests check against it).

use crate::{Boundary, GridShape, PoissonSide};

/// `phi[neighbour] - phi[centre]` across one face: inside, periodic, or through a ghost.
#[inline]
fn difference(
    phi: &[f64],
    centre: usize,
    neighbour: Option<usize>,
    wrap: usize,
    side: PoissonSide,
) -> f64 {
    let c = phi[centre];
    match (neighbour, side) {
        (Some(k), _) => phi[k] - c,
        (None, PoissonSide::Neumann) => 0.0,
        (None, PoissonSide::Dirichlet) => -2.0 * c,
        (None, PoissonSide::Periodic) => phi[wrap] - c,
    }
}

/// `out = Lap phi`.
pub(crate) fn apply(shape: &GridShape, boundary: &Boundary, phi: &[f64], out: &mut [f64]) {
    let (nx, ny) = (shape.nx, shape.ny);
    let (cx, cy) = (1.0 / (shape.hx * shape.hx), 1.0 / (shape.hy * shape.hy));
    for j in 0..ny {
        for i in 0..nx {
            let k = i + nx * j;
            let west = difference(
                phi,
                k,
                (i > 0).then(|| k - 1),
                nx * j + nx - 1,
                boundary.left,
            );
            let east = difference(phi, k, (i + 1 < nx).then(|| k + 1), nx * j, boundary.right);
            let south = difference(
                phi,
                k,
                (j > 0).then(|| k - nx),
                i + nx * (ny - 1),
                boundary.bottom,
            );
            let north = difference(phi, k, (j + 1 < ny).then(|| k + nx), i, boundary.top);
            out[k] = cx * (west + east) + cy * (south + north);
        }
    }
}
