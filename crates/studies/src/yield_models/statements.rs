//! The paper's statements about yield velocities, each tested under the three models on the
//! paper study's results, and the numbers the study's prose quotes.
//!
//! A statement rests on differences between cells; under the plate and transient models a
//! difference within the cells' error estimates (the plate's Richardson error carried to v_y,
//! the transient bracket plus its discretisation error) is "not resolved", never "no". The
//! beam is exact.

use super::paper::{Figure, Overall, Printed, Table2Cell, Table5Row};
use crate::verdict::Verdict;
use crate::Failure;
use serde::Serialize;

/// One statement of the paper and its verdict under each model (beam, plate, transient).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Statement {
    /// The statement, in words.
    pub text: String,
    /// Its verdict under the beam, the plate and the transient model.
    pub holds: [Verdict; 3],
    /// The numbers each verdict rests on.
    pub evidence: [Evidence; 3],
}

/// Where a body's centreline curve is lowest and highest, as fractions of L.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CurveExtremes {
    /// Body name.
    pub body: String,
    /// x/L of the minimum.
    pub min_at: f64,
    /// x/L of the maximum.
    pub max_at: f64,
}

/// The range of a body's v_y over Table 2, m/s.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ValueRange {
    /// Body name.
    pub body: String,
    /// Lowest v_y.
    pub lo: f64,
    /// Highest v_y.
    pub hi: f64,
}

/// The numbers one verdict rests on.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Evidence {
    /// Where each body's Con 1 centreline curve is lowest and highest.
    Extremes(Vec<CurveExtremes>),
    /// The smallest relative rise of v_y from Con 1 to Con 2, and the largest resolution of
    /// a pair of cells.
    Rise {
        /// min v_y(Con 2)/v_y(Con 1) - 1.
        smallest: f64,
        /// The largest sum of two cells' relative errors.
        resolution: f64,
    },
    /// In how many cells an order holds.
    Count {
        /// Cells where it holds.
        holds: usize,
        /// Cells tested.
        cells: usize,
        /// Cells where it is not resolved.
        open: usize,
    },
    /// The largest v_y(gangue 1)/v_y(coal) over Table 2.
    GangueOverCoal {
        /// The ratio.
        largest: f64,
    },
    /// Each body's v_y range over Table 2.
    Ranges(Vec<ValueRange>),
    /// Where the model's lowest v_y of all is.
    Located {
        /// Body name.
        body: String,
        /// Support set name.
        condition: String,
        /// x/L.
        x: f64,
        /// z/B.
        z: f64,
    },
    /// Coal's lowest v_y and its ratio to the gangues' lowest.
    Minimum {
        /// Coal's lowest v_y, m/s.
        coal: f64,
        /// Over the gangues' lowest.
        over_gangues: f64,
    },
}

/// The numbers the study's prose quotes, from Table 2 and the statements.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Coal at the midpoint (Area 4) under Con 1.
    pub coal_mid: Table2Cell,
    /// Gangue 1 there.
    pub gangue_mid: Table2Cell,
    /// (lowest, highest) over Table 2 of plate/beam - 1.
    pub plate_over_beam: (f64, f64),
    /// Of transient/beam - 1.
    pub transient_over_beam: (f64, f64),
    /// Of transient/plate - 1.
    pub transient_over_plate: (f64, f64),
    /// Of the transient bracket's width over v_y.
    pub bracket_width: (f64, f64),
    /// Of the plate's error estimate over v_y.
    pub plate_error: (f64, f64),
    /// Transient runs of Table 2's roots.
    pub table2_runs: usize,
    /// Cells whose transient v_y lies between the rigid-target value and the plate's.
    pub between: usize,
    /// Cells whose transient v_y exceeds the beam's.
    pub above_beam_cells: usize,
    /// Their areas, ascending, each once.
    pub above_beam_areas: Vec<usize>,
    /// The largest |relative difference| of the transient v_y between conditions at one point.
    pub condition_spread: f64,
    /// The resolution of a difference between two transient cells: both brackets and both
    /// discretisation error estimates.
    pub pair_resolution: f64,
    /// v_y of gangue 1 on a rigid target (eq. 14 with C = 0), m/s.
    pub rigid_gangue1: f64,
    /// Of gangue 2.
    pub rigid_gangue2: f64,
    /// Statements that hold, per model.
    pub held: [usize; 3],
    /// Statements not resolved, per model.
    pub unresolved: [usize; 3],
}

/// What the statements are tested on.
pub(super) struct Facts<'a> {
    pub table2: &'a [Table2Cell],
    /// The transient discretisation error estimate (relative), added to every transient cell.
    pub resolution: f64,
    pub length: f64,
    pub width: f64,
    pub figures: &'a [Figure],
    pub table5: &'a [Table5Row],
    pub overall: &'a [Overall; 3],
    /// The name of Con 1.
    pub first_condition: &'a str,
    /// Coal, gangue 1, gangue 2.
    pub bodies: [&'a str; 3],
    pub printed: &'a Printed,
}

/// The (min, max) of `values`.
fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)))
}

impl Facts<'_> {
    /// A Table 2 cell's v_y under model `m` and its relative resolution: the beam is exact,
    /// the plate carries the compliance error to v_y, the transient its root's bracket and
    /// the discretisation error estimate.
    fn cell(&self, m: usize, r: &Table2Cell) -> (f64, f64) {
        match m {
            0 => (r.beam, 0.0),
            1 => (r.plate, r.plate_error / r.plate),
            _ => (r.transient.velocity, r.transient.width / r.transient.velocity + self.resolution),
        }
    }

    fn find(&self, body: &str, cond: usize, area: usize) -> Option<&Table2Cell> {
        self.table2.iter().find(|r| r.body == body && r.condition == cond && r.area == area)
    }

    /// The three models' verdicts on the seven statements.
    pub fn statements(&self) -> Result<Vec<Statement>, Failure> {
        Ok(vec![
            self.ends_and_middle()?,
            self.springs_raise()?,
            self.condition_order()?,
            self.gangue_lower()?,
            self.orders_of_magnitude()?,
            self.lowest_of_all()?,
            self.section_4d()?,
        ])
    }

    /// The same test of every model: `test(m)` gives model m's verdict and evidence.
    fn each(
        text: impl Into<String>,
        mut test: impl FnMut(usize) -> Result<(Verdict, Evidence), Failure>,
    ) -> Result<Statement, Failure> {
        let (b, p, t) = (test(0)?, test(1)?, test(2)?);
        Ok(Statement { text: text.into(), holds: [b.0, p.0, t.0], evidence: [b.1, p.1, t.1] })
    }

    fn ends_and_middle(&self) -> Result<Statement, Failure> {
        let l = self.length;
        Self::each(
            "Con 1, centreline: v_y is lowest at the ends and highest at the midpoint (coal and gangue 1)",
            |m| {
                let mut holds = Verdict::Holds;
                let mut parts = Vec::new();
                for body in &self.bodies[..2] {
                    let curve = self
                        .figures
                        .iter()
                        .find(|f| f.body == *body)
                        .and_then(|f| f.curves.first())
                        .ok_or_else(|| format!("no curve {m} {body} 0"))?
                        .of(m);
                    let (min_x, _, max_x, _) = extremes(curve);
                    let here = !(0.05..=0.95).contains(&(min_x / l)) && (0.4..=0.6).contains(&(max_x / l));
                    holds = Verdict::all([holds, here.into()]);
                    parts.push(CurveExtremes { body: body.to_string(), min_at: min_x / l, max_at: max_x / l });
                }
                Ok((holds, Evidence::Extremes(parts)))
            },
        )
    }

    fn springs_raise(&self) -> Result<Statement, Failure> {
        Self::each("Elastic supports raise v_y: v_y(Con 2) > v_y(Con 1) at Areas 1-7", |m| {
            let (mut rise, mut res) = (f64::INFINITY, 0.0f64);
            let mut cells = Vec::new();
            for r1 in self.table2.iter().filter(|r| r.condition == 1) {
                let r2 = self.find(&r1.body, 2, r1.area).ok_or("Table 2 lacks a Con 2 cell")?;
                let ((v1, e1), (v2, e2)) = (self.cell(m, r1), self.cell(m, r2));
                let up = v2 / v1 - 1.0;
                cells.push(Verdict::compare(up, 0.0, e1 + e2, true));
                rise = rise.min(up);
                res = res.max(e1 + e2);
            }
            Ok((Verdict::all(cells), Evidence::Rise { smallest: rise, resolution: res }))
        })
    }

    fn condition_order(&self) -> Result<Statement, Failure> {
        Self::each("v_y(Con 2) ≥ v_y(Con 3) ≥ v_y(Con 1) at Areas 1-7 (coal and gangue 1)", |m| {
            let (mut n, mut open, mut total) = (0, 0, 0);
            let mut cells = Vec::new();
            for r1 in self.table2.iter().filter(|r| r.condition == 1) {
                let r2 = self.find(&r1.body, 2, r1.area).ok_or("Table 2 lacks a Con 2 cell")?;
                let r3 = self.find(&r1.body, 3, r1.area).ok_or("Table 2 lacks a Con 3 cell")?;
                let ((v1, e1), (v2, e2), (v3, e3)) = (self.cell(m, r1), self.cell(m, r2), self.cell(m, r3));
                // Each order on the relative scale of Con 1's value, to the two cells' resolution.
                let here = Verdict::all([
                    Verdict::compare(v2 / v1, v3 / v1, e2 + e3, false),
                    Verdict::compare(v3 / v1, 1.0, e3 + e1, false),
                ]);
                total += 1;
                match here {
                    Verdict::Holds => n += 1,
                    Verdict::NotResolved => open += 1,
                    _ => {}
                }
                cells.push(here);
            }
            Ok((Verdict::all(cells), Evidence::Count { holds: n, cells: total, open }))
        })
    }

    fn gangue_lower(&self) -> Result<Statement, Failure> {
        let [coal, gangue1, _] = self.bodies;
        Self::each("Gangue 1 yields at lower velocities than coal (every cell of Table 2)", |m| {
            let mut worst: f64 = 0.0;
            let mut cells = Vec::new();
            for rc in self.table2.iter().filter(|r| r.body == coal) {
                let rg = self.find(gangue1, rc.condition, rc.area).ok_or("Table 2 lacks a gangue 1 cell")?;
                let ((vg, eg), (vc, ec)) = (self.cell(m, rg), self.cell(m, rc));
                cells.push(Verdict::compare(1.0, vg / vc, eg + ec, true));
                worst = worst.max(vg / vc);
            }
            Ok((Verdict::all(cells), Evidence::GangueOverCoal { largest: worst }))
        })
    }

    fn orders_of_magnitude(&self) -> Result<Statement, Failure> {
        let [coal, gangue1, _] = self.bodies;
        let text =
            "v_y is of order 1e-2 m/s for coal and 1e-3 m/s for gangue 1 (within a factor √10, every cell of Table 2)";
        Self::each(text, |m| {
            let mut holds = Verdict::Holds;
            let mut parts = Vec::new();
            for (body, order) in [(coal, -2.0), (gangue1, -3.0)] {
                let vs: Vec<f64> = self.table2.iter().filter(|r| r.body == body).map(|r| self.cell(m, r).0).collect();
                let (lo, hi) = range(vs.iter().copied());
                let here = vs.iter().all(|v| (v.log10() - order).abs() <= 0.5);
                holds = Verdict::all([holds, here.into()]);
                parts.push(ValueRange { body: body.to_string(), lo, hi });
            }
            Ok((holds, Evidence::Ranges(parts)))
        })
    }

    /// The lowest v_y of `body` under Con 1, per model.
    fn con1_minimum(&self, body: &str, m: usize) -> Option<(f64, f64)> {
        self.table5
            .iter()
            .find(|r| r.body == body && r.condition == self.first_condition)
            .map(|r| (r.minima[m].velocity, r.minima[m].x))
    }

    fn lowest_of_all(&self) -> Result<Statement, Failure> {
        let [_, gangue1, gangue2] = self.bodies;
        let text = "Table 5: the lowest v_y of the three spheres is a gangue's, at an end (x = 0 or L), under Con 1";
        Self::each(text, |m| {
            let o = &self.overall[m];
            let v = o.at.velocity;
            // Con 1 attains the overall minimum (ties with Con 3's fixed end count) at an end,
            // and the body is a gangue.
            let con1 = [gangue1, gangue2]
                .iter()
                .filter_map(|g| self.con1_minimum(g, m))
                .find(|&(w, _)| w <= v * (1.0 + 1e-12));
            let at_end = con1.is_some_and(|(_, x1)| x1 == 0.0 || x1 == self.length);
            let holds = Verdict::from(o.body.starts_with("gangue") && at_end);
            let evidence = Evidence::Located {
                body: o.body.clone(),
                condition: o.condition.clone(),
                x: o.at.x / self.length,
                z: o.at.z / self.width,
            };
            Ok((holds, evidence))
        })
    }

    fn section_4d(&self) -> Result<Statement, Failure> {
        let quoted = self.printed;
        let [coal, gangue1, gangue2] = self.bodies;
        let coal_exceeds = quoted.coal_min_exceeds.value;
        let ratio_exceeds = quoted.coal_over_gangue_exceeds.value;
        let text = format!(
            "Section IV-D: coal's minimum v_y exceeds {} m/s and is more than {} times the gangues'",
            quoted.coal_min_exceeds.text, quoted.coal_over_gangue_exceeds.text
        );
        Self::each(text, |m| {
            // The largest relative resolution of the model over Table 2's cells.
            let res = self.table2.iter().map(|r| self.cell(m, r).1).fold(0.0, f64::max);
            let min_of = |name: &str| {
                self.table5
                    .iter()
                    .filter(|r| r.body == name)
                    .map(|r| r.minima[m].velocity)
                    .fold(f64::INFINITY, f64::min)
            };
            let coal = min_of(coal);
            let gangue = min_of(gangue1).min(min_of(gangue2));
            let holds = Verdict::all([
                Verdict::compare(coal / coal_exceeds, 1.0, res, true),
                Verdict::compare(coal / gangue / ratio_exceeds, 1.0, 2.0 * res, true),
            ]);
            Ok((holds, Evidence::Minimum { coal, over_gangues: coal / gangue }))
        })
    }

    /// The numbers the prose quotes; `rigid(body)` is a body's v_y on a rigid target.
    pub fn summary(&self, statements: &[Statement], rigid: impl Fn(&str) -> f64) -> Result<Summary, Failure> {
        let t2 = self.table2;
        let [coal, gangue1, gangue2] = self.bodies;
        let mid =
            |body: &str| self.find(body, 1, 4).cloned().ok_or_else(|| format!("Table 2 lacks {body} Con 1 Area 4"));
        let bracket_width = range(t2.iter().map(|r| r.transient.width / r.transient.velocity));
        let mut above_beam_areas: Vec<usize> =
            t2.iter().filter(|r| r.transient.velocity > r.beam).map(|r| r.area).collect();
        above_beam_areas.sort_unstable();
        above_beam_areas.dedup();
        // The transient v_y between conditions at one point, against its discretisation error.
        let mut condition_spread: f64 = 0.0;
        for r in t2 {
            if let Some(r1) = self.find(&r.body, 1, r.area) {
                condition_spread = condition_spread.max((r.transient.velocity / r1.transient.velocity - 1.0).abs());
            }
        }
        let count = |v: Verdict, m: usize| statements.iter().filter(|s| s.holds[m] == v).count();
        Ok(Summary {
            coal_mid: mid(coal)?,
            gangue_mid: mid(gangue1)?,
            plate_over_beam: range(t2.iter().map(|r| r.plate / r.beam - 1.0)),
            transient_over_beam: range(t2.iter().map(|r| r.transient.velocity / r.beam - 1.0)),
            transient_over_plate: range(t2.iter().map(|r| r.transient.velocity / r.plate - 1.0)),
            bracket_width,
            plate_error: range(t2.iter().map(|r| r.plate_error / r.plate)),
            table2_runs: t2.iter().map(|r| r.transient.runs).sum(),
            between: t2
                .iter()
                .filter(|r| r.transient.velocity > rigid(&r.body) && r.transient.velocity < r.plate)
                .count(),
            above_beam_cells: t2.iter().filter(|r| r.transient.velocity > r.beam).count(),
            above_beam_areas,
            condition_spread,
            // A difference between two cells is resolved beyond both cells' brackets and both
            // cells' discretisation error estimates.
            pair_resolution: 2.0 * (bracket_width.1 + self.resolution),
            rigid_gangue1: rigid(gangue1),
            rigid_gangue2: rigid(gangue2),
            held: [0, 1, 2].map(|m| count(Verdict::Holds, m)),
            unresolved: [0, 1, 2].map(|m| count(Verdict::NotResolved, m)),
        })
    }
}

/// The extremes (x_min, v_min, x_max, v_max) of a curve.
fn extremes(points: &[(f64, f64)]) -> (f64, f64, f64, f64) {
    let values: Vec<f64> = points.iter().map(|p| p.1).collect();
    match crate::verdict::extreme_indices(&values) {
        Some((lo, hi)) => (points[lo].0, points[lo].1, points[hi].0, points[hi].1),
        None => (f64::NAN, f64::INFINITY, f64::NAN, f64::NEG_INFINITY),
    }
}

#[cfg(test)]
mod tests {
    use super::super::paper::{Minimum, Quoted};
    use super::*;
    use coupled::yield_root::TransientYield;

    /// A symmetric curve whose mirror points differ by rounding names the first of each pair,
    /// whichever rounds lower; a real difference (1e-6) still decides.
    #[test]
    fn extremes_name_the_first_of_values_equal_to_rounding() {
        for eps in [1e-15, -1e-15] {
            let curve = [
                (0.0, 9.82e-3 * (1.0 + eps)),
                (0.1, 9.04e-3),
                (0.2, 9.5e-3),
                (0.3, 9.04e-3 * (1.0 + eps)),
                (0.4, 9.82e-3),
            ];
            let (min_x, _, max_x, _) = extremes(&curve);
            assert_eq!((min_x, max_x), (0.1, 0.0), "{eps}");
        }
        let (min_x, _, _, _) = extremes(&[(0.1, 9.04e-3), (0.3, 9.04e-3 * (1.0 - 1e-6))]);
        assert_eq!(min_x, 0.3);
    }

    /// A Table 2 cell whose three models give `v` (the transient bracket 1e-6 of it).
    fn cell(body: &str, condition: usize, area: usize, v: f64) -> Table2Cell {
        Table2Cell {
            body: body.into(),
            condition,
            area,
            x: 0.1 * area as f64,
            printed: v,
            beam: v,
            plate: v,
            plate_error: 1e-3 * v,
            transient: TransientYield {
                velocity: v,
                width: 1e-6 * v,
                runs: 7,
                reduced_runs: 5,
                yield_compression: 1e-5,
            },
        }
    }

    /// What the paper prints, as far as the statements read it.
    fn printed() -> Printed {
        Printed {
            areas: vec![0.1],
            table2: vec![],
            min_yield_velocity: 1e-3,
            coal_min_exceeds: Quoted { value: 1e-3, text: "0.001".into() },
            coal_over_gangue_exceeds: Quoted { value: 2.0, text: "2".into() },
        }
    }

    /// No overall minimum (the statements tested here do not read it).
    fn overall() -> [Overall; 3] {
        let none =
            Overall { body: String::new(), condition: String::new(), at: Minimum { velocity: 0.0, x: 0.0, z: 0.0 } };
        [none.clone(), none.clone(), none]
    }

    /// The facts of `table2` on a unit plate, with the transient discretisation error
    /// estimate `resolution`.
    fn facts<'a>(
        table2: &'a [Table2Cell],
        resolution: f64,
        printed: &'a Printed,
        overall: &'a [Overall; 3],
    ) -> Facts<'a> {
        Facts {
            table2,
            resolution,
            length: 1.0,
            width: 1.0,
            figures: &[],
            table5: &[],
            overall,
            first_condition: "Con 1",
            bodies: ["coal", "gangue 1", "gangue 2"],
            printed,
        }
    }

    /// Con 2 above Con 1 by 0.05 %: the exact beam says so, the plate (0.1 % error a cell)
    /// and the transient (0.1 % discretisation error a cell) cannot tell, and neither says no.
    #[test]
    fn a_rise_within_the_resolution_is_not_resolved() {
        let table2 = [cell("coal", 1, 1, 1e-2), cell("coal", 2, 1, 1.0005e-2)];
        let (printed, overall) = (printed(), overall());
        let facts = facts(&table2, 1e-3, &printed, &overall);
        let s = facts.springs_raise().unwrap();
        assert_eq!(s.holds, [Verdict::Holds, Verdict::NotResolved, Verdict::NotResolved]);
        let Evidence::Rise { smallest, resolution } = s.evidence[2] else { panic!("{:?}", s.evidence[2]) };
        assert!((smallest - 5e-4).abs() < 1e-12 && (resolution - 2.0 * (1e-3 + 1e-6)).abs() < 1e-12);
        // A rise beyond both cells' errors is resolved under every model.
        let table2 = [cell("coal", 1, 1, 1e-2), cell("coal", 2, 1, 1.01e-2)];
        let s = Facts { table2: &table2, ..facts }.springs_raise().unwrap();
        assert_eq!(s.holds, [Verdict::Holds; 3]);
    }

    /// The prose's rule and the statement it bears on: the page says the transient model
    /// "does not resolve the effect of the supports on v_y" where the largest spread of the
    /// transient v_y between conditions at one point is within the pair resolution (both
    /// cells' brackets and discretisation error estimates), and then the statement "elastic
    /// supports raise v_y" must read "not resolved" under the transient model, never "yes" or
    /// "no"; beyond it, the statement is decided by the sign of the rise.
    ///
    /// Hand-made cells (coal and gangue 1 at Area 4, Con 1 and Con 2) with one bracket width w
    /// and one discretisation error r, so that each pair's resolution equals the rule's
    /// 2(w + r) and the cases sit at half and at twice the threshold, far from its edge; the
    /// quasi-static values are left equal on both conditions, so only the transient moves.
    #[test]
    fn the_springs_statement_follows_the_prose_rule_on_both_sides() {
        let (w, r) = (1e-6, 1e-3);
        let (printed, overall) = (printed(), overall());
        for (times, expected) in
            [(0.5, Verdict::NotResolved), (-0.5, Verdict::NotResolved), (2.0, Verdict::Holds), (-2.0, Verdict::Fails)]
        {
            let rise = times * 2.0 * (w + r);
            let mut table2 = Vec::new();
            for (body, v) in [("coal", 1e-2), ("gangue 1", 2e-3)] {
                table2.push(cell(body, 1, 4, v));
                let mut up = cell(body, 2, 4, v);
                up.transient.velocity = v * (1.0 + rise);
                up.transient.width = w * up.transient.velocity;
                table2.push(up);
            }
            let facts = facts(&table2, r, &printed, &overall);
            let statement = facts.springs_raise().unwrap();
            let summary = facts.summary(std::slice::from_ref(&statement), |_| 1e-4).unwrap();
            let within = summary.condition_spread <= summary.pair_resolution;
            assert_eq!(
                within,
                times.abs() < 1.0,
                "{times}: {} vs {}",
                summary.condition_spread,
                summary.pair_resolution
            );
            assert_eq!(statement.holds[2], expected, "{times}: {:?}", statement.evidence[2]);
            assert_eq!(within, statement.holds[2] == Verdict::NotResolved, "{times}");
        }
    }
}
