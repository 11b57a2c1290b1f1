//! Accepted ranges, in the file's units. Each is wide against any real plate, rock or
//! support and narrow enough that the SI values, and the powers of them the models take
//! (δ^{5/2}, h³, R³), stay far from overflow and underflow.
//!
//! The command line's and the Python package's ranges are here too, so that the check, its
//! message and the generated references (`docs/cli.md`, `docs/scenes.md`) read one number.

use analytic::params::Range;

/// Plate length and width, mm (1 mm to 100 m).
pub const PLATE_SIZE_MM: Range = Range::closed(1.0, 1e5);
/// Plate thickness, mm (1 µm to 10 m; and never more than the smaller side).
pub const THICKNESS_MM: Range = Range::closed(1e-3, 1e4);
/// Sphere radius, mm (1 µm to 10 m).
pub const RADIUS_MM: Range = Range::closed(1e-3, 1e4);
/// Young's moduli, GPa (1 kPa to 10 TPa).
pub const MODULUS_GPA: Range = Range::closed(1e-6, 1e4);
/// Densities, kg/m³.
pub const DENSITY_KG_M3: Range = Range::closed(1.0, 1e5);
/// Cohesion, MPa (1 Pa to 100 GPa).
pub const COHESION_MPA: Range = Range::closed(1e-6, 1e5);
/// Corner spring stiffness, N/m. Below ~1e-5 N/m the plate on its springs no longer
/// factors for its fundamental period (rigid-body eigenvalues ~k against plate
/// eigenvalues beyond 1e12); 1e-3 N/m is still a spring a 25 g rock compresses by
/// metres, far below any prop or jack.
pub const SPRING_N_PER_M: Range = Range::closed(1e-3, 1e18);
/// Largest ratio of the plate's longer to its shorter side: beyond it the plate is a
/// strip (a beam), and its elements become needles that do not factor.
pub const MAX_ASPECT_RATIO: f64 = 100.0;
/// Restitution of the Flores law: below 0.01 its damping term 8(1-e)/(5e) exceeds 100
/// and the law (built as an expansion about e = 1) has no meaning left; a = 2K/(5e)
/// also overflows as e → 0.
pub const RESTITUTION: Range = Range::open_closed(0.01, 1.0);
/// Impact velocity, m/s (above 1 km/s no contact law here has meaning).
pub const VELOCITY_M_PER_S: Range = Range::closed(1e-9, 1e3);
/// Signal window, ms (0.1 ms to 1 s: from a few contact times to far beyond the plate's
/// ring-down at the default damping).
pub const SIGNAL_WINDOW_MS: Range = Range::closed(0.1, 1000.0);
/// Sampling rate, Hz (100 Hz to 10 MHz: Nyquist frequencies from below a plate's first
/// modes to far beyond any mesh's).
pub const SAMPLE_RATE_HZ: Range = Range::closed(100.0, 1e7);
/// Most samples per channel of one impact (8 MB a channel).
pub const MAX_SAMPLES: f64 = 1e6;
/// Fewest samples per channel: the spectral features (the dominant frequency, refined on a
/// bin and its two neighbours above DC, and the spectral centroid) need a spectrum of more
/// than a few bins; a window of one or two samples passes every check and says nothing.
pub const MIN_SAMPLES: f64 = 16.0;
/// Largest memory of one impact's signals, bytes (samples x channels x 8; three channels a
/// sensor and one a supported corner): 1e6 samples on 64 sensors would be 1.5 GB an impact,
/// held by every worker thread at once.
pub const MAX_IMPACT_SIGNAL_BYTES: f64 = 512.0 * 1024.0 * 1024.0;
/// Most modes of the reduced model on any plate: [`max_modes`] of a square plate, the plate
/// whose mesh has the most nodes (20 x 20 elements, 1764 degrees of freedom).
pub const MAX_MODES: usize = 220;
/// `signals.truncation_check_fraction`: the share of each family the check on N/2 modes
/// strikes again (none would leave the modal truncation unchecked).
pub const TRUNCATION_CHECK: Range = Range::open_closed(0.0, 1.0);
/// Modes of the reduced model, `[signals] modes` (and at most [`max_modes`] of the plate).
pub const MODES: Range = Range::closed(1.0, MAX_MODES as f64);
/// Share of its mesh's degrees of freedom the reduced model may keep as modes: 1/8.
pub const MODES_PER_DOF: usize = 8;

/// Most modes the reduced model keeps on a plate of sides `length` x `width` (any one unit):
/// an eighth of the degrees of freedom of its mesh (the transient model's 20 elements along
/// the longer side, four a node), 178 on the paper's plate (20 x 16 elements, 1428 DOFs).
///
/// A mesh resolves only the low end of its spectrum: on the paper's plate the 100th frequency
/// is 0.5 % and the 180th 1.6 % above that of a mesh twice as fine, and the error grows with
/// the square of the mode's number beyond. The shift-invert search for N modes converges on a
/// basis of about 2N + 30 vectors, a quarter of the space at an eighth; asked for more it may
/// need the whole space before it converges or fails: 200 modes of a 1 mm plate on Con 2's
/// springs searched all 1428 vectors for 41 s before an error (180 converged in 0.4 s), and
/// 1000 modes were accepted and failed the same way. Checked when the scene is read, before
/// any mesh is built.
pub fn max_modes(length: f64, width: f64) -> usize {
    let elements = coupled::reduced::ReducedSettings::default().elements;
    let (nx, nz) = coupled::discretisation::divisions(length, width, elements);
    4 * (nx + 1) * (nz + 1) / MODES_PER_DOF
}
/// Most sensors.
pub const MAX_SENSORS: usize = 64;
/// Lumps per second of a caving stream (`[stream]`): up to 10,000, where every contact
/// overlaps others and the stream is a granular flow, not a sequence of impacts.
pub const STREAM_RATE_PER_S: Range = Range::open_closed(0.0, 1e4);
/// Length of one stream, s: up to a day.
pub const STREAM_DURATION_S: Range = Range::open_closed(0.0, 86_400.0);
/// A scale of the ensemble's radius laws in `[stream] size_sweep`: a factor of ten either way
/// is another population of lumps, not a shift of one.
pub const STREAM_SIZE_SCALE: Range = Range::closed(0.1, 10.0);
/// Independent streams of a study.
pub const STREAMS: Range = Range::closed(1.0, 64.0);

/// A stream segment's tolerance: the share of the state at a warm-up's start its end may
/// keep (below 1e-15 the warm-up decays to rounding; above 1e-2 the segments' joins show).
pub const SEGMENT_TOLERANCE: Range = Range::closed(1e-15, 1e-2);

/// The shortest stream segment, s: a segment re-runs its warm-up, which is seconds for a
/// lightly damped plate, so shorter segments cost many times the stream.
pub const MIN_SEGMENT_S: f64 = 1.0;
/// Time blocks of the stream's cross-validation.
pub const STREAM_BLOCKS: Range = Range::closed(2.0, 1000.0);
/// Largest memory of a stream study's signals, held at once: every stream's model signals and
/// their recording (samples x channels x 8 bytes each), 4 GB.
pub const MAX_STREAM_SIGNAL_BYTES: f64 = 4.0 * 1024.0 * 1024.0 * 1024.0;
/// Most lumps of a stream study, over its streams, arrival rates and support sets: ten
/// million (hours at the measured 1,100-1,400 contact steps a lump).
pub const MAX_STREAM_LUMPS: f64 = 1e7;
/// Most windows of a stream study, over its streams: a million (each a feature row per
/// channel, computed on every recording of the sweeps).
pub const MAX_STREAM_WINDOWS: f64 = 1e6;
/// Relative tolerance of the energy balance: below 1e-14 double precision cannot
/// reach it (the bracketed Newton's rounding floor is ~2e-15); above 1e-3 the "root" is not one (a loose stop returns the starting value).
pub const SOLVER_TOLERANCE: Range = Range::closed(1e-14, 1e-3);
/// Iteration limit of the energy-balance solver, `[solver] max_iterations`.
pub const SOLVER_ITERATIONS: Range = Range::closed(1.0, 10_000.0);
/// Evenly spaced points, `[points] count` and each side of `[points.grid]` (and `impact sweep
/// --count`): two to reach both ends, at most [`MAX_POINTS`](crate::MAX_POINTS).
pub const POINT_COUNT: Range = Range::closed(2.0, crate::MAX_POINTS as f64);

/// Seconds of quasi-static work (the beam and plate models' responses and yield velocities)
/// one scene may ask for: three minutes, estimated with the costs below before any work. The
/// costs are about twice those measured on a quiet machine: a scene at the budget, 7,000
/// support sets at one point (estimated 177 s), ran `impact solve` in 112 s on this 2-core
/// machine beside another engineer's runs, and in 424 s while a release build ran beside it.
pub const QUASI_STATIC_BUDGET_S: f64 = 180.0;
/// Cost of a support set, s: its fundamental period for the quasi-static validity criterion
/// (a factorization and up to 200 steps of inverse iteration) and the plate model's
/// factorizations; measured 13-16 ms a set at one point (`impact solve` on 500 to 7,000 sets,
/// beam or plate model), 34 ms on 3,000 sets of the default scene (nine points, three bodies).
pub const SECONDS_PER_SUPPORT_SET: f64 = 0.025;
/// Cost of an impact point on a support set, s: the plate model's compliance there on its
/// mesh ladder; measured 0.30 ms (a 316 x 316 grid of one case: 36 s with the plate model, 7 s
/// with the beam).
pub const SECONDS_PER_POINT: f64 = 3e-4;
/// Cost of a result row, s: its energy balance, validity and row; measured 0.042 ms (50,000
/// velocities at one point: 2.1 s).
pub const SECONDS_PER_ROW: f64 = 5e-5;

/// The quasi-static work of `sets` support sets x `points` points x `bodies` bodies, each
/// case giving `rows` rows (its velocities and its yield velocity), s; none without rows.
pub fn quasi_static_seconds(sets: usize, points: usize, bodies: usize, rows: usize) -> f64 {
    if bodies * rows * points == 0 {
        return 0.0;
    }
    let per_point = SECONDS_PER_POINT + (bodies * rows) as f64 * SECONDS_PER_ROW;
    sets as f64 * (SECONDS_PER_SUPPORT_SET + points as f64 * per_point)
}

/// Why `sets` x `points` x `bodies` cases of `velocities` velocities (and a yield velocity when
/// `yields`) are beyond [`QUASI_STATIC_BUDGET_S`], naming the scene's fields; None within it.
pub fn quasi_static_excess(
    sets: usize,
    points: usize,
    bodies: usize,
    velocities: usize,
    yields: bool,
) -> Option<String> {
    let seconds = quasi_static_seconds(sets, points, bodies, velocities + usize::from(yields));
    (seconds > QUASI_STATIC_BUDGET_S).then(|| {
        format!(
            "{sets} [[conditions]] x {points} points x {bodies} [[bodies]] x ({velocities} velocities.m_per_s{}) ask for about {seconds:.0} s of quasi-static work ({:.0} ms a support set, {:.2} ms a point on each, {:.2} ms a result row); the budget is {QUASI_STATIC_BUDGET_S:.0} s: use fewer support sets, points, bodies or velocities",
            if yields { " + a yield velocity" } else { "" },
            SECONDS_PER_SUPPORT_SET * 1e3,
            SECONDS_PER_POINT * 1e3,
            SECONDS_PER_ROW * 1e3,
        )
    })
}

// ------------------------------------------------------------ the command line and Python

/// Relative error the transient model is asked for (`--tolerance`, Python's `tolerance`):
/// below 1e-6 the ladder's budget cannot reach it, above 0.1 an estimate is no longer one.
pub const TRANSIENT_TOLERANCE: Range = Range::closed(1e-6, 0.1);
/// Gravity on the sphere toward the plate (`gravity_m_per_s2`), m/s²: from none (the paper)
/// to ten times Earth's, which covers any inclination of the plate and a drop test on a
/// centrifuge's scale without admitting a typo in the wrong unit (9,806.65 mm/s²).
pub const GRAVITY_M_PER_S2: Range = Range::closed(0.0, 100.0);
/// The plate's damping ratio at the two frequencies of `[plate_damping]`: above zero (no
/// damping is the table left out) and at most half of critical, as the reduced model's
/// modal ratio; between the two frequencies the ratio is lower, outside them higher.
pub const PLATE_DAMPING_RATIO: Range = Range::open_closed(0.0, 0.5);
/// The two frequencies of `[plate_damping]`, Hz: from a slow sway of a large structure to
/// beyond any mode a plate FE mesh resolves.
pub const DAMPING_FREQUENCY_HZ: Range = Range::closed(1e-3, 1e7);
/// The share of m·v₀ a contact's impulse must reach to count as a main contact
/// (`--main-contact-share`): 0 counts every contact, 1 none after a full stop.
pub const MAIN_CONTACT_SHARE: Range = Range::closed(0.0, 1.0);
/// Relative error at the plate centre for `impact fem-bench --tolerance`, as the mesh
/// convergence study takes it.
pub const FEM_BENCH_TOLERANCE: Range = Range::closed_open(1e-12, 1.0);
/// Impact points along each side of the `impact fem-bench` map (`--nx`, `--nz`).
pub const FEM_BENCH_POINTS: Range = Range::closed(2.0, 1001.0);
/// Elements along the longer side for `impact field --elements`: 200 is about 1.3e5
/// unknowns and well under a gigabyte for the factorization; beyond that the field is finer
/// than any viewer needs.
pub const FIELD_ELEMENTS: Range = Range::closed(2.0, 200.0);
/// The load that scales `impact field`'s .vtu (`--force-n`), N. 1e12 N, a hundred thousand
/// tonnes-force, is beyond any rock impact; under it every scaled value of every valid scene
/// stays finite (the largest unit-load values, a deflection of about L²/(100 D) ≤ 1e22 m/N
/// and a stress 6M/h² ≤ 1e13 Pa/N at the scene limits, times 1e12 are far below f64::MAX ≈
/// 1.8e308), and the writer still refuses any value that is not finite.
pub const FORCE_N: Range = Range::closed(1e-9, 1e12);

/// The tail beam's jack angle to its length axis, degrees.
pub const JACK_ANGLE_DEG: Range = Range::open_closed(-180.0, 180.0);
/// Most unknowns of the tail beam's finest mesh (six a node): a sparse factorization of 600,000
/// shell unknowns takes about 15 s and 2 GB here (measured 494,169 in 9 s).
pub const MAX_TAIL_BEAM_DOFS: usize = 600_000;
/// Most struck points on the tail beam: each costs a solve and an energy pass on each of the
/// three meshes, about 0.2 s on the largest mesh the budget allows, so that 200 points stay
/// within a minute there.
pub const MAX_TAIL_BEAM_POINTS: usize = 200;
