//! What the transient loop strikes: the plate's Newmark state, or a rigid mass on a spring.
//!
//! The contact solve needs of the target only that its point displacement at the end of a
//! step be affine in the step-end force, w_p = ŵ_p + gP, with its velocity
//! ẇ_p = v̂_p + (2/Δt)gP (Newmark's average-acceleration rule for any linear structure).

use plate_fem::dynamics::{Newmark, PlateEnergy};

/// A linear structure stepped by Newmark's average-acceleration rule, loaded at one point.
pub trait Target {
    /// g: the point's step-end displacement per unit step-end force.
    fn point_flexibility(&self) -> f64;
    /// The step-end point displacement and velocity if no force acted in the step.
    fn predict(&mut self) -> (f64, f64);
    /// Ends the step with force `f` at the point.
    fn commit(&mut self, f: f64);
    /// Point displacement and velocity now.
    fn point_state(&self) -> (f64, f64);
    /// Kinetic, strain and spring energy now.
    fn energy(&self) -> PlateEnergy;
    /// Corner deflections now (zeros where the target has no corners).
    fn corner_displacements(&self) -> [f64; 4];
    /// The energy the target's own damping has taken so far, where it keeps count (J); 0
    /// for an undamped target and for one that does not count it.
    fn damping_loss(&self) -> f64 {
        0.0
    }
    /// An upper bound on |w_p| over all later motion free of force, if the target knows one
    /// (the transient loop's stopping rule then uses it when it is below the energy bound).
    fn free_reach(&self) -> Option<f64> {
        None
    }
}

impl Target for Newmark<'_> {
    fn point_flexibility(&self) -> f64 {
        Newmark::point_flexibility(self)
    }
    fn predict(&mut self) -> (f64, f64) {
        Newmark::predict(self)
    }
    fn commit(&mut self, f: f64) {
        Newmark::commit(self, f)
    }
    fn point_state(&self) -> (f64, f64) {
        Newmark::point_state(self)
    }
    fn energy(&self) -> PlateEnergy {
        Newmark::energy(self)
    }
    fn corner_displacements(&self) -> [f64; 4] {
        Newmark::corner_displacements(self)
    }
    fn damping_loss(&self) -> f64 {
        Newmark::damping_loss(self)
    }
}

/// A rigid mass on a linear spring (one degree of freedom), the simplest target with its own
/// vibration: with it the transient loop can be checked against an ODE solution of the
/// sphere-contact-mass system. Its static compliance is 1/k; its spring energy is reported as
/// strain energy.
#[derive(Debug, Clone, PartialEq)]
pub struct SpringMass {
    mass: f64,
    stiffness: f64,
    dt: f64,
    w: f64,
    v: f64,
    a: f64,
    w_hat: f64,
}

impl SpringMass {
    /// A mass `mass` (kg) at rest on a spring `stiffness` (N/m), stepped with `dt`.
    pub fn new(mass: f64, stiffness: f64, dt: f64) -> Self {
        Self { mass, stiffness, dt, w: 0.0, v: 0.0, a: 0.0, w_hat: 0.0 }
    }

    /// The static compliance 1/k, m/N.
    pub fn static_compliance(&self) -> f64 {
        1.0 / self.stiffness
    }

    fn effective(&self) -> f64 {
        self.stiffness + 4.0 * self.mass / (self.dt * self.dt)
    }
}

impl Target for SpringMass {
    fn point_flexibility(&self) -> f64 {
        1.0 / self.effective()
    }
    fn predict(&mut self) -> (f64, f64) {
        let (c0, c1) = (4.0 / (self.dt * self.dt), 4.0 / self.dt);
        self.w_hat = self.mass * (c0 * self.w + c1 * self.v + self.a) / self.effective();
        let vp = self.v + 0.5 * self.dt * (c0 * (self.w_hat - self.w) - c1 * self.v);
        (self.w_hat, vp)
    }
    fn commit(&mut self, f: f64) {
        let (c0, c1) = (4.0 / (self.dt * self.dt), 4.0 / self.dt);
        let w_new = self.w_hat + f / self.effective();
        let a_new = c0 * (w_new - self.w) - c1 * self.v - self.a;
        self.v += 0.5 * self.dt * (self.a + a_new);
        self.a = a_new;
        self.w = w_new;
    }
    fn point_state(&self) -> (f64, f64) {
        (self.w, self.v)
    }
    fn energy(&self) -> PlateEnergy {
        PlateEnergy {
            kinetic: 0.5 * self.mass * self.v * self.v,
            strain: 0.5 * self.stiffness * self.w * self.w,
            springs: 0.0,
        }
    }
    fn corner_displacements(&self) -> [f64; 4] {
        [0.0; 4]
    }
}
