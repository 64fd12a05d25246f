//! A part of a model for one process of a distributed run: the elements it owns, copies
//! (shadows) of the other processes' elements its interfaces touch, and the interfaces it
//! owns. Stepped with a domain-decomposition [`xper_solver::ContactSolve`], the parts together
//! make the step of the whole model (Perales et al., EJCM 19, 2010: elements are bodies, so
//! the non-smooth contact domain decomposition of rigid bodies applies unchanged).

use crate::model::{FractureEnergy, FractureModel};

impl FractureModel {
    /// The part made of `elements` (indices into `self.elements`, increasing), of which those
    /// flagged in `shadow` are copies, and of `interfaces` (indices into `self.interfaces`,
    /// increasing), whose two elements must be among `elements`. The part starts with the
    /// energy accumulators `energy` (the whole budget on one process, zero on the others, so
    /// that the parts' sums are the whole model's); `cell_copy` as
    /// [`FractureModel::cell_copy`] (true on every process but one).
    ///
    /// # Panics
    /// If an interface joins an element not in `elements` (a caller's bug).
    pub fn part(
        &self,
        elements: &[u32],
        shadow: &[bool],
        interfaces: &[u32],
        energy: FractureEnergy,
        cell_copy: bool,
    ) -> FractureModel {
        let local = |global: u32| -> u32 {
            elements
                .binary_search(&global)
                .expect("an interface of the part joins an element outside it") as u32
        };
        let mut part_interfaces: Vec<_> = interfaces
            .iter()
            .map(|&i| self.interfaces[i as usize].clone())
            .collect();
        for i in &mut part_interfaces {
            i.elements = i.elements.map(local);
        }
        FractureModel {
            mesh: self.mesh.clone(),
            spec: self.spec.clone(),
            elements: (elements.iter())
                .map(|&e| self.elements[e as usize].clone())
                .collect(),
            interfaces: part_interfaces,
            laws: self.laws.clone(),
            time: self.time,
            step: self.step,
            energy,
            shadow: shadow.to_vec(),
            cell: self.cell,
            cell_copy,
        }
    }
}
