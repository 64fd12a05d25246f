//! Grains in a fluid as named arrays ([`xper_run::state`]): the grains, walls and contacts as
//! for a rigid scene ([`crate::rigid::state`]), and the fluid on its MAC grid: at cell centres
//! (`(ny, nx)`, row `j` at height `origin_y + (j + 1/2) h`) and on the faces where the scheme
//! holds each velocity component.

use super::outputs::fluid_image;
use crate::rigid::state as rigid;
use xper_fluid::{CoupledState, FluidParams};
use xper_run::state::{ArrayData, ArrayInfo, StateArray};

/// The fluid's arrays (the grains' are [`rigid::ARRAYS`]).
pub const FLUID_ARRAYS: [ArrayInfo; 8] = [
    ArrayInfo::read_only(
        "fluid.cells",
        "(2,)",
        "int64",
        "1",
        "cells along x and y: nx, ny",
    ),
    ArrayInfo::read_only("fluid.spacing", "(1,)", "float64", "m", "cell side h"),
    ArrayInfo::read_only(
        "fluid.origin",
        "(2,)",
        "float64",
        "m",
        "lower-left corner of the grid",
    ),
    ArrayInfo::read_only(
        "fluid.velocity",
        "(ny, nx, 2)",
        "float64",
        "m/s",
        "velocity at cell centres (mean of the two faces)",
    ),
    ArrayInfo::read_only(
        "fluid.pressure",
        "(ny, nx)",
        "float64",
        "Pa",
        "pressure at cell centres",
    ),
    ArrayInfo::read_only(
        "fluid.vorticity",
        "(ny, nx)",
        "float64",
        "1/s",
        "vorticity dv/dx - du/dy at cell centres",
    ),
    ArrayInfo::read_only(
        "fluid.face_velocity_x",
        "(ny, nx + 1)",
        "float64",
        "m/s",
        "x velocity on the vertical faces, left to right",
    ),
    ArrayInfo::read_only(
        "fluid.face_velocity_y",
        "(ny + 1, nx)",
        "float64",
        "m/s",
        "y velocity on the horizontal faces, bottom to top",
    ),
];

/// Every array of a fluid scene.
pub fn arrays() -> Vec<ArrayInfo> {
    rigid::ARRAYS.iter().chain(&FLUID_ARRAYS).copied().collect()
}

/// The array `name` of `state`.
pub fn array(
    state: &CoupledState,
    params: &FluidParams,
    immersed: &[usize],
    name: &str,
) -> Option<StateArray> {
    let f = &state.fluid;
    let g = f.grid;
    let (nx, ny) = (g.nx, g.ny);
    let reals = |shape: Vec<usize>, data: Vec<f64>| StateArray {
        shape,
        data: ArrayData::F64(data),
    };
    let cell_field = |field: &str, components: usize| {
        let image = fluid_image(state, params, immersed);
        let (_, stride, values) = image.cell_data.into_iter().find(|(n, _, _)| n == field)?;
        let data: Vec<f64> = (values.chunks_exact(stride))
            .flat_map(|c| c[..components].to_vec())
            .collect();
        let shape = match components {
            1 => vec![ny, nx],
            c => vec![ny, nx, c],
        };
        Some(reals(shape, data))
    };
    let faces = |d: usize, (fx, fy): (usize, usize)| {
        let mut data = Vec::with_capacity(fx * fy);
        for j in 0..fy {
            for i in 0..fx {
                data.push(f.velocity[d][g.index(i as isize, j as isize)]);
            }
        }
        reals(vec![fy, fx], data)
    };
    match name {
        "fluid.cells" => Some(StateArray::integers(2, None, vec![nx as i64, ny as i64])),
        "fluid.spacing" => Some(StateArray::reals(1, None, vec![g.h])),
        "fluid.origin" => Some(StateArray::reals(2, None, vec![g.origin.x, g.origin.y])),
        "fluid.velocity" => cell_field("velocity", 2),
        "fluid.pressure" => cell_field("pressure", 1),
        "fluid.vorticity" => cell_field("vorticity", 1),
        "fluid.face_velocity_x" => Some(faces(0, (nx + 1, ny))),
        "fluid.face_velocity_y" => Some(faces(1, (nx, ny + 1))),
        _ => rigid::array(&state.world, name),
    }
}
