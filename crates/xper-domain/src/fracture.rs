//! Distributed fracture: a [`FractureModel`] stepped on several processes.
//!
//! Elements are bodies and cohesive interfaces are contacts (Perales et al., EJCM 19, 2010), so
//! the non-smooth contact domain decomposition of rigid bodies applies unchanged
//! ([`crate::nscdd::distributed_nlgs`]; Visseq et al., Comput. Mech. 49 (2012) 709):
//!
//! 1. **Partition** (once: the mesh topology is fixed). Recursive coordinate bisection of the
//!    element centroids gives each element an owner; an interface belongs to the owner of its
//!    first element. Each process holds a part of the model ([`FractureModel::part`]): its
//!    elements, shadow copies of the elements its interfaces touch, and its interfaces.
//! 2. **Step.** Each process runs [`FractureStepper::step_with`] on its part. The interface
//!    problem is solved by NLGS over the process's interfaces, the elements held by several
//!    processes having their inverse effective mass multiplied by their multiplicity and their
//!    velocities averaged after every sweep. Every copy of an element then ends the step with
//!    the same velocity bits, hence the same displacement, material state and internal force:
//!    shadows stay copies without any exchange of state. Energies and load readings are each
//!    counted by one process and summed (one all-reduce per step).
//! 3. **Gather** (for outputs and checkpoints): owners send their elements' and interfaces'
//!    states to rank 0, which holds the whole model.

use crate::comm::Communicator;
use crate::nscdd::interface::InterfaceMap;
use crate::nscdd::solve_with_split_masses;
use crate::partition::Bisection;
use crate::rigid::stepper::RankLoad;
use xper_fracture::{
    ElementContactOperator, FractureEnergy, FractureModel, FractureStepError, FractureStepReport,
    FractureStepper, PointState,
};
use xper_math::Vector;
use xper_solver::{CohesiveTerm, ContactSolve, NlgsParams, SolveError, SolveInfo};

/// A fracture model stepped by the processes of `comm`.
pub struct DistributedFracture<'c, C: Communicator + ?Sized> {
    comm: &'c C,
    part: FractureModel,
    stepper: FractureStepper,
    solve: SharedInterfaceNlgs<'c, C>,
    /// Index in the whole model of each element of the part.
    elements: Vec<u32>,
    /// Index in the whole model of each interface of the part.
    interfaces: Vec<u32>,
    /// The whole model's energy budget after the last step.
    energy: FractureEnergy,
}

impl<'c, C: Communicator + ?Sized> DistributedFracture<'c, C> {
    /// Partitions `whole` (the same model on every process, fresh or restored from a
    /// checkpoint) among the processes of `comm` and keeps this process's part. Collective.
    pub fn new(comm: &'c C, whole: &FractureModel) -> Self {
        let me = comm.rank() as u32;
        let owners = element_owners(whole, comm.size());
        let interfaces: Vec<u32> = (0..whole.interfaces.len() as u32)
            .filter(|&i| owners[whole.interfaces[i as usize].elements[0] as usize] == me)
            .collect();
        let mut held: Vec<bool> = owners.iter().map(|&o| o == me).collect();
        for &i in &interfaces {
            for e in whole.interfaces[i as usize].elements {
                held[e as usize] = true;
            }
        }
        let elements: Vec<u32> = (0..held.len() as u32)
            .filter(|&e| held[e as usize])
            .collect();
        let part_owners: Vec<u32> = elements.iter().map(|&e| owners[e as usize]).collect();
        let shadow: Vec<bool> = part_owners.iter().map(|&o| o != me).collect();
        let energy = if me == 0 {
            whole.energy
        } else {
            FractureEnergy::default()
        };
        let part = whole.part(&elements, &shadow, &interfaces, energy, me != 0);
        let ids: Vec<u64> = elements.iter().map(|&e| u64::from(e)).collect();
        let interface = InterfaceMap::build(comm, &ids, &part_owners, &vec![true; ids.len()], None);
        DistributedFracture {
            comm,
            part,
            stepper: FractureStepper::new(),
            solve: SharedInterfaceNlgs { comm, interface },
            elements,
            interfaces,
            energy: whole.energy,
        }
    }

    /// One step of the whole model (collective). The report holds the whole model's totals.
    /// An error other than [`FractureStepError::Diverging`] (which every process meets
    /// together) may be this process's alone.
    pub fn step(&mut self) -> Result<FractureStepReport, FractureStepError> {
        let report = self.stepper.step_with(&mut self.part, &mut self.solve);
        if let Ok(r) = &report {
            self.energy = r.energy;
        }
        report
    }

    /// Steps done.
    pub fn step_index(&self) -> u64 {
        self.part.step
    }

    /// Simulated time (s).
    pub fn time(&self) -> f64 {
        self.part.time
    }

    /// Copies the state of every element and interface into `whole` on rank 0 (collective;
    /// `whole` is left alone on the other ranks): displacements, velocities, material states,
    /// internal forces, tangents, interface points, step, time and the energy budget.
    pub fn gather(&self, whole: &mut FractureModel) {
        let me = self.comm.rank() as u32;
        let mut data = Vec::new();
        let owned = (0..self.elements.len()).filter(|&k| !self.part.is_shadow(k));
        data.push(owned.clone().count() as f64);
        for k in owned {
            let el = &self.part.elements[k];
            data.push(f64::from(self.elements[k]));
            data.extend(el.displacement);
            data.extend(el.velocity);
            data.extend(el.internal_force);
            data.extend(el.stiffness.iter().flatten());
            data.extend(el.state.stress);
            data.extend(el.state.plastic_strain);
            data.push(el.state.equivalent_plastic_strain);
        }
        for (k, i) in self.part.interfaces.iter().enumerate() {
            data.push(f64::from(self.interfaces[k]));
            for p in &i.points {
                data.extend(point_values(p));
            }
        }
        let mut sends = vec![Vec::new(); self.comm.size()];
        sends[0] = data;
        let received = self.comm.all_to_all(&sends);
        if me != 0 {
            return;
        }
        for message in received {
            unpack(&message, whole);
        }
        whole.step = self.part.step;
        whole.time = self.part.time;
        whole.energy = self.energy;
        whole.cell = self.part.cell;
    }

    /// This process's share: owned elements, shadows, interface points owned (two per
    /// interface), elements shared with other processes.
    pub fn load(&self) -> RankLoad {
        let shadows = self.part.shadow.iter().filter(|&&s| s).count();
        RankLoad {
            bodies: self.elements.len() - shadows,
            shadows,
            contacts: 2 * self.part.interfaces.len(),
            interface_bodies: self.solve.interface.shared_count(),
            ..RankLoad::default()
        }
    }
}

/// The process owning each element of `whole` on `processes` processes: the recursive
/// coordinate bisection of the element centroids. An interface belongs to the owner of its
/// first element.
pub fn element_owners(whole: &FractureModel, processes: usize) -> Vec<u32> {
    let centroids: Vec<Vector> = (whole.elements.iter())
        .map(|e| {
            let p = e.mesh_nodes.map(|n| whole.mesh.nodes[n as usize]);
            Vector::new(
                (p[0][0] + p[1][0] + p[2][0]) / 3.0,
                (p[0][1] + p[1][1] + p[2][1]) / 3.0,
            )
        })
        .collect();
    Bisection::new(&centroids, processes).assign(&centroids)
}

const ELEMENT_VALUES: usize = 1 + 6 + 6 + 6 + 36 + 4 + 4 + 1;
const INTERFACE_VALUES: usize = 1 + 2 * 8;

fn point_values(p: &PointState) -> [f64; 8] {
    [
        p.jump[0],
        p.jump[1],
        p.max_jump,
        p.intensity,
        p.impulse[0],
        p.impulse[1],
        p.adhesive_impulse[0],
        p.adhesive_impulse[1],
    ]
}

fn point_from(v: &[f64]) -> PointState {
    PointState {
        jump: [v[0], v[1]],
        max_jump: v[2],
        intensity: v[3],
        impulse: [v[4], v[5]],
        adhesive_impulse: [v[6], v[7]],
    }
}

/// Writes one process's message of [`DistributedFracture::gather`] into the whole model.
fn unpack(message: &[f64], whole: &mut FractureModel) {
    let Some((&count, rest)) = message.split_first() else {
        return;
    };
    let (elements, interfaces) = rest.split_at(count as usize * ELEMENT_VALUES);
    for v in elements.chunks_exact(ELEMENT_VALUES) {
        let el = &mut whole.elements[v[0] as usize];
        let take = |from: usize, out: &mut [f64]| out.copy_from_slice(&v[from..from + out.len()]);
        take(1, &mut el.displacement);
        take(7, &mut el.velocity);
        take(13, &mut el.internal_force);
        for (r, row) in el.stiffness.iter_mut().enumerate() {
            take(19 + 6 * r, row);
        }
        take(55, &mut el.state.stress);
        take(59, &mut el.state.plastic_strain);
        el.state.equivalent_plastic_strain = v[63];
    }
    for v in interfaces.chunks_exact(INTERFACE_VALUES) {
        let i = &mut whole.interfaces[v[0] as usize];
        i.points = [point_from(&v[1..9]), point_from(&v[9..17])];
    }
}

/// [`ContactSolve`] of fracture steps by NSCDD ([`solve_with_split_masses`]: the shared elements' masses split,
/// then restored bit for bit with their rows' Delassus blocks); sums by all-reduce.
struct SharedInterfaceNlgs<'c, C: Communicator + ?Sized> {
    comm: &'c C,
    interface: InterfaceMap,
}

impl<C: Communicator + ?Sized> ContactSolve<ElementContactOperator> for SharedInterfaceNlgs<'_, C> {
    fn solve(
        &mut self,
        op: &mut ElementContactOperator,
        mu: &[f64],
        shift: &[f64],
        cohesion: &[CohesiveTerm],
        impulses: &mut [[f64; 2]],
        params: &NlgsParams,
    ) -> Result<SolveInfo, SolveError> {
        solve_with_split_masses(
            self.comm,
            op,
            &self.interface,
            mu,
            shift,
            cohesion,
            impulses,
            params,
        )
    }

    fn sum(&mut self, values: &mut [f64]) {
        self.comm.all_reduce_sum(values);
    }

    fn max(&mut self, value: f64) -> f64 {
        let mut v = [value];
        self.comm.all_reduce_max(&mut v);
        v[0]
    }
}
