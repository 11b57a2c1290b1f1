//! Reproduction of the paper's section IV: Tables 2-12 beside the printed values, and the
//! curves of Figures 8-19, all from the beam model of `analytic`.
//!
//! Two numbers are reported for every printed response: the exact root of the energy
//! balance (converged to 1e-13), and the paper's own recursion stopped at ğ = 1e-6. The
//! paper does not state its ğ; the print matches the latter to its last digit, which
//! identifies it (see [`PAPER_RECURSION_TOLERANCE`]). The yield velocities of Table 2 do
//! not involve the recursion; they deviate through δ_my, which [`yield_inversion`] isolates.

use crate::output::Artifacts;
use crate::present::plot::{line_plot, Scale, Series};
use crate::present::table::{sig, Cell, Table};
use crate::scene::{even_points, Scene, SceneSource};
use analytic::{
    beam_compliance, contact_stiffness, evaluate, yield_velocity, Condition, DruckerPrager, Impact, Method, Plate,
    Response, Sphere,
};
use coupled::plan::{both_solvers, impact_of};
use std::fmt::Write as _;

use crate::report::Failure;

/// The stopping residual ğ of eq. 18 that reproduces the printed responses (Tables 3-12).
pub const PAPER_RECURSION_TOLERANCE: f64 = 1e-6;
/// Exact roots: far below every printed digit.
const CONVERGED: Method = Method::Bracketed { tolerance: 1e-13, max_iterations: 200 };
/// Deviations above this need an explanation (issue 2).
pub const EXPLAIN_ABOVE: f64 = 1e-5;
/// Velocities of section IV.
const V_TABLE3: f64 = 0.008;
const V_TABLE6: f64 = 0.0025;
/// Spring stiffnesses of Figs. 11-13 and the length study (section IV-B, IV-C).
const K_STUDY: [f64; 3] = [5e4, 2.50025e8, 5e8];
const K_LENGTH_STUDY: f64 = 5e6;
/// Lengths for Figs. 14-16 as multiples of L: the paper's lengths are only in the figure
/// images, not in the text, so we choose a spread around L.
const LENGTH_FACTORS: [f64; 4] = [0.8, 1.0, 1.2, 1.4];
/// Points of the sweeps: L in 100 parts (section IV-A).
const SWEEP: usize = 101;

/// The paper's setting: Table 1, with k_T = K_coal.
pub struct Paper {
    pub scene: Scene,
    pub coal: Sphere,
    pub gangue1: Sphere,
    pub gangue2: Sphere,
    pub k_t: f64,
}

/// How a response is solved.
#[derive(Clone, Copy, PartialEq)]
pub enum Solve {
    Converged,
    PaperRecursion,
}

impl Paper {
    pub fn new() -> Self {
        let scene = Scene::default_scene();
        let k_t = scene
            .conditions
            .iter()
            .find_map(|c| c.spring_stiffnesses().next())
            .expect("the default scene has a spring condition");
        let [coal, gangue1, gangue2]: [Sphere; 3] =
            scene.bodies.clone().try_into().expect("the default scene has coal, gangue 1, gangue 2");
        Self { scene, coal, gangue1, gangue2, k_t }
    }

    pub fn bodies(&self) -> [&Sphere; 3] {
        [&self.coal, &self.gangue1, &self.gangue2]
    }

    /// Con 1, 2 or 3 with spring stiffness `k_t`.
    pub fn condition(n: usize, k_t: f64) -> Condition {
        match n {
            1 => Condition::BothFixed,
            2 => Condition::BothSprings { k_t },
            _ => Condition::FixedAndSprings { k_t },
        }
    }

    fn impact(&self, plate: &Plate, body: &Sphere, v: f64) -> Impact {
        Impact { contact_stiffness: contact_stiffness(body, plate.material()), ..impact_of(&self.scene, body, v) }
    }

    /// Responses of `body` at x on `plate` under `cond`.
    pub fn respond(&self, plate: &Plate, body: &Sphere, cond: Condition, x: f64, v: f64, how: Solve) -> Response {
        let c = beam_compliance(plate, cond, x).expect("paper points lie on the plate");
        let imp = self.impact(plate, body, v);
        let bal = imp.balance(c.total());
        let sol = match how {
            Solve::Converged => bal.attempt(CONVERGED),
            Solve::PaperRecursion => {
                bal.attempt(Method::Recursion { tolerance: PAPER_RECURSION_TOLERANCE, max_iterations: 200 })
            }
        };
        evaluate(&imp, &c, sol)
    }

    /// δ_my of eq. 51 for `body`.
    pub fn yield_compression(&self, body: &Sphere) -> f64 {
        DruckerPrager::of(body).yield_compression(body.radius(), contact_stiffness(body, self.scene.plate.material()))
    }

    /// v_y of eqs. 52-54, with δ_my scaled by `scale` (1 for the paper's equations).
    pub fn yield_velocity_scaled(&self, plate: &Plate, body: &Sphere, cond: Condition, x: f64, scale: f64) -> f64 {
        let c = beam_compliance(plate, cond, x).expect("paper points lie on the plate").total();
        let imp = self.impact(plate, body, 1.0);
        yield_velocity(body, &imp, c, self.yield_compression(body) * scale)
    }

    pub fn yield_velocity(&self, body: &Sphere, cond: Condition, x: f64) -> f64 {
        self.yield_velocity_scaled(&self.scene.plate, body, cond, x, 1.0)
    }
}

impl Default for Paper {
    fn default() -> Self {
        Self::new()
    }
}

// ------------------------------------------------------------------ printed values

/// Table 2: x of Areas 1-7 (m).
pub const T2_X: [f64; 7] = [0.013752, 0.1146, 0.210864, 0.2292, 0.247536, 0.3438, 0.449232];
/// Table 2: (body index, condition, v_y of Areas 1-7 in m/s).
pub const T2: [(usize, usize, [&str; 7]); 6] = [
    (0, 1, ["0.00876323", "0.009710283", "0.010383947", "0.010403508", "0.010383947", "0.009710283", "0.008749759"]),
    (0, 2, ["0.00876592", "0.009711894", "0.01038516", "0.010404711", "0.01038516", "0.009711894", "0.008752507"]),
    (0, 3, ["0.008763232", "0.009710444", "0.010384457", "0.01040411", "0.01038465", "0.009711733", "0.008752506"]),
    (1, 1, ["0.002703202", "0.003414581", "0.003876427", "0.003889453", "0.003876427", "0.003414581", "0.002692325"]),
    (1, 2, ["0.00270537", "0.00341572", "0.003877236", "0.003890253", "0.003877236", "0.00341572", "0.002694546"]),
    (1, 3, ["0.002703204", "0.003414695", "0.003876767", "0.003889853", "0.003876896", "0.003415606", "0.002694545"]),
];

/// A quantity the paper prints, with the unit of its column.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Quantity {
    ContactForce,
    Compression,
    Deflection,
    RockTotal,
    RockStored,
    PlateRatio,
    SpringRatio,
    /// Force of the spring at index i of the response's spring list.
    SpringForce(usize),
}

impl Quantity {
    pub fn of(&self, r: &Response) -> f64 {
        match *self {
            Self::ContactForce => r.contact_force,
            Self::Compression => r.compression,
            Self::Deflection => r.deflection,
            Self::RockTotal => r.rock_total_ratio,
            Self::RockStored => r.rock_stored_ratio,
            Self::PlateRatio => r.plate_ratio,
            Self::SpringRatio => r.spring_ratio,
            Self::SpringForce(i) => r.spring_forces[i].force,
        }
    }
}

/// Table 3 (coal, v = 0.008 m/s): quantity, its column unit, and No.1-3 x Con 1-3.
pub const T3: [(Quantity, &str, f64, [[&str; 3]; 3]); 6] = [
    (
        Quantity::ContactForce,
        "Contact force (N)",
        1.0,
        [
            ["1.934765", "1.934031", "1.934765"],
            ["1.596266", "1.596071", "1.596168"],
            ["1.934765", "1.934031", "1.934031"],
        ],
    ),
    (
        Quantity::Compression,
        "Rock deformation (1e-6 m)",
        1e-6,
        [
            ["2.42752", "2.426906", "2.42752"],
            ["2.1354079", "2.135234", "2.135321"],
            ["2.42752", "2.426906", "2.426906"],
        ],
    ),
    (
        Quantity::Deflection,
        "Metal plate deflection (1e-7 m)",
        1e-7,
        [["0", "0", "0"], ["9.930872", "9.929656", "9.932702"], ["0", "0", "1.890195"]],
    ),
    (
        Quantity::RockTotal,
        "Rock total energy ratio",
        1.0,
        [["1", "0.999367", "1"], ["0.725764", "0.725615", "0.725689"], ["1", "0.999367", "0.999367"]],
    ),
    (
        Quantity::RockStored,
        "Rock absorbed energy ratio",
        1.0,
        [["0.65", "0.649589", "0.65"], ["0.471746", "0.47165", "0.471698"], ["0.65", "0.649589", "0.649589"]],
    ),
    (
        Quantity::PlateRatio,
        "Metal plate energy ratio",
        1.0,
        [["0", "0", "0"], ["0.2742364", "0.274169", "0.274203"], ["0", "0", "0"]],
    ),
];

/// Table 4 (coal, v = 0.008 m/s): spring forces (N) at Points 1-3.
pub const T4: [(&str, usize, usize, [&str; 3]); 3] = [
    ("Con 2 left spring", 2, 0, ["0.967015", "0.399018", "0"]),
    ("Con 2 right spring", 2, 1, ["0", "0.399018", "0.967015"]),
    ("Con 3 spring", 3, 0, ["0", "0.399003", "0.96692"]),
];

/// Columns of Tables 6-10 with their units.
pub const T6_COLUMNS: [(Quantity, &str, f64); 5] = [
    (Quantity::ContactForce, "Contact force (N)", 1.0),
    (Quantity::Compression, "Rock deformation (1e-7 m)", 1e-7),
    (Quantity::Deflection, "Metal plate deflection (1e-7 m)", 1e-7),
    (Quantity::RockTotal, "Rock total energy ratio", 1.0),
    (Quantity::PlateRatio, "Metal plate energy ratio", 1.0),
];

/// Tables 6, 7, 8 (Con 1, 2, 3; v = 0.0025 m/s at L/2): rows coal, gangue 1, gangue 2.
pub const T6_8: [(usize, [[&str; 5]; 3]); 3] = [
    (
        1,
        [
            ["0.42065148", "8.77725888", "2.61700466", "0.80498950", "0.19501103"],
            ["0.66265566", "3.57195473", "4.12258853", "0.51606256", "0.48393805"],
            ["0.91089265", "4.15261761", "5.66694865", "0.47420472", "0.52579516"],
        ],
    ),
    (
        2,
        [
            ["0.42061427", "8.77674131", "2.61677319", "0.80487084", "0.19497653"],
            ["0.66251790", "3.57145965", "4.12173146", "0.51588376", "0.48373685"],
            ["0.91068846", "4.15199701", "5.66567832", "0.47402757", "0.52555945"],
        ],
    ),
    (
        3,
        [
            ["0.42063287", "8.77700008", "2.61753126", "0.80493016", "0.19499379"],
            ["0.66258677", "3.57170715", "4.12317175", "0.51597315", "0.48383747"],
            ["0.91079054", "4.15230726", "5.66770423", "0.47411613", "0.52567732"],
        ],
    ),
];

/// Tables 9 and 10: coal minus gangue 1 (9) and gangue 2 (10), rows Con 1-3.
pub const T9_10: [(usize, [[&str; 5]; 3]); 2] = [
    (
        1,
        [
            ["-0.24200418", "5.20530415", "-1.50558387", "0.28892694", "-0.28892702"],
            ["-0.24190363", "5.20528166", "-1.50495827", "0.28898708", "-0.28876032"],
            ["-0.2419539", "5.20529293", "-1.50564049", "0.28895701", "-0.28884368"],
        ],
    ),
    (
        2,
        [
            ["-0.49024117", "4.62464127", "-3.04994399", "0.33078478", "-0.33078413"],
            ["-0.49007419", "4.6247443", "-3.04890513", "0.33084327", "-0.33058292"],
            ["-0.49015767", "4.62469282", "-3.05017297", "0.33081403", "-0.33068353"],
        ],
    ),
];

/// Columns of Table 11 (v = 0.0025 m/s at L/2): (label, condition, quantity).
pub const T11_COLUMNS: [(&str, usize, Quantity); 5] = [
    ("Con 2 left force (N)", 2, Quantity::SpringForce(0)),
    ("Con 2 right force (N)", 2, Quantity::SpringForce(1)),
    ("Con 2 spring energy ratio", 2, Quantity::SpringRatio),
    ("Con 3 spring force (N)", 3, Quantity::SpringForce(0)),
    ("Con 3 spring energy ratio", 3, Quantity::SpringRatio),
];
/// Table 11 rows: coal, gangue 1, gangue 2.
pub const T11: [[&str; 5]; 3] = [
    ["0.10515357", "0.10515357", "0.00015316", "0.10514789", "0.00007657"],
    ["0.16562947", "0.16562947", "0.00038000", "0.16563043", "0.00019000"],
    ["0.22767212", "0.22767212", "0.00041285", "0.22767528", "0.00020643"],
];
/// Table 12 columns: indices into Table 11's columns; rows coal - gangue 1, coal - gangue 2.
pub const T12_COLUMNS: [usize; 4] = [0, 2, 3, 4];
pub const T12: [[&str; 4]; 2] = [
    ["-0.0604759", "-0.00022684", "-0.06048254", "-0.00011343"],
    ["-0.12251855", "-0.00025969", "-0.12252739", "-0.00012986"],
];

// ------------------------------------------------------------------ comparison

/// A printed number: its value and half a unit of its last printed digit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Printed {
    pub value: f64,
    pub half_ulp: f64,
}

impl Printed {
    pub fn parse(text: &str) -> Self {
        let value: f64 = text.parse().expect("printed values are numbers");
        let decimals = text.split_once('.').map_or(0, |(_, d)| d.len()) as i32;
        Self { value, half_ulp: 0.5 * 10f64.powi(-decimals) }
    }
}

/// How a reproduced number stands against print.
#[derive(Debug, Clone, PartialEq)]
pub enum Verdict {
    /// Within half a unit of the last printed digit.
    WithinPrint,
    /// Beyond print rounding but within [`EXPLAIN_ABOVE`] relative.
    Close,
    /// Beyond 1e-5, with the reason.
    Explained(String),
    /// Beyond 1e-5 and not understood: a defect of this reproduction if it ever appears.
    Unexplained,
}

/// One printed number beside its reproductions (all in the printed units).
#[derive(Debug, Clone)]
pub struct Comparison {
    pub table: &'static str,
    pub case: String,
    pub quantity: String,
    pub printed: Printed,
    pub printed_text: String,
    /// The exact root of the balance.
    pub equations: f64,
    /// The paper's recursion at ğ = 1e-6, where the number comes from the balance.
    pub recursion: Option<f64>,
    /// Resolution of the column, used where the paper prints a bare 0.
    pub column_half_ulp: f64,
}

impl Comparison {
    /// The reproduction judged against print: the recursion where there is one.
    pub fn best(&self) -> f64 {
        self.recursion.unwrap_or(self.equations)
    }

    fn half_ulp(&self) -> f64 {
        if self.printed.value == 0.0 {
            self.column_half_ulp
        } else {
            self.printed.half_ulp
        }
    }

    /// Relative deviation of `ours` from print (absolute where print is 0).
    pub fn deviation(&self, ours: f64) -> f64 {
        if self.printed.value == 0.0 {
            ours.abs()
        } else {
            (ours - self.printed.value).abs() / self.printed.value.abs()
        }
    }

    pub fn verdict(&self, explain: &dyn Fn(&Comparison) -> Option<String>) -> Verdict {
        let ours = self.best();
        // 1e-12 absorbs the binary representation of the printed decimal.
        if (ours - self.printed.value).abs() <= self.half_ulp() * (1.0 + 1e-9) + 1e-12 * self.printed.value.abs() {
            Verdict::WithinPrint
        } else if self.deviation(ours) <= EXPLAIN_ABOVE {
            Verdict::Close
        } else {
            explain(self).map_or(Verdict::Unexplained, Verdict::Explained)
        }
    }
}

/// The paper's δ_my recovered from each printed v_y of Table 2, over eq. 51's δ_my.
///
/// v_y² m/2 = aδ^{5/2} + bδ³ is solved for δ with the beam compliance at the printed
/// point; a ratio that is the same for every point and condition of a body shows that
/// the compliances agree and the difference lies only in δ_my.
pub fn yield_inversion(paper: &Paper) -> Vec<(String, Vec<f64>)> {
    let mut out: Vec<(String, Vec<f64>)> = Vec::new();
    for &(b, cond, values) in T2.iter() {
        let body = paper.bodies()[b];
        let d_my = paper.yield_compression(body);
        for (i, text) in values.iter().enumerate() {
            let v = Printed::parse(text).value;
            let c = beam_compliance(&paper.scene.plate, Paper::condition(cond, paper.k_t), T2_X[i]).unwrap().total();
            let imp = paper.impact(&paper.scene.plate, body, v);
            let delta = imp.balance(c).attempt(CONVERGED).delta;
            match out.iter_mut().find(|(n, _)| n == &body.name) {
                Some((_, r)) => r.push(delta / d_my),
                None => out.push((body.name.clone(), vec![delta / d_my])),
            }
        }
    }
    out
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

/// Every printed number of Tables 2-4 and 6-12 beside its reproduction.
pub fn comparisons(paper: &Paper) -> Vec<Comparison> {
    let plate = paper.scene.plate;
    let l = plate.length();
    let mut out = Vec::new();
    let points = [0.0, l / 2.0, l];
    let cmp = |table, case: String, quantity: String, text: &str, scale: f64, eq: f64, rec: Option<f64>, col: f64| {
        Comparison {
            table,
            case,
            quantity,
            printed: Printed::parse(text),
            printed_text: text.to_string(),
            equations: eq / scale,
            recursion: rec.map(|r| r / scale),
            column_half_ulp: col,
        }
    };

    for &(b, cond, values) in T2.iter() {
        let body = paper.bodies()[b];
        for (i, text) in values.iter().enumerate() {
            let v = paper.yield_velocity(body, Paper::condition(cond, paper.k_t), T2_X[i]);
            let case = format!("{} Con {cond} Area {}", body.name, i + 1);
            out.push(cmp("Table 2", case, "v_y (m/s)".into(), text, 1.0, v, None, 0.0));
        }
    }

    let resp = |body: &Sphere, cond: usize, x: f64, v: f64, how| {
        paper.respond(&plate, body, Paper::condition(cond, paper.k_t), x, v, how)
    };
    for (q, label, scale, rows) in T3.iter() {
        // Finest printed resolution of the column, for cells printed as a bare 0.
        let col = rows.iter().flatten().map(|t| Printed::parse(t)).filter(|p| p.value != 0.0).map(|p| p.half_ulp);
        let col = col.fold(f64::INFINITY, f64::min);
        for (n, row) in rows.iter().enumerate() {
            for (ci, text) in row.iter().enumerate() {
                let (eq, rec) = (
                    resp(&paper.coal, ci + 1, points[n], V_TABLE3, Solve::Converged),
                    resp(&paper.coal, ci + 1, points[n], V_TABLE3, Solve::PaperRecursion),
                );
                let case = format!("No.{} Con {}", n + 1, ci + 1);
                out.push(cmp("Table 3", case, label.to_string(), text, *scale, q.of(&eq), Some(q.of(&rec)), col));
            }
        }
    }

    for (label, cond, idx, values) in T4.iter() {
        for (n, text) in values.iter().enumerate() {
            let q = Quantity::SpringForce(*idx);
            let eq = resp(&paper.coal, *cond, points[n], V_TABLE3, Solve::Converged);
            let rec = resp(&paper.coal, *cond, points[n], V_TABLE3, Solve::PaperRecursion);
            let case = format!("{label} Point {}", n + 1);
            out.push(cmp("Table 4", case, "spring force (N)".into(), text, 1.0, q.of(&eq), Some(q.of(&rec)), 5e-7));
        }
    }

    let mid = l / 2.0;
    let at_mid = |b: &Sphere, cond: usize, how| resp(b, cond, mid, V_TABLE6, how);
    for (t, (cond, rows)) in T6_8.iter().enumerate() {
        let table = ["Table 6", "Table 7", "Table 8"][t];
        for (b, row) in rows.iter().enumerate() {
            let body = paper.bodies()[b];
            let (eq, rec) = (at_mid(body, *cond, Solve::Converged), at_mid(body, *cond, Solve::PaperRecursion));
            for (ci, (q, label, scale)) in T6_COLUMNS.iter().enumerate() {
                out.push(cmp(
                    table,
                    body.name.clone(),
                    label.to_string(),
                    row[ci],
                    *scale,
                    q.of(&eq),
                    Some(q.of(&rec)),
                    5e-9,
                ));
            }
        }
    }

    for (t, (g, rows)) in T9_10.iter().enumerate() {
        let table = ["Table 9", "Table 10"][t];
        let gangue = paper.bodies()[*g];
        for (ci, row) in rows.iter().enumerate() {
            let cond = ci + 1;
            let d = |how| (at_mid(&paper.coal, cond, how), at_mid(gangue, cond, how));
            let ((ce, ge), (cr, gr)) = (d(Solve::Converged), d(Solve::PaperRecursion));
            for (qi, (q, label, scale)) in T6_COLUMNS.iter().enumerate() {
                let case = format!("coal - {} Con {cond}", gangue.name);
                let (eq, rec) = (q.of(&ce) - q.of(&ge), q.of(&cr) - q.of(&gr));
                out.push(cmp(table, case, label.to_string(), row[qi], *scale, eq, Some(rec), 5e-9));
            }
        }
    }

    let t11 = |body: &Sphere, col: usize, how| {
        let (_, cond, q) = T11_COLUMNS[col];
        q.of(&at_mid(body, cond, how))
    };
    for (b, row) in T11.iter().enumerate() {
        let body = paper.bodies()[b];
        for (ci, text) in row.iter().enumerate() {
            let (eq, rec) = (t11(body, ci, Solve::Converged), t11(body, ci, Solve::PaperRecursion));
            out.push(cmp("Table 11", body.name.clone(), T11_COLUMNS[ci].0.into(), text, 1.0, eq, Some(rec), 5e-9));
        }
    }
    for (gi, row) in T12.iter().enumerate() {
        let gangue = paper.bodies()[gi + 1];
        for (k, text) in row.iter().enumerate() {
            let col = T12_COLUMNS[k];
            let diff = |how| t11(&paper.coal, col, how) - t11(gangue, col, how);
            let case = format!("coal - {}", gangue.name);
            let (eq, rec) = (diff(Solve::Converged), diff(Solve::PaperRecursion));
            out.push(cmp("Table 12", case, T11_COLUMNS[col].0.into(), text, 1.0, eq, Some(rec), 5e-9));
        }
    }
    out
}

/// The explanation of a deviation above 1e-5, or None if we have none.
pub fn explain<'a>(paper: &'a Paper, inversion: &[(String, Vec<f64>)]) -> impl Fn(&Comparison) -> Option<String> + 'a {
    let ratios: Vec<(String, f64)> = inversion.iter().map(|(n, r)| (n.clone(), mean(r))).collect();
    move |c: &Comparison| {
        if c.table == "Table 2" {
            let (name, r) = ratios.iter().find(|(n, _)| c.case.starts_with(n.as_str()))?;
            let body = paper.bodies().into_iter().find(|b| &b.name == name)?;
            let cond: usize = c.case.split("Con ").nth(1)?.split(' ').next()?.parse().ok()?;
            let area: usize = c.case.rsplit(' ').next()?.parse().ok()?;
            let rescaled = paper.yield_velocity_scaled(
                &paper.scene.plate,
                body,
                Paper::condition(cond, paper.k_t),
                T2_X[area - 1],
                *r,
            );
            let dev = (rescaled - c.printed.value).abs() / c.printed.value;
            return Some(format!(
                "δ_my constant: with δ_my × {r:.7} ({name}, see below) the equations give {} ({dev:.1e} from print)",
                sig(rescaled, 9)
            ));
        }
        let ratio = c.printed.value / c.best();
        if (ratio / 100.0 - 1.0).abs() < 1e-5 {
            return Some(format!(
                "unit slip: the printed {} equals the equations' value in units of 1e-9 m, not the column's 1e-7 m (ratio {:.6})",
                c.printed_text, ratio
            ));
        }
        None
    }
}

/// The comparison tables, one per printed table, with a summary.
fn comparison_markdown(paper: &Paper, rows: &[Comparison], inversion: &[(String, Vec<f64>)]) -> (String, Table) {
    let explain = explain(paper, inversion);
    let mut md = String::new();
    let mut all = Table::new(
        "",
        &[
            "table",
            "case",
            "quantity",
            "printed",
            "equations (converged)",
            "rel. dev.",
            "recursion ğ=1e-6",
            "rel. dev.",
            "verdict",
        ],
    );
    let mut tables: Vec<&str> = rows.iter().map(|r| r.table).collect();
    tables.dedup();
    let mut counts = [0usize; 4];
    for t in tables {
        let mut tab = Table::new(
            "",
            &[
                "case",
                "quantity",
                "printed",
                "equations (converged)",
                "rel. dev.",
                "recursion ğ=1e-6",
                "rel. dev.",
                "verdict",
            ],
        );
        for r in rows.iter().filter(|r| r.table == t) {
            let verdict = r.verdict(&explain);
            let v = match &verdict {
                Verdict::WithinPrint => {
                    counts[0] += 1;
                    "within print rounding".to_string()
                }
                Verdict::Close => {
                    counts[1] += 1;
                    "≤ 1e-5".to_string()
                }
                Verdict::Explained(s) => {
                    counts[2] += 1;
                    s.clone()
                }
                Verdict::Unexplained => {
                    counts[3] += 1;
                    "UNEXPLAINED".to_string()
                }
            };
            let rec = r.recursion.map_or(Cell::Empty, Cell::Num);
            let rec_dev = r.recursion.map_or(Cell::Empty, |x| Cell::Num(r.deviation(x)));
            let row = vec![
                Cell::from(r.case.clone()),
                r.quantity.clone().into(),
                r.printed_text.clone().into(),
                Cell::Num(r.equations),
                Cell::Num(r.deviation(r.equations)),
                rec,
                rec_dev,
                v.into(),
            ];
            let mut full = vec![Cell::from(t)];
            full.extend(row.iter().cloned());
            all.push(full);
            tab.push(row);
        }
        let _ = writeln!(md, "\n### {t}\n\n{}", tab.to_markdown());
    }
    let summary = format!(
        "{} printed numbers compared: {} within print rounding, {} within 1e-5 relative, {} above 1e-5 and explained, {} unexplained.\n",
        rows.len(),
        counts[0],
        counts[1],
        counts[2],
        counts[3]
    );
    (format!("{summary}{md}"), all)
}

/// How well each ğ reproduces the printed responses (Tables 3, 4, 6-12): evidence for the
/// paper's stopping residual.
fn tolerance_evidence(paper: &Paper) -> Table {
    let mut t = Table::new(
        "",
        &[
            "ğ of eq. 18",
            "max |reproduced - printed| in half units of the last printed digit",
            "cells within print rounding",
            "cells",
        ],
    );
    let plate = paper.scene.plate;
    let mid = plate.length() / 2.0;
    for tol in [f64::NAN, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8] {
        // Tables 6-8 and 11 print 8 decimals, finer than Tables 3-4, so they identify ğ best.
        let mut worst: f64 = 0.0;
        let (mut ok, mut n) = (0usize, 0usize);
        let mut check = |ours: f64, text: &str, scale: f64| {
            let p = Printed::parse(text);
            let v = ours / scale;
            worst = worst.max((v - p.value).abs() / p.half_ulp);
            ok += usize::from((v - p.value).abs() <= p.half_ulp * (1.0 + 1e-9) + 1e-12 * p.value.abs());
            n += 1;
        };
        let solve = |body: &Sphere, cond: usize| {
            let c = beam_compliance(&plate, Paper::condition(cond, paper.k_t), mid).unwrap();
            let imp = paper.impact(&plate, body, V_TABLE6);
            let m = if tol.is_nan() { CONVERGED } else { Method::Recursion { tolerance: tol, max_iterations: 200 } };
            evaluate(&imp, &c, imp.balance(c.total()).attempt(m))
        };
        for (cond, rows) in T6_8.iter() {
            for (b, row) in rows.iter().enumerate() {
                let r = solve(paper.bodies()[b], *cond);
                for (ci, (q, _, scale)) in T6_COLUMNS.iter().enumerate() {
                    check(q.of(&r), row[ci], *scale);
                }
            }
        }
        for (b, row) in T11.iter().enumerate() {
            for (ci, text) in row.iter().enumerate() {
                let (_, cond, q) = T11_COLUMNS[ci];
                check(q.of(&solve(paper.bodies()[b], cond)), text, 1.0);
            }
        }
        let label = if tol.is_nan() { "converged (1e-13)".to_string() } else { format!("{tol:e}") };
        t.push(vec![label.into(), worst.into(), ok.into(), n.into()]);
    }
    t
}

// ------------------------------------------------------------------ figures

/// A figure panel: its file stem, title, axis label, series and scale.
struct Panel {
    stem: String,
    title: String,
    y_label: String,
    series: Vec<Series>,
    scale: Scale,
}

fn panel(stem: &str, title: &str, y_label: &str, series: Vec<Series>) -> Panel {
    Panel { stem: stem.into(), title: title.into(), y_label: y_label.into(), series, scale: Scale::Linear }
}

/// The 8 response panels of Figs. 10 and 13, and the 6 of Figs. 14 and 17.
const RESPONSE_PANELS: [(&str, &str, Quantity, f64); 8] = [
    ("contact-force", "Maximum contact force (N)", Quantity::ContactForce, 1.0),
    ("compression", "Maximum rock compression (µm)", Quantity::Compression, 1e-6),
    ("deflection", "Impact-point deflection (µm)", Quantity::Deflection, 1e-6),
    ("spring-force", "Spring force (N)", Quantity::SpringForce(0), 1.0),
    ("rock-total", "Rock total energy ratio", Quantity::RockTotal, 1.0),
    ("rock-stored", "Rock absorbed energy ratio", Quantity::RockStored, 1.0),
    ("plate-energy", "Plate energy ratio", Quantity::PlateRatio, 1.0),
    ("spring-energy", "Spring energy ratio", Quantity::SpringRatio, 1.0),
];

/// A curve setting: plate, body, condition, velocity, label.
struct Curve<'a> {
    plate: Plate,
    body: &'a Sphere,
    cond: Condition,
    v: f64,
    label: String,
}

fn sweep_responses(paper: &Paper, c: &Curve) -> Vec<(f64, Response)> {
    even_points(c.plate.length(), SWEEP)
        .into_iter()
        .map(|x| (x * 1e3, paper.respond(&c.plate, c.body, c.cond, x, c.v, Solve::Converged)))
        .collect()
}

/// Panels of the response quantities for a family of curves; spring panels list every
/// spring of every curve that has springs, and are left out when none has.
fn response_panels(paper: &Paper, fig: &str, what: &str, curves: &[Curve], which: &[usize]) -> Vec<Panel> {
    let data: Vec<Vec<(f64, Response)>> = curves.iter().map(|c| sweep_responses(paper, c)).collect();
    let mut panels = Vec::new();
    for (k, &i) in which.iter().enumerate() {
        let (stem, label, q, scale) = RESPONSE_PANELS[i];
        let mut series = Vec::new();
        for (c, d) in curves.iter().zip(&data) {
            match q {
                Quantity::SpringForce(_) => {
                    for (si, s) in d[0].1.spring_forces.iter().enumerate() {
                        let pts = d.iter().map(|(x, r)| (*x, r.spring_forces[si].force)).collect();
                        series.push(Series::new(format!("{} {}", c.label, s.name), pts));
                    }
                }
                Quantity::SpringRatio if c.cond.spring_stiffness().is_none() => {}
                _ => series.push(Series::new(c.label.clone(), d.iter().map(|(x, r)| (*x, q.of(r) / scale)).collect())),
            }
        }
        if series.is_empty() {
            continue;
        }
        let title = format!("Fig. {fig}({}) {what}", k + 1);
        panels.push(panel(&format!("fig{fig}-{}-{stem}", k + 1), &title, label, series));
    }
    panels
}

fn yield_panel(paper: &Paper, stem: &str, title: &str, curves: &[Curve]) -> Panel {
    let series = curves
        .iter()
        .map(|c| {
            let pts = even_points(c.plate.length(), SWEEP)
                .into_iter()
                .map(|x| (x * 1e3, paper.yield_velocity_scaled(&c.plate, c.body, c.cond, x, 1.0)))
                .collect();
            Series::new(c.label.clone(), pts)
        })
        .collect();
    panel(stem, title, "Yield velocity (m/s)", series)
}

fn figures(paper: &Paper) -> Vec<Panel> {
    let plate = paper.scene.plate;
    fn cons<'a>(body: &'a Sphere, v: f64, k_t: f64, plate: Plate, prefix: &str) -> Vec<Curve<'a>> {
        (1..=3)
            .map(|n| Curve { plate, body, cond: Paper::condition(n, k_t), v, label: format!("{prefix}Con {n}") })
            .collect()
    }
    let mut out = Vec::new();
    let coal = &paper.coal;
    out.push(yield_panel(
        paper,
        "fig08-yield-coal",
        "Fig. 8 Yield velocity of the coal sphere",
        &cons(coal, 1.0, paper.k_t, plate, ""),
    ));
    out.push(yield_panel(
        paper,
        "fig09-yield-gangue1",
        "Fig. 9 Yield velocity of gangue sphere 1",
        &cons(&paper.gangue1, 1.0, paper.k_t, plate, ""),
    ));
    let all8: Vec<usize> = (0..8).collect();
    out.extend(response_panels(paper, "10", "coal, v = 0.008 m/s", &cons(coal, V_TABLE3, paper.k_t, plate, ""), &all8));

    let k_curves = |n: usize| -> Vec<Curve> {
        K_STUDY
            .iter()
            .map(|&k| Curve {
                plate,
                body: coal,
                cond: Paper::condition(n, k),
                v: V_TABLE3,
                label: format!("k_T = {k:e}"),
            })
            .collect()
    };
    out.push(yield_panel(
        paper,
        "fig11-yield-con2-stiffness",
        "Fig. 11 Yield velocity, Con 2, three k_T",
        &k_curves(2),
    ));
    out.push(yield_panel(
        paper,
        "fig12-yield-con3-stiffness",
        "Fig. 12 Yield velocity, Con 3, three k_T",
        &k_curves(3),
    ));
    let mut k13 = Vec::new();
    for n in [2, 3] {
        for c in k_curves(n) {
            k13.push(Curve { label: format!("Con {n} {}", c.label), ..c });
        }
    }
    out.extend(response_panels(paper, "13", "coal, v = 0.008 m/s, three k_T", &k13, &all8));

    let mut lengths = Vec::new();
    for f in LENGTH_FACTORS {
        let p = plate.with_length(plate.length() * f).expect("positive length");
        lengths.extend(cons(coal, V_TABLE3, K_LENGTH_STUDY, p, &format!("L = {:.1} mm ", p.length() * 1e3)));
    }
    out.extend(response_panels(
        paper,
        "14",
        "coal, v = 0.008 m/s, k_T = 5e6 N/m, four lengths",
        &lengths,
        &[0, 1, 2, 4, 5, 6],
    ));
    let springs: Vec<Curve> = lengths.into_iter().filter(|c| c.cond.spring_stiffness().is_some()).collect();
    for (fig, i) in [("15", 3), ("16", 7)] {
        let mut p = response_panels(paper, fig, "coal, v = 0.008 m/s, k_T = 5e6 N/m, four lengths", &springs, &[i]);
        for q in &mut p {
            q.stem = q.stem.replacen(&format!("fig{fig}-1-"), &format!("fig{fig}-"), 1);
        }
        out.extend(p);
    }

    let mut bodies = Vec::new();
    for b in paper.bodies() {
        bodies.extend(cons(b, V_TABLE6, paper.k_t, plate, &format!("{} ", b.name)));
    }
    out.extend(response_panels(paper, "17", "three spheres, v = 0.0025 m/s", &bodies, &[1, 0, 2, 4, 5, 6]));
    let springs: Vec<Curve> = bodies.into_iter().filter(|c| c.cond.spring_stiffness().is_some()).collect();
    for (fig, i) in [("18", 3), ("19", 7)] {
        let mut p = response_panels(paper, fig, "three spheres, v = 0.0025 m/s", &springs, &[i]);
        for q in &mut p {
            q.stem = q.stem.replacen(&format!("fig{fig}-1-"), &format!("fig{fig}-"), 1);
        }
        out.extend(p);
    }
    // Spring forces and energies span decades when k_T changes (Fig. 13) or soft springs
    // take most of the energy; a log axis keeps every curve visible.
    for p in &mut out {
        if p.stem.starts_with("fig13") && (p.stem.ends_with("spring-energy") || p.stem.ends_with("deflection")) {
            p.scale = Scale::Log;
        }
    }
    out
}

// ------------------------------------------------------------------ Table 5 and solvers

/// Minimum yield velocity over the 101 points for every body and condition (Table 5,
/// whose values the text does not carry; section IV-D quotes the overall minimum).
fn table5(paper: &Paper) -> (Table, f64) {
    let mut t = Table::new("", &["body", "condition", "min v_y (m/s)", "at x (mm)"]);
    let mut overall = f64::INFINITY;
    for b in paper.bodies() {
        for n in 1..=3 {
            let (x, v) = even_points(paper.scene.plate.length(), SWEEP)
                .into_iter()
                .map(|x| (x, paper.yield_velocity(b, Paper::condition(n, paper.k_t), x)))
                .fold((0.0, f64::INFINITY), |a, p| if p.1 < a.1 { p } else { a });
            overall = overall.min(v);
            t.push(vec![b.name.clone().into(), format!("Con {n}").into(), v.into(), (x * 1e3).into()]);
        }
    }
    (t, overall)
}

/// The paper's recursion against the bracketed solver on stiff and extreme cases.
pub fn solver_study(paper: &Paper) -> Table {
    let plate = paper.scene.plate;
    let c_paper = beam_compliance(&plate, Condition::BothFixed, plate.length() / 2.0).unwrap().total();
    let mut t = Table::new(
        "",
        &[
            "C / C_paper",
            "v (m/s)",
            "E_sphere / E_plate",
            "recursion iterations",
            "recursion residual",
            "bracketed iterations",
            "bracketed residual",
            "rel. diff. in δ",
            "both converged",
        ],
    );
    let e_plate = plate.material().youngs_modulus();
    for factor in [0.0, 1e-3, 1.0, 1e3, 1e6] {
        for v in [1e-6, 1e-3, 1e-1, 10.0] {
            for ratio in [1e-3, 1e-2, 1.0, 1e3] {
                let m = analytic::Elastic::new(ratio * e_plate, 0.28).unwrap();
                let body =
                    Sphere::new("s", paper.coal.density(), paper.coal.radius(), m, paper.coal.strength()).unwrap();
                let imp = paper.impact(&plate, &body, v);
                let (r, b) = both_solvers(&imp, factor * c_paper);
                t.push(vec![
                    factor.into(),
                    v.into(),
                    ratio.into(),
                    r.iterations.into(),
                    r.residual.into(),
                    b.iterations.into(),
                    b.residual.into(),
                    ((r.delta - b.delta).abs() / b.delta).into(),
                    (if r.converged && b.converged { "yes" } else { "NO" }).into(),
                ]);
            }
        }
    }
    t
}

// ------------------------------------------------------------------ the report

/// Everything `impact paper` writes.
/// The reproduction as a report: the paper's own scene, whatever scene is given.
pub fn report(_scene: &Scene) -> Result<Artifacts, Failure> {
    reproduce()
}

/// Reproduces Tables 2-12 and Figs. 8-19 beside the printed values.
pub fn reproduce() -> Result<Artifacts, Failure> {
    let paper = Paper::new();
    let mut a = Artifacts::new();
    let rows = comparisons(&paper);
    let inversion = yield_inversion(&paper);
    let (cmp_md, cmp_all) = comparison_markdown(&paper, &rows, &inversion);
    a.add("comparison.csv", cmp_all.to_csv());

    let mut inv = Table::new("", &["body", "cells", "mean δ_my ratio", "min", "max"]);
    for (name, r) in &inversion {
        let (lo, hi) = r.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
        inv.push(vec![name.clone().into(), r.len().into(), mean(r).into(), lo.into(), hi.into()]);
    }
    let evidence = tolerance_evidence(&paper);
    let (t5, overall_min) = table5(&paper);
    a.add("table5.csv", t5.to_csv());
    let solvers = solver_study(&paper);
    a.add("solvers.csv", solvers.to_csv());

    let panels = figures(&paper);
    let mut fig_md = String::new();
    let mut last_fig = String::new();
    for p in &panels {
        let svg = line_plot(&p.title, "Impact position x (mm)", &p.y_label, &p.series, p.scale);
        a.add(format!("{}.svg", p.stem), svg);
        a.add(format!("{}.csv", p.stem), crate::present::plot::series_csv(&p.series));
        let fig = p.stem[..5].to_string();
        if fig != last_fig {
            let _ = writeln!(fig_md, "\n### Fig. {}\n", fig[3..].trim_start_matches('0'));
            last_fig = fig;
        }
        let _ = writeln!(fig_md, "![{}]({}.svg)", p.title, p.stem);
    }

    let coal_min = t5.rows.iter().filter(|r| r[0] == Cell::from("coal")).filter_map(|r| match r[2] {
        Cell::Num(v) => Some(v),
        _ => None,
    });
    let coal_min = coal_min.fold(f64::INFINITY, f64::min);
    let gangue_min = t5
        .rows
        .iter()
        .filter(|r| r[0] != Cell::from("coal"))
        .filter_map(|r| if let Cell::Num(v) = r[2] { Some(v) } else { None })
        .fold(f64::INFINITY, f64::min);
    let dev_0002683 = (overall_min - 0.002683) / 0.002683;

    let mut md = String::new();
    let _ = write!(
        md,
        r#"# The paper reproduced: Tables 2-12 and Figures 8-19 (beam model)

Generated by `impact paper` from the embedded default scene (the paper's Table 1). Every
number below comes from `crates/analytic`; nothing is tuned to print. Regenerate with
`cargo run --release -- report`.

## How to read the comparisons

Each printed number stands beside two reproductions:

- **equations (converged)**: the exact root of the energy balance
  ½mv² = (2K/5e)δ^{{5/2}} + ½CK²δ³ (eqs. 14, 25, 46), solved to a relative residual of 1e-13.
- **recursion ğ = 1e-6**: the paper's own recursion (eqs. 15-19) from δ = 0, stopped when the
  relative residual of eq. 18 falls to ğ = {tol:e}. The paper does not state its ğ. The
  table below shows that ğ = 1e-6 reproduces the printed responses to the last printed
  digit, while the converged root differs from print by up to ~5e-7: the small deviations of
  the converged values are the paper's truncated recursion, not a different model.

{evidence}
The verdict column judges the recursion value where there is one: *within print rounding*
(within half a unit of the last printed digit), *≤ 1e-5* (relative), or an explanation.
A bare printed 0 is judged against the finest resolution printed in its column.

{cmp_md}

### Notes on the tables

- **Table 3, No.3 Con 3, plate deflection**: printed 1.890195 in a column of 1e-7 m. Eq. 41 at
  x = L gives the cantilever tip deflection P L³/(2k_T L³ + 3EI) = {defl3:.6e} m, which is the
  printed digits in units of 1e-9 m. The table's unit is wrong for this cell, by a factor 100.
- **Table 3, No.3 Con 3, plate energy ratio**: printed 0. Eq. 44 gives the cantilever store
  W_X/E₀ = {wx3:.3e} at x = L; it is not zero, only small.
- Tables 3-4 print 6-7 digits, too few to identify ğ; a few of their cells differ from print by
  2e-7 to 8e-7 relative beyond print rounding with either reproduction. We have no cause for
  these; all are below the 1e-5 threshold.
- Tables 9, 10 and 12 are differences of the printed Tables 6-8 and 11 and inherit their
  recursion truncation; reproduced as differences of our values.
- **Con 3 is not self-consistent** (reproduced as printed): by Clapeyron the stores of a linear
  structure under P hold ½ P w, so the deflection per unit load should equal the total
  compliance. At x = L, eqs. 43-44 give C_T + C_X = {c3_stores:.6e} m/N while eq. 40 gives the
  cantilever tip deflection {c3_defl:.6e} m/N per unit load (ratio {c3_ratio:.6}). The energy
  balance uses the stores, the reported deflection uses eq. 41, as the paper does.

## Table 2: the yield velocities and δ_my

The printed yield velocities deviate from eqs. 51-54 by about 1e-3 (coal) and 1.5e-4
(gangue 1). Solving each printed v_y back for the compression it implies, with the beam
compliance of its own point and condition, gives the ratio of the paper's δ_my to eq. 51's:

{inv}
The ratio is the same for all 21 cells of a body to about 1e-7: the compliance terms of
eqs. 52-54 agree with the paper, and only the δ_my constant differs (by +0.084 % for coal,
-0.012 % for gangue 1). δ_my is not printed in the paper. No single rounding of α, ε₀, K,
π or √3 in eq. 51 reproduces both factors, so we keep eq. 51 as written (with the cohesion
ζ in k; design.md section 2) and report the factor rather than adopt it.

## Table 5: minimum yield velocities

Table 5's values are not in the text we have (the table is an image). Section IV-D states
that the minimum yield velocity of the three spheres is 0.002683 m/s, that coal's minimum
exceeds 0.0087 m/s, and that coal's is more than 3 times the gangue's. The equations give:

{t5}
- Overall minimum: {overall_min:.7} m/s against the quoted 0.002683 m/s ({dev_0002683:+.2e} relative;
  the δ_my factor of gangue 1 above accounts for -1.5e-4 of it, the quoted value's 4 digits
  for up to ±1.9e-4).
- Coal's minimum: {coal_min:.7} m/s (> 0.0087: {coal_ok}). Ratio of coal's minimum to the
  gangue's: {ratio:.3} (> 3: {ratio_ok}).

## Figures 8-19

Curves over the 101 points of section IV-A (L in 100 parts), from the converged balance.
Each panel's data is in the CSV of the same name. Figs. 14-16 (plate length) use
k_T = 5e6 N/m as section IV-C states; the lengths the paper used are only in its figure
images, so we show L × {factors:?}. Figs. 11-13 use k_T = {ks:?} N/m.
{fig_md}

## Solvers on stiff and extreme cases

The paper's recursion (ğ = 1e-12) beside the bracketed Newton solver (1e-14), for
compliances from 0 to 1e6 times the paper's (Con 1 at L/2, C_paper = {c_paper:e} m/N),
velocities from 1e-6 to 10 m/s and sphere-to-plate modulus ratios from 1e-3 to 1e3
(coal's density and radius). The recursion contracts by at least 5x per step (|g'| ≤ 1/5,
see `analytic::balance`), so it converges everywhere; Newton from the upper bracket end
takes fewer steps.

{solvers}
"#,
        tol = PAPER_RECURSION_TOLERANCE,
        evidence = evidence.to_markdown(),
        inv = inv.to_markdown(),
        t5 = t5.to_markdown(),
        coal_ok = coal_min > 0.0087,
        ratio = coal_min / gangue_min,
        ratio_ok = coal_min / gangue_min > 3.0,
        factors = LENGTH_FACTORS,
        ks = K_STUDY,
        c_paper = beam_compliance(&paper.scene.plate, Condition::BothFixed, paper.scene.plate.length() / 2.0)?.total(),
        solvers = solvers.to_markdown(),
        defl3 = paper
            .respond(
                &paper.scene.plate,
                &paper.coal,
                Paper::condition(3, paper.k_t),
                paper.scene.plate.length(),
                V_TABLE3,
                Solve::PaperRecursion
            )
            .deflection,
        c3_stores = {
            let c = beam_compliance(&paper.scene.plate, Paper::condition(3, paper.k_t), paper.scene.plate.length())?;
            c.total()
        },
        c3_defl = beam_compliance(&paper.scene.plate, Paper::condition(3, paper.k_t), paper.scene.plate.length())?
            .deflection_per_unit_load(),
        c3_ratio = {
            let c = beam_compliance(&paper.scene.plate, Paper::condition(3, paper.k_t), paper.scene.plate.length())?;
            c.total() / c.deflection_per_unit_load()
        },
        wx3 = paper
            .respond(
                &paper.scene.plate,
                &paper.coal,
                Paper::condition(3, paper.k_t),
                paper.scene.plate.length(),
                V_TABLE3,
                Solve::PaperRecursion
            )
            .plate_ratio,
    );
    a.add("index.md", md);
    Ok(a)
}
