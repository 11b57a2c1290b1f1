//! The reduced model checked in the run itself: the median impact (every variable at its
//! median, the first family) on the full Newmark model of the same mesh and step rule, its
//! P_max and first-contact time against the reduced model's, and its cost.

use super::FullModelCheck;
use crate::Failure;
use coupled::identification::Instrument;
use identify::{Held, Study};
use scene::{Scene, SupportSet};
use std::time::Instant;

/// The median impact of the first family on the full model of `set` and on `instrument`.
pub fn check(
    scene: &Scene,
    study: &Study,
    set: &SupportSet,
    instrument: &Instrument<'_>,
) -> Result<FullModelCheck, Failure> {
    let e = &study.ensemble;
    let reduced_settings = scene.signals.reduced();
    let all = Held { position: true, size: true, speed: true, material: true };
    let draw = e.draw(0, all).ok_or("the ensemble is empty")?;
    let name = &e.families[draw.family].name;
    let sphere = draw.sphere(name)?;
    let striker = coupled::transient::Striker {
        k: analytic::contact_stiffness(&sphere, scene.plate.material()),
        restitution: scene.restitution,
        mass: sphere.mass(),
        velocity: draw.velocity,
        law: scene.contact_law.law_for(&sphere),
        gravity: scene.gravity,
    };
    let reduced = instrument.impact(draw.clone(), name)?;
    let t = Instant::now();
    let props = coupled::discretisation::plate_properties(&scene.plate);
    let fe = plate_fem::Model::new(props, coupled::discretisation::mesh_for(&props, reduced_settings.elements)?)?;
    let full = crate::transient::first_contact(
        &fe,
        set.supports,
        &striker,
        draw.x,
        draw.z,
        reduced_settings.steps_per_contact,
    )?;
    let seconds = t.elapsed().as_secs_f64();
    let full_force = full.force_max_interpolated.max(full.force_max);
    let contact_time_difference = match (reduced.contact_time, full.contact_time) {
        (Some(a), Some(b)) if b > 0.0 => a / b - 1.0,
        _ => 0.0,
    };
    Ok(FullModelCheck {
        seconds,
        force_max: full_force,
        force_difference: reduced.force_max / full_force - 1.0,
        contact_time_difference,
    })
}
