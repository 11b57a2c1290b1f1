//! The tail-beam study (`studies::tail_beam::compute`): one row per body, velocity and struck
//! point with the columns of `tail-beam/impacts.csv` and the structure's, and the whole study
//! as JSON text for the Python layer to parse.

use crate::columns::Table;
use crate::errors::{argument_message, model_error};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use studies::tail_beam::TailBeamData;

/// The scene's impacts on its `[tail_beam]`.
#[pyfunction]
pub fn tail_beam<'py>(py: Python<'py>, scene: &crate::scene::Scene) -> PyResult<Bound<'py, PyDict>> {
    let s = &scene.scene;
    if s.tail_beam.is_none() {
        return Err(argument_message(
            "scene",
            "has no [tail_beam] table (and \"tail-beam\" among its analyses); see docs/scenes.md".into(),
        ));
    }
    let data = py.detach(|| studies::tail_beam::compute(s).map_err(|e| e.to_string())).map_err(model_error)?;
    let out = PyDict::new(py);
    out.set_item("results", serde_json::to_string(&data).map_err(model_error)?)?;
    out.set_item("rows", rows(&data).into_py(py)?)?;
    Ok(out)
}

/// One row per impact, keyed as the report's CSV keys them (SI, unit in the name).
fn rows(d: &TailBeamData) -> Table {
    let mut t = Table::new(d.rows.len(), &[]);
    for (i, r) in d.rows.iter().enumerate() {
        t.text("body", i, &r.body);
        t.num("v_m_per_s", i, r.velocity);
        t.num("x_m", i, r.x);
        t.num("z_m", i, r.z);
        t.num("C_m_per_N", i, r.compliance);
        t.num("C_error_m_per_N", i, r.compliance_error);
        for (k, name) in ["membrane_share", "bending_share", "shear_share", "jacks_share"].into_iter().enumerate() {
            t.num(name, i, r.shares[k]);
        }
        t.num("P_max_wave_controlled_N", i, r.p_wave);
        t.num("P_max_quasi_static_N", i, r.p_quasi_static);
        t.num("P_max_rigid_target_N", i, r.p_rigid);
        t.num("jacks_force_N", i, r.jack_force);
        t.num("t_c_s", i, r.contact_time);
        t.num("t_c_per_T_1", i, r.quasi_static.value);
        t.num("M_i_per_M_p", i, r.mass_ratio);
        t.num("lambda", i, r.lambda);
        t.num("zeta", i, r.zeta);
        let regime = if r.over_wall { format!("{}, over a wall", r.regime.key()) } else { r.regime.key().into() };
        t.text("regime", i, &regime);
        t.flag("over_wall", i, r.over_wall);
        t.num("delta_max_per_delta_my", i, r.elastic.value);
        t.num("v_y_m_per_s", i, r.yield_velocity);
        t.num("v_y_rigid_m_per_s", i, r.yield_velocity_rigid);
    }
    // The box in time, one row per impact in the same order.
    for (i, (r, rigid_box)) in d.in_time.rows.iter().zip(&d.jacks_rigid_box).enumerate() {
        t.num("P_max_in_time_N", i, r.p_max);
        t.num("P_max_in_time_error_N", i, r.p_max_error);
        t.num("truncation_rel", i, r.truncation);
        t.num("mesh_rel", i, r.mesh);
        if let Some(t_c) = r.contact_time {
            t.num("t_c_in_time_s", i, t_c);
        }
        t.count("contacts_in_time", i, r.contacts as u64);
        t.num("jacks_force_in_time_N", i, r.spring_force);
        t.num("jacks_force_in_time_error_N", i, r.spring_force_error);
        t.num("jacks_force_rigid_box_N", i, *rigid_box);
    }
    t
}
