//! Grasps: the contacts of a hand with a body, and their quality.

use graspkit_sys as sys;

use crate::error::{check, Result};
use crate::strings::read_string;
use crate::world::BodyRef;

/// Which grasp wrench space measures the grasp.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WrenchSpace {
    /// GraspIt!'s default: the hull of the contacts' unit wrenches.
    L1,
    /// The Minkowski sum of the contacts' wrench sets.
    LInfinity,
}

/// How a contact transmits force.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ContactModel {
    /// Normal force only.
    Frictionless,
    /// A Coulomb friction cone.
    Point,
    /// A friction cone and torsional friction (an elastic body).
    SoftFinger,
}

/// One contact, seen from the hand's link.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// The hand's solid.
    pub link: BodyRef,
    /// The other solid.
    pub body: BodyRef,
    /// On the link, world, mm.
    pub position: [f64; 3],
    /// Unit, into the link.
    pub normal: [f64; 3],
    /// Friction coefficient of the two materials.
    pub mu: f64,
    /// Soft fingers: GraspIt!'s e_tau (mm); 0 otherwise.
    pub torsion: f64,
    /// How it transmits force.
    pub model: ContactModel,
}

/// A grasp's measures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quality {
    /// -1 without force closure or when the hull failed.
    pub epsilon: f64,
    /// 0 when the hull failed.
    pub volume: f64,
    /// Whether the grasp resists any wrench.
    pub force_closure: bool,
}

/// An analysed grasp (freed when dropped). `Send`, not `Sync`, as every handle of the C ABI.
pub struct Grasp {
    pub(crate) raw: *mut sys::graspkit_grasp,
}

unsafe impl Send for Grasp {}

impl Drop for Grasp {
    fn drop(&mut self) {
        unsafe { sys::graspkit_grasp_free(self.raw) }
    }
}

impl Grasp {
    /// Epsilon, volume and force closure.
    pub fn quality(&self) -> Result<Quality> {
        let mut q = sys::graspkit_quality::default();
        check(unsafe { sys::graspkit_grasp_quality(self.raw, &mut q) })?;
        Ok(Quality {
            epsilon: q.epsilon,
            volume: q.volume,
            force_closure: q.force_closure != 0,
        })
    }

    /// The contacts with the object.
    pub fn contacts(&self) -> Result<Vec<Contact>> {
        let mut count = 0usize;
        check(unsafe { sys::graspkit_grasp_contact_count(self.raw, &mut count) })?;
        let mut raw = vec![sys::graspkit_contact::default(); count];
        let mut copied = 0usize;
        check(unsafe {
            sys::graspkit_grasp_contacts(self.raw, raw.as_mut_ptr(), raw.len(), &mut copied)
        })?;
        raw.truncate(copied);
        Ok(raw
            .iter()
            .map(|c| Contact {
                link: BodyRef::from_raw(c.link),
                body: BodyRef::from_raw(c.body),
                position: c.position,
                normal: c.normal,
                mu: c.mu,
                torsion: c.torsion,
                model: match c.model {
                    sys::GRASPKIT_CONTACT_FRICTIONLESS => ContactModel::Frictionless,
                    sys::GRASPKIT_CONTACT_SOFT_FINGER => ContactModel::SoftFinger,
                    _ => ContactModel::Point,
                },
            })
            .collect())
    }

    /// Why the wrench space could not be built; empty when it was.
    pub fn failure(&self) -> Result<String> {
        read_string(|b, c, l| unsafe { sys::graspkit_grasp_failure(self.raw, b, c, l) })
    }
}
