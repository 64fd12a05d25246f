//! Grains in a fluid as named arrays ([`xper_run::state`]): the grains, walls and contacts as
//! for a rigid scene ([`crate::rigid::state`]), and the fluid on its MAC grid: at cell centres
//! (`(ny, nx)`, row `j` at height `origin_y + (j + 1/2) h`) and on the faces where the scheme
//! holds each velocity component.

use crate::rigid::state as rigid;
use xper_fluid::CoupledState;
use xper_run::state::{ArrayInfo, StateArray};

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
pub fn array(state: &CoupledState, name: &str) -> Option<StateArray> {
    let f = &state.fluid;
    let g = f.grid;
    let (nx, ny) = (g.nx, g.ny);
    // A field at cell centres, row by row from the bottom: `push` appends a cell's values.
    let cells = |shape: &[usize], push: &dyn Fn(usize, usize, &mut Vec<f64>)| {
        let mut data = Vec::with_capacity(shape.iter().product());
        for j in 0..ny {
            for i in 0..nx {
                push(i, j, &mut data);
            }
        }
        StateArray::reals(shape, data)
    };
    let faces = |d: usize, (fx, fy): (usize, usize)| {
        let mut data = Vec::with_capacity(fx * fy);
        for j in 0..fy {
            for i in 0..fx {
                data.push(f.velocity[d][g.index(i as isize, j as isize)]);
            }
        }
        StateArray::reals(&[fy, fx], data)
    };
    match name {
        "fluid.cells" => Some(StateArray::integers(&[2], vec![nx as i64, ny as i64])),
        "fluid.spacing" => Some(StateArray::reals(&[1], vec![g.h])),
        "fluid.origin" => Some(StateArray::reals(&[2], vec![g.origin.x, g.origin.y])),
        "fluid.velocity" => Some(cells(&[ny, nx, 2], &|i, j, d| {
            let v = f.cell_velocity(i, j);
            d.extend([v.x, v.y]);
        })),
        "fluid.pressure" => Some(cells(&[ny, nx], &|i, j, d| d.push(f.cell_pressure(i, j)))),
        "fluid.vorticity" => Some(cells(&[ny, nx], &|i, j, d| d.push(f.cell_vorticity(i, j)))),
        "fluid.face_velocity_x" => Some(faces(0, (nx + 1, ny))),
        "fluid.face_velocity_y" => Some(faces(1, (nx, ny + 1))),
        _ => rigid::array(&state.world, name),
    }
}
