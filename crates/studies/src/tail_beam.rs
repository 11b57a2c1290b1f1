//! The tail beam: the scene's bodies, at its velocities, striking a box-section tail beam
//! (`[tail_beam]`), beside the paper's beam and Kirchhoff plate under the same impacts.
//!
//! Three forces bound what a lump feels on a tail beam:
//!
//! - **quasi-static**: the paper's energy balance (eqs. 14-20) with the whole structure's
//!   compliance at the struck point (walls, box, jacks). Valid for slow contacts, t_c/T₁ ≥ 0.2;
//! - **wave controlled**: Christoforou and Yigit's infinite-plate asymptote for the top plate,
//!   F̄_∞(ζ)·P_rigid ([`coupled::regimes::ChristoforouYigit`], the contact linearised to
//!   the spring that gives P_rigid): the contact is over before the
//!   flexural waves reach a support, so only the plate's impedance 8√(Dρh) matters. Olsson's
//!   mass criterion puts an impact here when the lump is light against the structure
//!   (M_i/M_p < 0.23);
//! - **rigid target**: the balance with C = 0 under the same contact law, an upper bound of
//!   both, and the unit of the other two (so that the law's restitution enters all alike).
//!
//! A lump on a tail beam is light against a box of hundreds of kilograms and its contact
//! lasts a fraction of a millisecond against a fundamental period set by the jacks: the
//! wave-controlled force is the answer, and the quasi-static one shows what the paper's
//! balance would say with the whole structure behind the point.

use crate::in_time::{InTime, OnMesh, IN_TIME_LEVEL};
use crate::settings::{BASE_MESH, LEVELS};
use crate::Failure;
use analytic::{respond, yield_velocity, DruckerPrager, Plate, PointCompliance};
use coupled::compliance::tail_beam::{contact_patch, TailBeamModel, TailBeamScene, TAIL_BEAM_LEVELS};
use coupled::compliance::{BeamModel, ComplianceModel, PlateModel};
use coupled::plan::{impact_of, transient_response};
use coupled::regimes::{ChristoforouYigit, OlssonRegime};
use coupled::transient::{law::Flores, ContactLaw, Striker};
use coupled::transient::{Discretisation, Ladder};
use coupled::validity::{self, Criterion, MINDLIN_PLATE_MAX_RATIO};
use coupled::SupportSet;
use plate_fem::shell::tail_beam::TailBeam;
use plate_fem::{EdgeSupport, Supports};
use scene::Scene;
use serde::Serialize;
use std::time::Instant;

/// One impact on the tail beam.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TailBeamRow {
    /// The body.
    pub body: String,
    /// Impact velocity, m/s.
    pub velocity: f64,
    /// The struck point along the beam, m.
    pub x: f64,
    /// The struck point across the beam, m.
    pub z: f64,
    /// The structure's compliance at the point (extrapolated), m/N.
    pub compliance: f64,
    /// Its error estimate, m/N.
    pub compliance_error: f64,
    /// The shares of the compliance stored in the walls' membrane, bending and shear, and in
    /// the jacks.
    pub shares: [f64; 4],
    /// P_max by the quasi-static balance with the whole compliance, N.
    pub p_quasi_static: f64,
    /// The jacks' force then, N (their sum).
    pub jack_force: f64,
    /// P_max in the wave-controlled limit, F̄_∞(ζ)·P_rigid, N.
    pub p_wave: f64,
    /// P_max on a rigid target under the same law (the balance with C = 0), N.
    pub p_rigid: f64,
    /// Hertz's contact time on a rigid target, s.
    pub contact_time: f64,
    /// Christoforou and Yigit's relative stiffness λ = k_α C with the whole compliance.
    pub lambda: f64,
    /// Their loss factor ζ of the top plate.
    pub zeta: f64,
    /// The lump's mass over the struck panel's (the top plate between the walls that hold
    /// the point; over a wall, the lighter of the two panels beside it): Olsson's M_i/M_p.
    pub mass_ratio: f64,
    /// Olsson's regime by it.
    pub regime: OlssonRegime,
    /// Whether the point lies over a wall (a web or a rib): the top plate is held there, and
    /// the infinite plate of the wave-controlled force is not what it strikes (the rigid
    /// target's force is the nearer bound).
    pub over_wall: bool,
    /// The yield velocity (eqs. 51-54) with the whole compliance, m/s.
    pub yield_velocity: f64,
    /// The yield velocity on a rigid target (C = 0), m/s.
    pub yield_velocity_rigid: f64,
    /// δ_max/δ_my of the quasi-static balance.
    pub elastic: Criterion,
    /// t_c/T₁ of the quasi-static balance.
    pub quasi_static: Criterion,
}

/// The paper's plate under the same impact: its beam and Kirchhoff plate at the plate's centre
/// under the scene's first support set.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PaperRow {
    /// The body.
    pub body: String,
    /// Impact velocity, m/s.
    pub velocity: f64,
    /// The support set.
    pub condition: String,
    /// P_max by the beam, N.
    pub beam: f64,
    /// P_max by the Kirchhoff plate, N.
    pub plate: f64,
}

/// The transient model (Kirchhoff plate, Newmark, the scene's contact law) on the top plate's
/// panel that holds the first struck point, under clamped and under simply supported edges:
/// where the impact is wave controlled the edges do not matter, and the force is the
/// wave-controlled one.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PanelCheck {
    /// The body.
    pub body: String,
    /// Impact velocity, m/s.
    pub velocity: f64,
    /// P_max with the panel's edges clamped, and its error estimate, N.
    pub clamped: (f64, Option<f64>),
    /// P_max with the panel's edges simply supported, and its error estimate, N.
    pub simple: (f64, Option<f64>),
    /// The wave-controlled P_max of the same impact at the first point, N.
    pub wave: Option<f64>,
}

/// The panel of the transient check: its width (m) and the point in its coordinates (m).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Panel {
    /// Length along x (the beam's length), m.
    pub length: f64,
    /// Width between its walls, m.
    pub width: f64,
    /// The struck point in the panel, (x, z), m.
    pub at: (f64, f64),
}

/// The transient check's relative tolerance on P_max and the contact time: its estimate is
/// reported beside each force.
pub const PANEL_TOLERANCE: f64 = 1e-3;

/// The study's data.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TailBeamData {
    /// The scene's tail beam.
    pub scene: TailBeamScene,
    /// The meshes: (elements along x, elements across z, unknowns, seconds).
    pub levels: Vec<(usize, usize, usize, f64)>,
    /// The finest element's side, m.
    pub finest_element: f64,
    /// The fundamental frequency, Hz, its change from the mesh before (relative) and the inverse
    /// iteration's last relative change (converged below 1e-10).
    pub frequency: (f64, f64, f64),
    /// The walls' mass, kg.
    pub mass: f64,
    /// The fundamental frequency of the box as a rigid body turning about the pins on its jacks,
    /// Hz ([`rigid_frequency`]): an upper bound of the shell model's.
    pub rigid_frequency: f64,
    /// The walls' largest thickness over the shortest span of their panel, against the
    /// Reissner-Mindlin range.
    pub thickness_range: Criterion,
    /// The finest element's side over the contact patch's.
    pub resolution: Criterion,
    /// One row per body, velocity and point.
    pub rows: Vec<TailBeamRow>,
    /// The paper's plate under the same impacts.
    pub paper: Vec<PaperRow>,
    /// The transient check's panel; None where the first point lies on a wall's line.
    pub panel: Option<Panel>,
    /// The transient check at the first point, per body and velocity.
    pub panel_checks: Vec<PanelCheck>,
    /// Seconds the shell model took.
    pub seconds: f64,
    /// The impacts on the box's own modes in time, one per row.
    pub in_time: InTime,
    /// The rigid box's answer to each impact's impulse J at x, the jacks' summed force
    /// Σk_j a_j·J x/(I ω_r), N ([`RigidTurning`]): the first mode's alone.
    pub jacks_rigid_box: Vec<f64>,
}

/// Runs the study on a scene with a `[tail_beam]`.
pub fn compute(scene: &Scene) -> Result<TailBeamData, Failure> {
    let tb = scene.tail_beam.as_ref().ok_or("the scene has no [tail_beam]")?;
    let material = scene.plate.material();
    let t = Instant::now();
    let model = TailBeamModel::compute(
        &tb.beam,
        (material.youngs_modulus(), material.poisson_ratio(), scene.plate.density()),
        &tb.points,
        tb.element,
        TAIL_BEAM_LEVELS,
    )?;
    let seconds = t.elapsed().as_secs_f64();
    let top = Plate::new(tb.beam.length, tb.beam.width, tb.beam.top, scene.plate.density(), material)?;
    let mut rows = Vec::new();
    for body in &scene.bodies {
        for &v in &scene.velocities {
            for &(x, z) in &tb.points {
                rows.push(row(scene, &model, &top, body, v, (x, z))?);
            }
        }
    }
    // The panel as a plate the transient model takes (its aspect ratio within a plate's);
    // otherwise no check, and the report says why.
    let on_panel = panel(tb).and_then(|p| {
        Plate::new(p.length, p.width, tb.beam.top, scene.plate.density(), material).ok().map(|plate| (p, plate))
    });
    let panel_checks = match &on_panel {
        Some((p, plate)) => panel_checks(scene, plate, *p, &rows)?,
        None => Vec::new(),
    };
    let panel = on_panel.map(|(p, _)| p);
    let (in_time, jacks_rigid_box) = in_time_of(scene, tb, &rows)?;
    Ok(TailBeamData {
        in_time,
        jacks_rigid_box,
        panel,
        panel_checks,
        scene: tb.clone(),
        levels: model.levels.iter().map(|l| (l.nx, l.nz, l.dofs, l.seconds)).collect(),
        finest_element: model.finest_element,
        frequency: (model.frequency, model.frequency_change, model.frequency_iteration),
        mass: model.mass,
        rigid_frequency: rigid_frequency(&tb.beam, scene.plate.density()),
        thickness_range: thickness_range(tb),
        resolution: Criterion::at_most("element/patch side", model.finest_element / tb.beam.top, 1.0),
        rows,
        paper: paper_rows(scene)?,
        seconds,
    })
}

/// The study's impacts on the box in time ([`crate::in_time`]) on the ladder's middle mesh and
/// the coarser, with the rigid box's answer for the jacks beside each.
fn in_time_of(scene: &Scene, tb: &TailBeamScene, rows: &[TailBeamRow]) -> Result<(InTime, Vec<f64>), Failure> {
    let started = Instant::now();
    let (m, rho) = (scene.plate.material(), scene.plate.density());
    let on = |level: u32| -> Result<_, Failure> {
        let built = tb.beam.build(m.youngs_modulus(), m.poisson_ratio(), tb.element, level)?;
        let loads = tb
            .points
            .iter()
            .map(|&(x, z)| built.structure.patch_load(built.top, &contact_patch(&tb.beam, x, z)))
            .collect::<Result<Vec<_>, _>>()?;
        let groups = built.jack_groups();
        Ok(OnMesh { structure: built.structure, restraints: built.restraints, loads, groups })
    };
    let (fine, coarse) =
        crate::in_time::models(&on(IN_TIME_LEVEL)?, &on(IN_TIME_LEVEL - 1)?, (rho, scene.signals.reduced().damping()))?;
    let impacts = rows
        .iter()
        .map(|r| {
            let point = tb.points.iter().position(|&p| p == (r.x, r.z)).ok_or("a row at an unknown point")?;
            Ok((r.body.clone(), r.velocity, point))
        })
        .collect::<Result<Vec<_>, Failure>>()?;
    let t = crate::in_time::compute(scene, fine, coarse, &impacts, started)?;
    let rigid = RigidTurning::of(&tb.beam, rho);
    let omega_r = (rigid.stiffness / rigid.inertia).sqrt();
    let jacks =
        t.rows.iter().zip(rows).map(|(r, q)| rigid.jacks_force * r.impulse * q.x / (rigid.inertia * omega_r)).collect();
    Ok((t, jacks))
}

/// One impact's three forces on a structure (module docs), with what they came from: the
/// impact's contact parameters, the quasi-static balance with the whole compliance, the rigid
/// target's force, Christoforou and Yigit's parameters for the struck wall, the impact as a
/// Hertz striker, and the lump's yield compression (eq. 51).
pub(crate) struct ThreeForces {
    pub imp: analytic::Impact,
    pub quasi_static: analytic::Response,
    pub p_rigid: f64,
    pub cy: ChristoforouYigit,
    pub striker: Striker,
    pub d_my: f64,
}

/// [`ThreeForces`] of `body` at `v` striking a structure of compliance `c` whose struck wall,
/// as an infinite plate, is `face`.
pub(crate) fn three_forces(
    scene: &Scene,
    body: &analytic::Sphere,
    v: f64,
    c: &PointCompliance,
    face: &Plate,
) -> Result<ThreeForces, Failure> {
    let imp = impact_of(scene, body, v);
    let quasi_static = respond(&imp, c, scene.solver)?;
    // The rigid target under the same law: the balance with C = 0. Every force below is
    // measured against it, so that the restitution of the paper's law (which lowers the peak
    // against Hertz's elastic one by e^0.6) enters all three alike.
    let p_rigid = respond(&imp, &PointCompliance::new(Vec::new(), Vec::new(), 0.0)?, scene.solver)?.contact_force;
    let cy = ChristoforouYigit::with_peak(face, imp.mass, v, p_rigid, c.total());
    let striker = Striker {
        k: imp.contact_stiffness,
        restitution: imp.restitution,
        mass: imp.mass,
        velocity: v,
        law: ContactLaw::Flores(Flores),
        gravity: 0.0,
    };
    let d_my = DruckerPrager::of(body).yield_compression(body.radius(), imp.contact_stiffness);
    Ok(ThreeForces { imp, quasi_static, p_rigid, cy, striker, d_my })
}

/// The share of the compliance `c` in the stores whose names start with `name` (0 where C = 0).
pub(crate) fn share(c: &PointCompliance, name: &str) -> f64 {
    let s: f64 = c.stores().iter().filter(|s| s.name.starts_with(name)).map(|s| s.compliance).sum();
    if c.total() > 0.0 {
        s / c.total()
    } else {
        0.0
    }
}

/// One impact of `body` at `v` on the tail beam at `at`.
fn row(
    scene: &Scene,
    model: &TailBeamModel,
    top: &Plate,
    body: &analytic::Sphere,
    v: f64,
    at: (f64, f64),
) -> Result<TailBeamRow, Failure> {
    let est = model.compliance(at.0, at.1)?;
    let c = est.compliance.total();
    let ThreeForces { imp, quasi_static: r, p_rigid, cy, striker, d_my } =
        three_forces(scene, body, v, &est.compliance, top)?;
    let share = |name: &str| share(&est.compliance, name);
    let jack_force = est.compliance.springs().iter().map(|s| s.per_unit_load).sum::<f64>() * r.contact_force;
    let (panel_width, over_wall) =
        panel_at(&scene.tail_beam.as_ref().ok_or("the scene has no [tail_beam]")?.beam, at.1);
    let ratio = body.mass() / (top.density() * top.thickness() * top.length() * panel_width);
    let t_c = striker.hertz_time();
    Ok(TailBeamRow {
        body: body.name.clone(),
        velocity: v,
        x: at.0,
        z: at.1,
        compliance: c,
        compliance_error: est.error_estimate,
        shares: [share("walls membrane"), share("walls bending"), share("walls shear"), share("jack")],
        p_quasi_static: r.contact_force,
        jack_force,
        p_wave: cy.infinite_plate_force() * p_rigid,
        p_rigid,
        contact_time: t_c,
        lambda: cy.relative_stiffness,
        zeta: cy.loss_factor,
        mass_ratio: ratio,
        regime: OlssonRegime::of(ratio),
        over_wall,
        yield_velocity: yield_velocity(body, &imp, c, d_my),
        yield_velocity_rigid: yield_velocity(body, &imp, 0.0, d_my),
        elastic: validity::elastic(r.compression, d_my),
        quasi_static: validity::quasi_static(t_c, 1.0 / model.frequency),
    })
}

/// The box as a rigid body turning about the pins' line on its jacks, f = √(k_θ/I)/2π (Hz):
/// k_θ = Σ k_j a_j² (a_j = y_pin cos θ_j + x_j sin θ_j, the jack's arm about the pins) and I the
/// walls' moment of inertia about the pins' line (thin plates on their mid-surfaces, density
/// `rho`). Rayleigh's quotient of the rigid mode: the shell model's f₁ lies below it, to within
/// about 0.2 % (the model spreads each jack over its pad's nodes, whose arms differ from the
/// pad centre's).
pub fn rigid_frequency(b: &TailBeam, rho: f64) -> f64 {
    let r = RigidTurning::of(b, rho);
    (r.stiffness / r.inertia).sqrt() / (2.0 * std::f64::consts::PI)
}

/// The box as a rigid body turning about the pins' line on its jacks (see [`rigid_frequency`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidTurning {
    /// k_θ = Σ k_j a_j², N m/rad.
    pub stiffness: f64,
    /// The walls' moment of inertia about the pins' line, kg m².
    pub inertia: f64,
    /// Σ k_j a_j, N/rad: the jacks' summed force per unit rotation.
    pub jacks_force: f64,
}

impl RigidTurning {
    /// The rigid box of `b` in steel of density `rho`.
    pub fn of(b: &TailBeam, rho: f64) -> Self {
        let (l, h, w, yp) = (b.length, b.height, b.width, b.pin_height);
        // ∫ (y - y_p)² dy / H over the depth: what a vertical wall adds per unit mass.
        let depth = h * h / 3.0 - h * yp + yp * yp;
        let long = l * l / 3.0;
        let flanges = rho * l * w * (b.top * (long + (h - yp).powi(2)) + b.bottom * (long + yp * yp));
        let walls = rho * l * h * (2.0 * b.webs + b.ribs.len() as f64 * b.rib) * (long + depth);
        let ends = rho * w * h * b.ends * (depth + (l * l + depth));
        // A diaphragm at x turns about the pins at x² + (y - y_p)² per unit mass.
        let diaphragms: f64 = b.diaphragm_walls().iter().map(|(x, t)| rho * w * h * t * (x * x + depth)).sum();
        let arm = |j: &plate_fem::shell::tail_beam::Jack| yp * j.angle.cos() + j.x * j.angle.sin();
        let stiffness: f64 = b.jacks.iter().map(|j| j.stiffness * arm(j).powi(2)).sum();
        // Each jack's force magnitude per unit rotation: jacks on both sides of the pins' line
        // push and pull, and the time model sums each one's peak magnitude.
        let jacks_force = b.jacks.iter().map(|j| j.stiffness * arm(j).abs()).sum();
        Self { stiffness, inertia: flanges + walls + ends + diaphragms, jacks_force }
    }
}

/// The walls' z positions, sorted: the webs and the ribs.
fn wall_lines(b: &TailBeam) -> Vec<f64> {
    let mut zs: Vec<f64> = [0.0, b.width].into_iter().chain(b.ribs.iter().copied()).collect();
    zs.sort_by(f64::total_cmp);
    zs
}

/// The width of the top plate's panel at `z` and whether `z` lies over a wall (within 1e-9 m;
/// there the narrower of the panels beside it).
fn panel_at(b: &TailBeam, z: f64) -> (f64, bool) {
    let walls = wall_lines(b);
    let widths = walls.windows(2).map(|w| (w[1] - w[0], w[0] - 1e-9 <= z && z <= w[1] + 1e-9));
    let beside: Vec<f64> = widths.filter(|(_, holds)| *holds).map(|(w, _)| w).collect();
    let on_wall = walls.iter().any(|w| (w - z).abs() <= 1e-9);
    (beside.into_iter().fold(f64::INFINITY, f64::min).min(b.width), on_wall)
}

/// The walls' largest t/(shortest span of the panel): the top and bottom plates between webs
/// and ribs and between diaphragms, the webs and ribs over the depth, the end plates and
/// diaphragms between webs and ribs and over the depth.
fn thickness_range(tb: &TailBeamScene) -> Criterion {
    let b = &tb.beam;
    let mut across: Vec<f64> = [0.0, b.length].into_iter().chain(b.diaphragm_walls().iter().map(|w| w.0)).collect();
    across.sort_by(f64::total_cmp);
    let bay = across.windows(2).map(|w| w[1] - w[0]).fold(b.length, f64::min);
    let panel = wall_lines(b).windows(2).map(|w| w[1] - w[0]).fold(bay, f64::min);
    let ratios = [
        b.top / panel,
        b.bottom / panel,
        b.webs / b.height.min(b.length),
        b.ends / b.height.min(panel),
        if b.ribs.is_empty() { 0.0 } else { b.rib / b.height.min(b.length) },
    ]
    .into_iter()
    .chain(b.diaphragm_walls().into_iter().map(|(_, t)| t / b.height.min(panel)));
    Criterion::at_most("t/(shortest panel span)", ratios.fold(0.0, f64::max), MINDLIN_PLATE_MAX_RATIO)
}

/// The beam's and the Kirchhoff plate's P_max at the centre of the scene's plate under its
/// first support set, for every body and velocity.
fn paper_rows(scene: &Scene) -> Result<Vec<PaperRow>, Failure> {
    let Some(set) = scene.conditions.first() else { return Ok(Vec::new()) };
    let centre = (scene.plate.length() / 2.0, scene.plate.width() / 2.0);
    let plate = PlateModel::compute(&scene.plate, std::slice::from_ref(set), &[centre], BASE_MESH, LEVELS)?;
    let beam = BeamModel { plate: &scene.plate };
    let (cb, cp) = (beam.compliance(set, centre.0, centre.1)?, plate.compliance(set, centre.0, centre.1)?);
    let mut out = Vec::new();
    for body in &scene.bodies {
        for &v in &scene.velocities {
            let imp = impact_of(scene, body, v);
            out.push(PaperRow {
                body: body.name.clone(),
                velocity: v,
                condition: set.name.clone(),
                beam: respond(&imp, &cb.compliance, scene.solver)?.contact_force,
                plate: respond(&imp, &cp.compliance, scene.solver)?.contact_force,
            });
        }
    }
    Ok(out)
}

/// The top plate's panel between walls (webs and ribs) that holds the first struck point
/// strictly inside; None where it lies on a wall's line or there is no point.
fn panel(tb: &TailBeamScene) -> Option<Panel> {
    let &(x, z) = tb.points.first()?;
    let b = &tb.beam;
    let walls = wall_lines(b);
    let w = walls.windows(2).find(|w| w[0] < z && z < w[1])?;
    (x > 0.0 && x < b.length).then_some(Panel { length: b.length, width: w[1] - w[0], at: (x, z - w[0]) })
}

/// The transient model on `panel` (the plate `plate`: the top plate's thickness and steel) under clamped
/// and simply supported edges, for every body and velocity, beside the wave-controlled force of
/// the same impact at the first point (from `rows`).
fn panel_checks(scene: &Scene, plate: &Plate, panel: Panel, rows: &[TailBeamRow]) -> Result<Vec<PanelCheck>, Failure> {
    let on_panel = Scene { plate: *plate, conditions: Vec::new(), ..scene.clone() };
    let disc = Discretisation::tolerance(PANEL_TOLERANCE);
    let ladder = Ladder::new(&on_panel.plate, disc.start())?;
    let edges = |e: EdgeSupport| SupportSet::new("panel", Supports { edges: [e; 4], ..Supports::all_edges_simple() });
    let (clamped, simple) = (edges(EdgeSupport::Clamped), edges(EdgeSupport::Simple));
    let first = scene.tail_beam.as_ref().and_then(|t| t.points.first().copied());
    let mut out = Vec::new();
    for body in &scene.bodies {
        for &v in &scene.velocities {
            let force = |set: &SupportSet| -> Result<(f64, Option<f64>), Failure> {
                let (values, _) = transient_response(&on_panel, disc, &ladder, set, body, panel.at, v)?;
                Ok((values.contact_force, values.contact_force_error))
            };
            let wave = rows
                .iter()
                .find(|r| r.body == body.name && r.velocity == v && Some((r.x, r.z)) == first)
                .map(|r| r.p_wave);
            out.push(PanelCheck {
                body: body.name.clone(),
                velocity: v,
                clamped: force(&clamped)?,
                simple: force(&simple)?,
                wave,
            });
        }
    }
    Ok(out)
}

/// The contact patch's side along x and z at `at` (m), for the report.
pub fn patch_sides(tb: &TailBeamScene, at: (f64, f64)) -> (f64, f64) {
    let p = contact_patch(&tb.beam, at.0, at.1);
    (p.side_z, p.side_x)
}
