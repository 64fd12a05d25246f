//! Periodic cells: the lattice of images of a cell and the images of bodies near its sides.
//!
//! A periodic cell is the parallelepiped `origin + H s`, `s` in `[0, 1)^DIM`, whose edge
//! vectors are the columns of `H`; along each periodic axis `k` the bodies repeat at
//! `x + H n` for every integer vector `n` (`n_k = 0` along the other axes). A contact between
//! body `i` and the image `x_j + H n` of body `j` is detected, and solved, like any other,
//! with `n` recorded beside it: the image moves with the cell, `d(H n)/dt = L H n` for a cell
//! deforming at velocity gradient `L` (M.P. Allen, D.J. Tildesley, "Computer simulation of
//! liquids", Oxford 1987, section 1.5.2 for images, section 11.3.1 for sheared cells; A.W.
//! Lees, S.F. Edwards, J. Phys. C 5:1921, 1972).
//!
//! The detector finds these contacts by adding, at each build of its candidate list, the
//! images of the bodies within reach of a side (each body's own reach, the largest reach, the
//! alert distance and the skin) to the broad phase: a contact with an image that touches the
//! cell is then a pair of a body and such an image.

use serde::{Deserialize, Serialize};
use xper_math::{Aabb, Real, Tensor, Vector, DIM};

/// Which image of a body: the integer multiples of the cell's edges it is shifted by.
pub type Image = [i32; DIM];

/// The lattice of a periodic cell.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Lattice {
    /// The cell's corner at `s = 0` (m).
    pub origin: Vector,
    /// The cell's edge vectors, as the columns of `H` (m).
    pub edges: Tensor,
    /// The axes along which bodies repeat.
    pub periodic: [bool; DIM],
    /// Counts the changes of the edges that relabel the images without moving them (a
    /// Lees-Edwards cell reduced by a whole edge): candidate lists built before are invalid.
    pub relabels: u64,
}

impl Lattice {
    /// The shift `H n` of image `n` (m).
    #[inline]
    pub fn shift(&self, n: &Image) -> Vector {
        self.edges * Vector::from_fn(|k, _| n[k] as Real)
    }

    /// `H^-1`, or `None` for a degenerate cell.
    pub fn inverse(&self) -> Option<Tensor> {
        self.edges.try_inverse()
    }

    /// The distance between the two faces of the cell across axis `k` (m): `1 / |row k of
    /// H^-1|`, the cell's width along the normal of those faces.
    pub fn width(&self, inverse: &Tensor, k: usize) -> Real {
        1.0 / inverse.row(k).norm()
    }

    /// The smallest width across a periodic axis (m); infinite when no axis repeats.
    pub fn smallest_width(&self) -> Real {
        let Some(inverse) = self.inverse() else {
            return 0.0;
        };
        (0..DIM)
            .filter(|&k| self.periodic[k])
            .map(|k| self.width(&inverse, k))
            .fold(Real::INFINITY, Real::min)
    }

    /// The image that brings `p` into the cell along the periodic axes: `p - H n` has its
    /// reduced coordinates in `[0, 1)` there (`n = floor(H^-1 (p - origin))`).
    pub fn wrap_of(&self, inverse: &Tensor, p: &Vector) -> Image {
        let s = inverse * (p - self.origin);
        std::array::from_fn(|k| {
            if self.periodic[k] {
                s[k].floor() as i32
            } else {
                0
            }
        })
    }

    /// Appends to `out` the images `n != 0` of a body at `p` that may come within `reach` (m)
    /// of the cell: along each periodic axis `k`, `n_k = 1` when the body is within `reach`
    /// of the face `s_k = 0` (its image then lies within `reach` beyond the face `s_k = 1`),
    /// `n_k = -1` when within `reach` of `s_k = 1`; every combination of these.
    pub fn images_near(&self, inverse: &Tensor, p: &Vector, reach: Real, out: &mut Vec<Image>) {
        let s = inverse * (p - self.origin);
        let mut choices = [[0i32; 3]; DIM];
        let mut counts = [1usize; DIM];
        for k in (0..DIM).filter(|&k| self.periodic[k]) {
            let margin = reach * inverse.row(k).norm();
            if s[k] < margin {
                choices[k][counts[k]] = 1;
                counts[k] += 1;
            }
            if s[k] > 1.0 - margin {
                choices[k][counts[k]] = -1;
                counts[k] += 1;
            }
        }
        let total: usize = counts.iter().product();
        for mut r in 1..total {
            out.push(std::array::from_fn(|k| {
                let c = choices[k][r % counts[k]];
                r /= counts[k];
                c
            }));
        }
    }

    /// A box moved by the shift of image `n`.
    pub fn shifted(&self, b: &Aabb, n: &Image) -> Aabb {
        let d = self.shift(n);
        Aabb {
            min: b.min + d,
            max: b.max + d,
        }
    }
}

/// What a detection in a periodic cell needs besides the bodies: the lattice and how many
/// times each body has been wrapped back into the cell (the image its current position is
/// of its unwrapped trajectory), which the caller keeps and the detector compares with the
/// counts at its last build.
#[derive(Clone, Copy, Debug)]
pub struct Periodic<'a> {
    /// The cell's lattice.
    pub lattice: &'a Lattice,
    /// Per body, the sum of the images it was moved back by so far.
    pub wraps: &'a [Image],
}

/// The image of body `j` seen from body `i` now, of a pair whose image was `n` when the
/// wrap counts were `built` (`[i, j]`) and are now `now`: each wrap since moved the body back
/// by one edge, so `n + (now_j - built_j) - (now_i - built_i)`.
#[inline]
pub(crate) fn relabel(n: &Image, now: [&Image; 2], built: [&Image; 2]) -> Image {
    std::array::from_fn(|k| n[k] + (now[1][k] - built[1][k]) - (now[0][k] - built[0][k]))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Lattice {
        Lattice {
            origin: Vector::zeros(),
            edges: Tensor::identity() * 2.0,
            periodic: [true; DIM],
            relabels: 0,
        }
    }

    #[test]
    fn a_body_in_a_corner_has_an_image_across_each_side_and_the_corner() {
        let lattice = square();
        let inverse = lattice.inverse().unwrap();
        let mut out = Vec::new();
        lattice.images_near(&inverse, &Vector::repeat(0.1), 0.2, &mut out);
        assert_eq!(out.len(), 2usize.pow(DIM as u32) - 1);
        out.clear();
        lattice.images_near(&inverse, &Vector::repeat(1.0), 0.2, &mut out);
        assert!(out.is_empty());
        let mut p = Vector::repeat(1.0);
        p[0] = 1.9;
        lattice.images_near(&inverse, &p, 0.2, &mut out);
        let mut expected = [0; DIM];
        expected[0] = -1;
        assert_eq!(out, [expected]);
    }

    #[test]
    fn wrapping_brings_a_point_back_into_a_sheared_cell() {
        let mut lattice = square();
        lattice.edges[(0, DIM - 1)] = 0.7;
        let inverse = lattice.inverse().unwrap();
        let p = Vector::from_fn(|k, _| [-0.3, 2.5, 4.1][k]);
        let n = lattice.wrap_of(&inverse, &p);
        let s = inverse * (p - lattice.shift(&n) - lattice.origin);
        assert!(s.iter().all(|&x| (0.0..1.0).contains(&x)), "{s:?}");
    }
}
