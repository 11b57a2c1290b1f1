//! The analog filters of a measurement chain, realised on samples at rate f_s by the bilinear
//! transform with prewarping (Oppenheim & Schafer, *Discrete-Time Signal Processing*, 3rd ed.,
//! section 7.2.2).
//!
//! An analog section H_a(s) becomes H(z) = H_a(κ (1 - z⁻¹)/(1 + z⁻¹)) with
//! κ = ω₀ / tan(ω₀/(2f_s)), ω₀ the section's own corner or resonance. The digital response at
//! frequency f is then *exactly* the analog one at the warped frequency
//!
//! Ω(f) = κ tan(πf/f_s),                                                          (bilinear map)
//!
//! so the two agree at ω₀ and at DC, and differ elsewhere by the warp Ω(f)/(2πf) - 1, which is
//! ((πf)² - (πf₀)²)/(3f_s²) to leading order: a section prewarped near DC is within 3 % at
//! f_s/10, but a resonance high in the band is realised with its frequency exact and its
//! bandwidth and its low-frequency flank compressed (at f₀ = 0.3 f_s about half the analog
//! bandwidth). The chain therefore reports the largest deviation of its digital response
//! from the analog one over the ADC's band ([`Cascade::largest_deviation`]). Each section is a second-order section
//! (biquad) run in direct form II transposed, the form with the smallest round-off for
//! floating point (Oppenheim & Schafer, section 6.5).

use rustfft::num_complex::Complex;
use serde::Serialize;
use std::f64::consts::PI;

/// An analog section H_a(s) = (n₂s² + n₁s + n₀)/(d₂s² + d₁s + d₀) and the angular frequency
/// ω₀ (rad/s) at which its digital image is made exact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Analog {
    /// Numerator coefficients n₂, n₁, n₀.
    pub numerator: [f64; 3],
    /// Denominator coefficients d₂, d₁, d₀.
    pub denominator: [f64; 3],
    /// The prewarping frequency ω₀, rad/s.
    pub omega0: f64,
}

impl Analog {
    /// H_a(jΩ), the analog response at angular frequency Ω.
    pub fn response(&self, omega: f64) -> Complex<f64> {
        let s = Complex::new(0.0, omega);
        let poly = |c: &[f64; 3]| s * s * c[0] + s * c[1] + c[2];
        poly(&self.numerator) / poly(&self.denominator)
    }

    /// The slowest decay rate of its poles, -max Re(s) over the roots of d₂s² + d₁s + d₀,
    /// 1/s: how fast what it holds of its past input fades.
    pub fn decay_rate(&self) -> f64 {
        let [d2, d1, d0] = self.denominator;
        if d2 == 0.0 {
            return d0 / d1;
        }
        let disc = d1 * d1 - 4.0 * d2 * d0;
        if disc < 0.0 {
            d1 / (2.0 * d2)
        } else {
            (d1 - disc.sqrt()) / (2.0 * d2)
        }
    }

    /// The second-order low-pass resonance ω_r²/(s² + 2ζω_r s + ω_r²): a sensor's mounted
    /// resonance (flat below it, a peak of 1/(2ζ) at it, falling as (ω_r/Ω)² above).
    pub fn resonance(omega_r: f64, zeta: f64) -> Self {
        let w2 = omega_r * omega_r;
        Self { numerator: [0.0, 0.0, w2], denominator: [1.0, 2.0 * zeta * omega_r, w2], omega0: omega_r }
    }

    /// The first-order high-pass s/(s + ω_h): a sensor's AC coupling (an IEPE or charge
    /// amplifier's discharge time constant 1/ω_h).
    pub fn high_pass(omega_h: f64) -> Self {
        Self { numerator: [0.0, 1.0, 0.0], denominator: [0.0, 1.0, omega_h], omega0: omega_h }
    }

    /// The sections of the Butterworth low-pass of `order` and corner ω_c:
    /// abs(H_a(jΩ))² = 1/(1 + (Ω/ω_c)^(2n)), from the poles ω_c e^{jπ(2k+n+1)/(2n)}, k = 0..n-1
    /// (Oppenheim & Schafer, eq. 7.26): ω_c²/(s² + 2 sin θ_k ω_c s + ω_c²) with
    /// θ_k = π(2k+1)/(2n) for each conjugate pair, and ω_c/(s + ω_c) for the real pole of an
    /// odd order.
    pub fn butterworth(order: usize, omega_c: f64) -> Vec<Self> {
        let w2 = omega_c * omega_c;
        let mut out: Vec<Self> = (0..order / 2)
            .map(|k| {
                let theta = PI * (2 * k + 1) as f64 / (2 * order) as f64;
                Self { numerator: [0.0, 0.0, w2], denominator: [1.0, 2.0 * theta.sin() * omega_c, w2], omega0: omega_c }
            })
            .collect();
        if order % 2 == 1 {
            out.push(Self { numerator: [0.0, 0.0, omega_c], denominator: [0.0, 1.0, omega_c], omega0: omega_c });
        }
        out
    }
}

/// A digital second-order section (b₀ + b₁z⁻¹ + b₂z⁻²)/(1 + a₁z⁻¹ + a₂z⁻²).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Biquad {
    /// b₀, b₁, b₂.
    pub b: [f64; 3],
    /// a₁, a₂.
    pub a: [f64; 2],
}

impl Biquad {
    /// The bilinear image of `analog` at sample rate `rate_hz`, prewarped at its ω₀ (module
    /// docs); ω₀ must lie below the Nyquist frequency πf_s.
    pub fn bilinear(analog: &Analog, rate_hz: f64) -> Self {
        let kappa = analog.omega0 / (analog.omega0 / (2.0 * rate_hz)).tan();
        // s = κ(1 - z⁻¹)/(1 + z⁻¹): multiply through by (1 + z⁻¹)², so
        // c₂s² + c₁s + c₀ → c₂κ²(1 - z⁻¹)² + c₁κ(1 - z⁻¹)(1 + z⁻¹) + c₀(1 + z⁻¹)².
        let map = |c: &[f64; 3]| {
            let (p, q, r) = (c[0] * kappa * kappa, c[1] * kappa, c[2]);
            [p + q + r, 2.0 * (r - p), p - q + r]
        };
        if analog.numerator[0] == 0.0 && analog.denominator[0] == 0.0 {
            // A first-order section: multiplied through by (1 + z⁻¹) alone, so that no pole
            // and zero at z = -1 are left to cancel only to round-off.
            let first = |c: &[f64; 3]| [c[1] * kappa + c[2], c[2] - c[1] * kappa];
            let (n, d) = (first(&analog.numerator), first(&analog.denominator));
            return Self { b: [n[0] / d[0], n[1] / d[0], 0.0], a: [d[1] / d[0], 0.0] };
        }
        let (n, d) = (map(&analog.numerator), map(&analog.denominator));
        Self { b: [n[0] / d[0], n[1] / d[0], n[2] / d[0]], a: [d[1] / d[0], d[2] / d[0]] }
    }

    /// H(e^{jω}) at frequency `f_hz` for sample rate `rate_hz`.
    pub fn response(&self, f_hz: f64, rate_hz: f64) -> Complex<f64> {
        let z1 = Complex::from_polar(1.0, -2.0 * PI * f_hz / rate_hz);
        let z2 = z1 * z1;
        (z1 * self.b[1] + z2 * self.b[2] + self.b[0]) / (z1 * self.a[0] + z2 * self.a[1] + 1.0)
    }

    /// Filters `x` in place from rest (direct form II transposed).
    pub fn run(&self, x: &mut [f64]) {
        let (mut s1, mut s2) = (0.0, 0.0);
        for v in x.iter_mut() {
            let input = *v;
            let y = self.b[0] * input + s1;
            s1 = self.b[1] * input - self.a[0] * y + s2;
            s2 = self.b[2] * input - self.a[1] * y;
            *v = y;
        }
    }
}

/// A cascade of analog sections and their digital images at one sample rate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Cascade {
    rate_hz: f64,
    analog: Vec<Analog>,
    digital: Vec<Biquad>,
}

impl Cascade {
    /// The sections `analog` at `rate_hz`, each prewarped at its own ω₀.
    pub fn new(analog: Vec<Analog>, rate_hz: f64) -> Self {
        let digital = analog.iter().map(|a| Biquad::bilinear(a, rate_hz)).collect();
        Self { rate_hz, analog, digital }
    }

    /// The analog cascade's response Π H_a(j2πf): what the chain is meant to be.
    pub fn analog_response(&self, f_hz: f64) -> Complex<f64> {
        self.analog.iter().map(|a| a.response(2.0 * PI * f_hz)).product()
    }

    /// The digital cascade's response at `f_hz`: what the samples go through.
    pub fn response(&self, f_hz: f64) -> Complex<f64> {
        self.digital.iter().map(|d| d.response(f_hz, self.rate_hz)).product()
    }

    /// The largest of abs(abs(H(f)) - abs(H_a(j2πf))) over 200 frequencies spread evenly on
    /// (0, `band_hz`], relative to the analog chain's largest gain there: how far the samples'
    /// filter is from the analog chain in that band, as a share of its passband (a relative
    /// error taken point by point would be dominated by the steep flank of a high-order
    /// filter, where a small warp of frequency is a large ratio of small gains).
    pub fn largest_deviation(&self, band_hz: f64) -> f64 {
        let at = |k: usize| band_hz * k as f64 / 200.0;
        let top = (1..=200).map(|k| self.analog_response(at(k)).norm()).fold(0.0, f64::max);
        let worst = (1..=200)
            .map(|k| (self.response(at(k)).norm() - self.analog_response(at(k)).norm()).abs())
            .fold(0.0, f64::max);
        if top > 0.0 {
            worst / top
        } else {
            0.0
        }
    }

    /// The slowest decay rate of its sections' poles, 1/s (infinite for no section: it holds
    /// no past).
    pub fn slowest_decay(&self) -> f64 {
        self.analog.iter().map(Analog::decay_rate).fold(f64::INFINITY, f64::min)
    }

    /// Filters `x` (sampled at the cascade's rate) in place, from rest.
    pub fn run(&self, x: &mut [f64]) {
        for d in &self.digital {
            d.run(x);
        }
    }

    /// The sample rate, Hz.
    pub fn rate_hz(&self) -> f64 {
        self.rate_hz
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const RATE: f64 = 40_000.0;

    /// The digital Butterworth is the analog one at the warped frequency, so its magnitude
    /// has the closed form 1/(1 + (tan(πf/f_s)/tan(πf_c/f_s))^(2n)) (the bilinear map).
    #[test]
    fn butterworth_magnitude_is_the_closed_form() {
        for order in 1..=8 {
            let fc = 4_000.0;
            let c = Cascade::new(Analog::butterworth(order, 2.0 * PI * fc), RATE);
            for f in [0.0, 100.0, 1_000.0, 3_999.0, 4_000.0, 6_000.0, 12_000.0, 19_000.0] {
                let ratio = (PI * f / RATE).tan() / (PI * fc / RATE).tan();
                let exact = 1.0 / (1.0 + ratio.powi(2 * order as i32)).sqrt();
                let got = c.response(f).norm();
                assert!((got - exact).abs() < 1e-12, "order {order}, {f} Hz: {got} against {exact}");
            }
        }
    }

    /// Each digital section equals its analog section at the warped frequency Ω(f), in
    /// magnitude and phase, the resonance and the high-pass included.
    #[test]
    fn every_section_is_its_analog_at_the_warped_frequency() {
        let sections = [Analog::resonance(2.0 * PI * 12_000.0, 0.05), Analog::high_pass(2.0 * PI * 2.0)];
        for a in sections {
            let d = Biquad::bilinear(&a, RATE);
            let kappa = a.omega0 / (a.omega0 / (2.0 * RATE)).tan();
            for f in [0.5, 2.0, 50.0, 1_000.0, 11_000.0, 12_000.0, 15_000.0] {
                let warped = kappa * (PI * f / RATE).tan();
                let (got, exact) = (d.response(f, RATE), a.response(warped));
                assert!((got - exact).norm() < 1e-9 * exact.norm().max(1e-3), "{f} Hz: {got} against {exact}");
            }
        }
    }

    /// The realised chain's deviation follows the warp: a 1 Hz high-pass alone is its analog
    /// self to the warp of frequencies near DC ((πf)² - (πf₀)²)/(3f_s²), under 2e-3 over a
    /// 5 kHz band at 40 kHz; a resonance prewarped at 0.3 f_s keeps its frequency but not its
    /// bandwidth, and its flank below deviates by several per cent of the passband.
    #[test]
    fn the_deviation_follows_the_warp() {
        let dc = Cascade::new(vec![Analog::high_pass(2.0 * PI * 1.0)], RATE);
        assert!(dc.largest_deviation(5_000.0) < 2e-3, "{}", dc.largest_deviation(5_000.0));
        let high = Cascade::new(vec![Analog::resonance(2.0 * PI * 12_000.0, 0.05)], RATE);
        let d = high.largest_deviation(11_000.0);
        assert!(d > 0.02, "{d}");
    }

    /// The filter run on samples has the response it reports: a long sine through the
    /// cascade, once its transient has decayed, comes out scaled by abs(H) at that frequency.
    #[test]
    fn running_a_sine_gives_the_response() {
        let c = Cascade::new(Analog::butterworth(4, 2.0 * PI * 3_000.0), RATE);
        for f in [500.0, 3_000.0, 5_000.0] {
            let mut x: Vec<f64> = (0..40_000).map(|k| (2.0 * PI * f * k as f64 / RATE).sin()).collect();
            c.run(&mut x);
            let tail = &x[30_000..];
            let rms = (tail.iter().map(|v| v * v).sum::<f64>() / tail.len() as f64).sqrt();
            let expected = c.response(f).norm() / 2f64.sqrt();
            assert!((rms - expected).abs() < 1e-3 * expected, "{f} Hz: {rms} against {expected}");
        }
    }
}
