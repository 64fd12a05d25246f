//! `xper._xper`: the compiled half of the Python module. A [`PySimulation`] holds a scene's
//! simulation and the run driver's state ([`xper_simulation::Run`]) and steps it when asked;
//! between steps its state is read into NumPy arrays ([`xper_simulation::state`]) and some of it
//! written back. The loop over steps, namespaces and conveniences are `xper/__init__.py`'s.
//!
//! Nothing a caller passes may crash the interpreter: errors are exceptions of the module
//! ([`SceneError`] for bad input, [`RunError`] for a run that cannot go on), and a panic, a bug,
//! becomes an [`XperError`] naming it.

use numpy::ndarray::{ArrayView, IxDyn};
use numpy::{PyArray1, PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::cell::Cell;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;
use std::rc::Rc;
use xper_simulation::state::{ArrayData, StateArray};
use xper_simulation::{Run, RunOptions, Simulation};

mod solve;

create_exception!(xper, XperError, PyException, "Every error xper raises.");
create_exception!(
    xper,
    SceneError,
    XperError,
    "A scene, a checkpoint or an argument that cannot be run: the message names the file, the \
     place and the reason."
);
create_exception!(
    xper,
    RunError,
    XperError,
    "A run that cannot go on: a failed step (the message gives the step and the time) or an \
     output that cannot be written."
);

fn to_py(e: xper_simulation::RunError) -> PyErr {
    match e {
        xper_simulation::RunError::BadInput(m) => SceneError::new_err(m),
        xper_simulation::RunError::Runtime(m) => RunError::new_err(m),
    }
}

/// Runs `f`, turning a panic into an [`XperError`].
fn guard<T>(f: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    catch_unwind(AssertUnwindSafe(f)).unwrap_or_else(|panic| {
        let what = (panic.downcast_ref::<String>().cloned())
            .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        Err(XperError::new_err(format!(
            "internal error (a bug in xper, please report it): {what}"
        )))
    })
}

/// A scene being run: its simulation and the driver's state between steps.
#[pyclass(name = "Simulation", module = "xper._xper", unsendable)]
pub struct PySimulation {
    sim: Box<dyn Simulation>,
    /// `None` once the run is finished.
    run: Option<Run<'static>>,
    summary: Option<serde_json::Value>,
    scene: PathBuf,
    out: PathBuf,
    /// Views from [`PySimulation::view`] still alive: while there are any, nothing may move
    /// the storage they read ([`PySimulation::add_bodies`] is refused).
    views: Rc<Cell<usize>>,
}

/// The owner (NumPy's `base`) of a view into a simulation's state: it keeps the simulation
/// alive and counts itself among its live views until NumPy drops it.
#[pyclass(module = "xper._xper", unsendable)]
struct ViewOwner {
    _simulation: Py<PySimulation>,
    views: Rc<Cell<usize>>,
}

impl ViewOwner {
    fn new(simulation: Py<PySimulation>, views: Rc<Cell<usize>>) -> Self {
        views.set(views.get() + 1);
        ViewOwner {
            _simulation: simulation,
            views,
        }
    }
}

impl Drop for ViewOwner {
    fn drop(&mut self) {
        self.views.set(self.views.get() - 1);
    }
}

impl PySimulation {
    /// The run under way and its simulation, or the error of a finished run.
    fn running(&mut self) -> PyResult<(&mut Run<'static>, &mut dyn Simulation)> {
        let Some(run) = self.run.as_mut() else {
            return Err(RunError::new_err(format!(
                "the run of {} is finished (at step {}); resume from its checkpoint to go on",
                self.scene.display(),
                self.sim.step_index()
            )));
        };
        Ok((run, self.sim.as_mut()))
    }

    fn end(&mut self) -> PyResult<()> {
        if let Some(run) = self.run.take() {
            self.summary = Some(run.finish(self.sim.as_mut()).map_err(to_py)?);
        }
        Ok(())
    }
}

fn state_to_numpy<'py>(py: Python<'py>, a: StateArray) -> PyResult<Bound<'py, PyAny>> {
    let array = match a.data {
        ArrayData::F64(v) => PyArray1::from_vec(py, v).reshape(a.shape)?.into_any(),
        ArrayData::I64(v) => PyArray1::from_vec(py, v).reshape(a.shape)?.into_any(),
    };
    array.getattr("flags")?.setattr("writeable", false)?;
    Ok(array)
}

#[pymethods]
impl PySimulation {
    /// Reads the scene file `scene` and prepares its run with outputs in `out` (created if
    /// needed): at time 0 with the first frame written, or, with `resume`, from the checkpoint
    /// in `out` (as `xper run --resume`). `max_memory` (bytes) bounds the memory estimate.
    #[new]
    #[pyo3(signature = (scene, out, resume=false, progress=false, max_memory=None))]
    fn new(
        scene: PathBuf,
        out: PathBuf,
        resume: bool,
        progress: bool,
        max_memory: Option<f64>,
    ) -> PyResult<Self> {
        guard(|| {
            let scene = xper_simulation::scene_path(scene).map_err(SceneError::new_err)?;
            let opts = RunOptions {
                scene: scene.clone(),
                out: out.clone(),
                resume,
                stop_at_step: None,
                compare_serial: false,
                max_memory,
            };
            let mut prepared = xper_simulation::prepare(&opts, None).map_err(to_py)?;
            let run = Run::start(
                prepared.simulation.as_mut(),
                prepared.schedule,
                opts,
                !progress,
                None,
                prepared.file,
            )
            .map_err(to_py)?;
            Ok(PySimulation {
                sim: prepared.simulation,
                run: Some(run),
                summary: None,
                scene,
                out,
                views: Rc::new(Cell::new(0)),
            })
        })
    }

    /// Advances `n` steps, each with the frames and checkpoints the scene's schedule puts
    /// after it. Reaching the scene's end finishes the run (`summary.json`, plots, the last
    /// checkpoint); a failed step finishes it too and raises `RunError`.
    #[pyo3(signature = (n=1))]
    fn step(&mut self, n: u64) -> PyResult<()> {
        guard(|| {
            for _ in 0..n {
                let (run, sim) = self.running()?;
                if run.is_over(sim) {
                    let step = sim.step_index();
                    return Err(RunError::new_err(format!(
                        "{}: the scene's end (step {step}) is reached",
                        self.scene.display()
                    )));
                }
                run.advance(sim).map_err(to_py)?;
                if run.is_over(sim) {
                    self.end()?;
                }
            }
            Ok(())
        })
    }

    /// Ends the run now: the last checkpoint, `summary.json` and plots (status `completed`
    /// at the scene's end, `stopped` before it). Returns the summary as a dict. Does nothing
    /// more when the run is already finished.
    fn finish<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            self.end()?;
            json_to_py(
                py,
                self.summary.as_ref().unwrap_or(&serde_json::Value::Null),
            )
        })
    }

    /// Writes a frame of the current state now (`frames/`, `result.pvd`).
    fn write_frame(&mut self) -> PyResult<()> {
        guard(|| {
            let (run, sim) = self.running()?;
            run.write_frame(sim).map_err(to_py)
        })
    }

    /// Writes the tables and `checkpoint.bin` now: `xper run --resume` or
    /// `Simulation(..., resume=True)` continue from this state.
    fn write_checkpoint(&mut self) -> PyResult<()> {
        guard(|| {
            let (run, sim) = self.running()?;
            run.write_checkpoint(sim).map_err(to_py)
        })
    }

    /// Steps done.
    #[getter]
    fn step_index(&self) -> u64 {
        self.sim.step_index()
    }

    /// Simulated time (s).
    #[getter]
    fn time(&self) -> f64 {
        self.sim.time()
    }

    /// Steps the scene asks for.
    #[getter]
    fn steps(&self) -> u64 {
        self.sim.progress().0
    }

    /// Whether the scene's end is reached.
    #[getter]
    fn is_complete(&self) -> bool {
        self.sim.is_complete()
    }

    /// Whether the run is finished (its end reached, a step failed, or `finish()` called).
    #[getter]
    fn is_finished(&self) -> bool {
        self.run.is_none()
    }

    /// The scene file.
    #[getter]
    fn scene(&self) -> PathBuf {
        self.scene.clone()
    }

    /// The output directory.
    #[getter]
    fn out(&self) -> PathBuf {
        self.out.clone()
    }

    /// The arrays of the state: a list of dicts with `name`, `shape` (`n` for the count of
    /// bodies, contacts...), `dtype`, `unit`, `writable` and `about`.
    fn array_info<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let list = PyList::empty(py);
        for a in self.sim.arrays() {
            let d = PyDict::new(py);
            d.set_item("name", a.name)?;
            d.set_item("shape", a.shape)?;
            d.set_item("dtype", a.dtype)?;
            d.set_item("unit", a.unit)?;
            d.set_item("writable", a.writable)?;
            d.set_item("view", self.sim.view(a.name).is_some())?;
            d.set_item("about", a.about)?;
            list.append(d)?;
        }
        Ok(list)
    }

    /// Names of the groups, in the order the `group` arrays index them.
    #[getter]
    fn group_names(&self) -> Vec<String> {
        self.sim.group_names()
    }

    /// The array `name` of the current state, a new read-only NumPy array (a copy: the state
    /// moves on with the next step).
    fn array<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let a = self.sim.array(name).ok_or_else(|| {
                let names: Vec<&str> = self.sim.arrays().iter().map(|a| a.name).collect();
                SceneError::new_err(format!(
                    "no array {name:?}; this simulation has: {}",
                    names.join(", ")
                ))
            })?;
            state_to_numpy(py, a)
        })
    }

    /// The array `name` read in place: a read-only NumPy view of the simulation's own memory,
    /// no copy, whose values follow the steps and writes. Only arrays kept as contiguous reals
    /// have one (`array_info()`'s `view`); the view keeps the simulation alive, and
    /// `add_bodies` is refused while any view lives.
    fn view<'py>(slf: Bound<'py, Self>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        let this = slf.borrow();
        let view = guard(|| {
            this.sim.view(name).ok_or_else(|| {
                let names: Vec<&str> = (this.sim.arrays().iter())
                    .filter(|a| this.sim.view(a.name).is_some())
                    .map(|a| a.name)
                    .collect();
                SceneError::new_err(format!(
                    "{name:?} cannot be read in place (it is computed, rebuilt every step, or \
                     not an array of this simulation): read a copy with array({name:?}); the \
                     arrays with a view: {}",
                    names.join(", ")
                ))
            })
        })?;
        let owner = Bound::new(py, ViewOwner::new(slf.clone().unbind(), this.views.clone()))?;
        // SAFETY: `view.data` holds the shape's product of f64s of the simulation, which
        // `owner` keeps alive for as long as NumPy keeps the array; `add_bodies`, the only
        // call that can reallocate them, is refused while an owner lives.
        let array = unsafe {
            let values = ArrayView::from_shape_ptr(IxDyn(&view.shape), view.data);
            PyArrayDyn::borrow_from_array(&values, owner.into_any())
        };
        array.getattr("flags")?.setattr("writeable", false)?;
        Ok(array.into_any())
    }

    /// Writes `values` (the shape `array(name)` has) into the writable array `name`; the
    /// next step starts from them.
    fn set_array(&mut self, name: &str, values: PyReadonlyArrayDyn<'_, f64>) -> PyResult<()> {
        guard(|| {
            let flat: Vec<f64> = values.as_array().iter().copied().collect();
            (self.sim)
                .set_array(name, values.shape(), &flat)
                .map_err(SceneError::new_err)
        })
    }

    /// Adds the bodies of `text` (a scene file holding only them and what they need) between
    /// steps; returns their indices.
    fn add_bodies(&mut self, text: &str) -> PyResult<Vec<usize>> {
        guard(|| {
            self.running()?;
            if self.views.get() > 0 {
                return Err(SceneError::new_err(format!(
                    "add_bodies: {} view(s) from view() read the bodies' arrays in place, and \
                     adding bodies may move them; delete the views (and arrays sliced from \
                     them) or read copies with array() first",
                    self.views.get()
                )));
            }
            self.sim.add_bodies(text).map_err(SceneError::new_err)
        })
    }

    /// The tables of the run (`series.csv`, ...) as dicts of NumPy columns, by file name.
    fn tables<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let tables = PyDict::new(py);
        for (name, table) in self.sim.tables() {
            let columns = PyDict::new(py);
            for (k, column) in table.columns.iter().enumerate() {
                let values: Vec<f64> = table.rows.iter().map(|r| r[k]).collect();
                let array = PyArray1::from_vec(py, values);
                array.getattr("flags")?.setattr("writeable", false)?;
                columns.set_item(column, array)?;
            }
            tables.set_item(name, columns)?;
        }
        Ok(tables)
    }

    /// The last row of the first table (`series.csv`: the last step's sweeps, residual,
    /// energies...) as a dict, empty before the first step.
    fn report<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let row = PyDict::new(py);
        if let Some((_, table)) = self.sim.tables().first() {
            if let Some(last) = table.rows.last() {
                for (column, value) in table.columns.iter().zip(last) {
                    row.set_item(column, value)?;
                }
            }
        }
        Ok(row)
    }

    /// The summary of the finished run (`summary.json`), `None` before.
    #[getter]
    fn summary<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.summary.as_ref().map(|s| json_to_py(py, s)).transpose()
    }
}

/// Reads and checks the scene file at `path` without running it; returns its kind:
/// `rigid`, `rigid3d`, `fluid` or `fracture`.
#[pyfunction]
fn scene_kind(path: PathBuf) -> PyResult<&'static str> {
    guard(|| {
        Ok(
            match xper_simulation::LoadedScene::read(&path).map_err(to_py)? {
                xper_simulation::LoadedScene::Rigid { .. } => "rigid",
                xper_simulation::LoadedScene::Rigid3 { .. } => "rigid3d",
                xper_simulation::LoadedScene::Fluid { .. } => "fluid",
                xper_simulation::LoadedScene::Fracture { .. } => "fracture",
            },
        )
    })
}

/// The text of the scene the checkpoint in `out` was written for (each checkpoint keeps it).
#[pyfunction]
fn checkpoint_scene(out: PathBuf) -> PyResult<String> {
    guard(|| {
        let sealed = xper_simulation::checkpoint::open(&out, "cannot load").map_err(to_py)?;
        Ok(sealed.header.scene_text)
    })
}

/// A JSON value as Python objects (through the standard `json` module).
fn json_to_py<'py>(py: Python<'py>, v: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (v.to_string(),))
}

/// The compiled module.
#[pymodule]
fn _xper(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_class::<PySimulation>()?;
    m.add_function(wrap_pyfunction!(solve::solve_csr, m)?)?;
    m.add_function(wrap_pyfunction!(solve::read_problem, m)?)?;
    m.add_function(wrap_pyfunction!(scene_kind, m)?)?;
    m.add_function(wrap_pyfunction!(checkpoint_scene, m)?)?;
    m.add("XperError", py.get_type::<XperError>())?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("RunError", py.get_type::<RunError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
