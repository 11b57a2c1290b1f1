"""Rock-sphere impact on supported steel plates, from Python.

The same library as the ``impact`` command line (Rust, through PyO3): the paper's beam model,
Kirchhoff plate finite elements with Richardson error estimates, and the transient impact
model (sphere, Flores/Hertz/Thornton contact and plate dynamics in time).

Scenes are the command line's scene files (TOML, units in the key names), or the same
layout as a dict, read by the same parser and validation::

    import impact, pandas as pd
    scene = impact.Scene.from_toml("scenes/clamped-edge-props.toml")
    r = impact.solve(scene, model="plate")
    pd.DataFrame(r.responses)

Results are columnar: a dict of numpy arrays, one entry per row, ready for
``pandas.DataFrame``. Conventions:

- SI units, the unit in the column name (``contact_force_N``, ``x_m``, ``velocity_m_per_s``);
  ratios are over the sphere's kinetic energy E0 = m v^2 / 2.
- Every row carries its validity: ``valid`` (inside every criterion), ``validity_flags`` (the
  criteria it is beyond, "; "-separated; empty for a valid row) and the measured ratios ``elastic_ratio``
  (delta_max/delta_my, limit 1), ``quasi_static_ratio`` (t_c/T1, limit 0.2),
  ``thin_plate_ratio`` (h/min(L, B), limit 0.05), ``regime_force_error`` (the closed-form
  regime rule's bound on the quasi-static force error, limit 0.03) and ``contacts``
  (transient, limit 1).
  Beyond validity a number is still computed, and flagged.
- ``applicable`` is False where the model does not describe a row (the beam and a general
  support set); ``reason`` says why.
- NaN only where a quantity does not apply to a row (a not-applicable row, an error
  estimate a model does not give, a spring its support set lacks), never as a computed
  value; a column that applies to no row is left out.
- Counts (``steps``, ``contacts``, ``elements``, ``solver_iterations``) are int64; in a
  table that mixes rows where a count does not apply (``model="all"``, a not-applicable
  row) the column is float64 with NaN there, as pandas does for missing integers.

Every long computation releases the GIL.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any, Literal, Mapping, Optional, Sequence, Union

import numpy as np

try:
    from . import _impact
except ImportError as e:  # the source tree's python/impact, not the installed package
    raise ImportError(
        "impact's extension module impact._impact is not built here: install the package with "
        "`pip install ./python` and import it from outside the python/ directory"
    ) from e
from ._impact import Detector, ModelError, Scene, SceneError, SceneTypeError

__all__ = [
    "Columns",
    "DEFAULT_TOLERANCE",
    "Detector",
    "DropResults",
    "ModelError",
    "Results",
    "Scene",
    "SceneError",
    "SceneTypeError",
    "StreamCondition",
    "StreamRecording",
    "StreamResults",
    "TRANSIENT_TOLERANCE",
    "TailBeamResults",
    "Transient",
    "drops",
    "ensemble_size",
    "identify",
    "load_scene",
    "read_signal",
    "solve",
    "stream",
    "stream_recording",
    "stream_segments",
    "sweep",
    "tail_beam",
    "transient",
    "yield_velocity",
]
__version__: str = _impact.__version__

#: The transient model's relative tolerances accepted, ``(low, high)``, both ends included
#: (``impact solve --tolerance``); from the Rust constant the command line checks.
TRANSIENT_TOLERANCE: tuple[float, float] = _impact.TRANSIENT_TOLERANCE
#: The transient model's relative tolerance when none is given.
DEFAULT_TOLERANCE: float = _impact.DEFAULT_TOLERANCE

#: A table as columns: name -> numpy array, every array one entry per row.
Columns = dict[str, np.ndarray]

#: What the functions accept as a scene: a Scene, a path to a scene file, or a dict with the
#: layout of a scene file.
SceneLike = Union[Scene, str, "os.PathLike[str]", Mapping[str, Any]]
#: The models that answer: the paper's beam, the Kirchhoff plate FE (quasi-static), the transient
#: plate, the Reissner-Mindlin plate FE (quasi-static, with transverse shear), or all.
Model = Literal["beam", "plate", "transient", "mindlin", "all"]


def load_scene(scene: SceneLike) -> Scene:
    """A validated :class:`Scene` from a Scene, a scene-file path or a dict.

    Raises :class:`SceneError` (a ``ValueError``) naming the field, the value as written and
    the allowed range, exactly as the command line does.
    """
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, Mapping):
        return Scene.from_dict(dict(scene))
    if isinstance(scene, (str, os.PathLike)):
        return Scene.from_toml(os.fspath(scene))
    raise TypeError(f"a scene is a Scene, a path or a dict, not {type(scene).__name__}")


def _columns(raw: Mapping[str, Any]) -> Columns:
    """numpy arrays for every column (texts come from Rust as lists)."""
    return {k: (np.asarray(v, dtype=np.str_) if isinstance(v, list) else v) for k, v in raw.items()}


@dataclass(frozen=True)
class Results:
    """The rows of one run, as columns.

    Attributes:
        scene: the scene's name.
        responses: responses at maximum compression, one row per model, body, support set,
            point and velocity (empty for :func:`yield_velocity`).
        yields: yield velocities (eqs. 51-54), one row per model, body, support set and point.
        status: the command line's status line ("status: N results, M inside every
            validity criterion; ...").
        summary: counts of rows by validity (computed, valid, beyond_elastic,
            not_quasi_static, beyond_thin_plate, outside_regime_rule, recontact,
            unfinished, above_tolerance, not_applicable).
    """

    scene: str
    responses: Columns
    yields: Columns
    status: str
    summary: dict[str, int]


def _results(raw: Mapping[str, Any]) -> Results:
    return Results(
        scene=raw["scene"],
        responses=_columns(raw["responses"]),
        yields=_columns(raw["yields"]),
        status=raw["status"],
        summary=dict(raw["summary"]),
    )


def solve(
    scene: SceneLike,
    model: Model = "beam",
    *,
    tolerance: float | None = None,
    main_contact_share: float | None = None,
) -> Results:
    """Responses and yield velocities at the scene's points (``impact solve``).

    Args:
        scene: a :class:`Scene`, a scene-file path or a dict (see :func:`load_scene`).
        model: "beam" (the paper's closed forms), "plate" (Kirchhoff plate finite elements,
            quasi-static, Richardson-extrapolated with an error estimate), "transient" (the
            plate in time, each response with its discretisation error), "mindlin"
            (Reissner-Mindlin plate finite elements: Kirchhoff's plate with transverse shear,
            the contact spread over a square of side h) or "all".
        tolerance: the transient model's relative tolerance on the forces and the contact
            time, for which each case's mesh and step are chosen (within
            :data:`TRANSIENT_TOLERANCE`; default :data:`DEFAULT_TOLERANCE`, ``impact solve
            --tolerance``).
        main_contact_share: the share of m·v₀ a contact's impulse must reach to count among
            the transient impact's ``main_contacts``; the others are ``micro_contacts``
            (chatter), counted with their total impulse (in [0, 1]; default 0.05, ``impact
            solve --main-contact-share``).

    The scene's ``analyses`` decide what is computed ("responses", "yield-velocity").
    The numbers are those of ``impact solve --json`` for the same scene, bit for bit.
    """
    return _results(
        _impact.run(load_scene(scene), model, tolerance=tolerance, main_contact_share=main_contact_share)
    )


def sweep(
    scene: SceneLike,
    count: int = 101,
    model: Model = "beam",
    *,
    tolerance: float | None = None,
    main_contact_share: float | None = None,
) -> Results:
    """:func:`solve` on ``count`` evenly spaced points of the centreline z = B/2, from x = 0
    to L (``impact sweep --count``; the paper uses 101)."""
    run = _impact.run(
        load_scene(scene), model, sweep=float(count), tolerance=tolerance, main_contact_share=main_contact_share
    )
    return _results(run)


def yield_velocity(
    scene: SceneLike, model: Model = "beam", *, tolerance: float | None = None, main_contact_share: float | None = None
) -> Results:
    """Yield velocities only (eqs. 51-54; ``impact yield``); for the transient model, the
    velocity at which the transient delta_max reaches the paper's delta_my."""
    run = _impact.run(
        load_scene(scene), model, yield_only=True, tolerance=tolerance, main_contact_share=main_contact_share
    )
    return _results(run)


@dataclass(frozen=True)
class Transient:
    """One transient impact.

    Attributes:
        response: the responses at maximum compression, one row with the columns of
            :attr:`Results.responses` (errors when run with ``error_estimate``).
        history: time series, one entry per time step: ``t_s``, ``force_N``,
            ``compression_m``, ``sphere_velocity_m_per_s``, ``plate_displacement_m`` (at the
            impact point), the energies ``sphere_kinetic_J``, ``contact_J``,
            ``plate_kinetic_J``, ``plate_strain_J``, ``springs_J``, ``dissipated_J``, and
            ``first_contact`` (True up to the first separation).
        contacts: one row per completed contact: ``start_s``, ``duration_s``,
            ``peak_force_N``, ``impulse_N_s``, ``rebound_velocity_m_per_s``, ``steps``.
        left_for_good: whether the run proved that the sphere cannot strike again (else the
            window ended first, or gravity brings it back after the window).
        returns_at_s: under gravity (the scene's ``gravity_m_per_s2``), the earliest instant
            the sphere can touch the plate again, after the window; None otherwise.
    """

    response: Columns
    history: Columns
    contacts: Columns
    left_for_good: bool
    returns_at_s: float | None = None


def transient(
    scene: SceneLike,
    body: str,
    condition: str,
    x_mm: float,
    z_mm: float,
    velocity_m_per_s: float,
    *,
    error_estimate: bool = True,
    tolerance: float | None = None,
) -> Transient:
    """One transient impact with its histories.

    Args:
        scene: the scene (its plate, contact law and restitution).
        body: a body of the scene, by name.
        condition: a support set of the scene, by name.
        x_mm, z_mm: the impact point, mm (x along the length from the left end, z across).
        velocity_m_per_s: the impact velocity.
        error_estimate: choose the mesh and time step for the relative ``tolerance`` on the
            forces and the contact time, and give every response its error, exactly as
            ``impact solve --model transient`` computes a row; without, one run on the
            starting mesh (20 elements, 200 steps per Hertz contact time).
        tolerance: the relative tolerance (within :data:`TRANSIENT_TOLERANCE`; default
            :data:`DEFAULT_TOLERANCE`, ``--tolerance``).
    """
    raw = _impact.transient(
        load_scene(scene),
        body,
        condition,
        float(x_mm),
        float(z_mm),
        float(velocity_m_per_s),
        error_estimate=error_estimate,
        tolerance=None if tolerance is None else float(tolerance),
    )
    return Transient(
        response=_columns(raw["response"]),
        history=_columns(raw["history"]),
        contacts=_columns(raw["contacts"]),
        left_for_good=bool(raw["left_for_good"]),
        returns_at_s=None if raw["returns_at_s"] is None else float(raw["returns_at_s"]),
    )


def identify(
    scene: SceneLike,
    condition: str,
    start: int = 0,
    stop: int | None = None,
    *,
    sensors_mm: Sequence[tuple[float, float]] | None = None,
) -> Columns:
    """Impacts ``start`` to ``stop - 1`` of the scene's coal-gangue ensemble on the support
    set ``condition``, as ``impact identify`` runs them: the scene's ``[ensemble]`` draws,
    the reduced-order transient model and the ``[signals]`` (window, rate, modes, damping,
    named sensors), every channel reduced to its features.

    Impact ``i`` is drawn from its own stream (ChaCha8, the ensemble's seed, stream i), so
    any split of [0, n) into index ranges gives, concatenated, the rows of one run of the
    whole ensemble, bit for bit (:func:`impact.shards.run_identify` runs them on Dask).
    ``stop`` defaults to the ensemble's size. The sensors are the scene's named ones
    (``[signals] sensors_mm``) unless ``sensors_mm`` gives others ((x, z) in mm); a sensor's
    features do not depend on the other sensors.

    Columns: ``index``, ``family``, ``class`` ("coal" | "gangue"), the draw (``x_m``,
    ``z_m``, ``velocity_m_per_s``, ``radius_m``, ``density_kg_m3``, ``youngs_modulus_pa``,
    ``poisson_ratio``, ``cohesion_pa``, ``friction_angle_deg``), the contact
    (``force_max_N``, ``contact_time_s``, ``contacts``, ``unfinished``), the validity
    (``valid``, ``validity_flags``, ``elastic_ratio`` = delta_max/delta_my, ``quasi_static_ratio`` =
    t_c/T1, a regime label here), and one column per channel and feature, named
    "<channel>: <feature> (<unit>)" with the channel as the identify report names it, e.g.
    "acceleration at (229.2, 180) mm: peak (m/s^2)". An empty range has no feature columns.

    Under the scene's measurement chain (``[measurement]``) the features are those of the
    recorded signals (filtered, sampled, with the seeded background, quantised), only the
    recorded quantities have columns, and each channel adds "<channel>: clean peak (<unit>)"
    (its peak before the background: the signal of its SNR) beside ``clipped_samples``.
    """
    s = load_scene(scene)
    n = ensemble_size(s)
    sensors = None if sensors_mm is None else [(float(x), float(z)) for x, z in sensors_mm]
    return _columns(
        _impact.identify(s, condition, float(start), float(n if stop is None else stop), sensors_mm=sensors)
    )


@dataclass(frozen=True)
class StreamCondition:
    """One support set of a stream study.

    Attributes:
        windows: every window of the main run (``stream``, ``start_s``, ``end_s``, ``lumps``,
            ``gangue_lumps``, ``expected_gangue_share``, ``gangue_rich``, and
            ``probability_gangue_rich``: the every-channel detector's out-of-fold probability,
            NaN where a window straddles a block edge and is not scored).
        lumps: every lump of the main run (``stream``, ``time_s``, ``family``, ``gangue``,
            ``mass_kg``, ``velocity_m_per_s``, ``x_m``, ``z_m``, ``contacts``,
            ``contact_time_s``, ``force_max_N``, ``overlapped``).
        signal: the first stream as recorded, one array per channel named as in the report
            ("acceleration at (229.2, 180) mm (m/s^2)"), when the scene sets ``write_signal``.
        signal_rate_hz: its sample rate.
        detector: the every-channel detector fitted on every window of the main run, the one
            ``impact stream`` writes as ``detector.json`` (without the scene's hash, which
            the command line adds); ``detector.score(channels, rate_hz)`` applies it.
    """

    windows: Columns
    lumps: Columns
    signal: dict[str, np.ndarray] | None
    signal_rate_hz: float | None
    detector: Detector


@dataclass(frozen=True)
class StreamResults:
    """A stream study: ``results`` as ``impact stream`` writes them to ``stream.json``
    (the study, and per support set the simulation, the detector by channel group, the
    baselines, the sweeps and, where the scene sets ``design_sensors``, the window-level
    sensor design under ``"design"``), and per support set its columns."""

    results: dict[str, Any]
    conditions: dict[str, StreamCondition]


def stream(scene: SceneLike) -> StreamResults:
    """The scene's ``[stream]`` study, as ``impact stream`` runs it: the ``[ensemble]``'s
    lumps arriving as Poisson streams whose gangue share changes, one continuous signal per
    stream on the reduced model (lumps in contact together solved jointly), recorded through
    ``[measurement]`` if given, and a logistic detector over sliding windows cross-validated
    by time blocks. Numbers are the command line's, bit for bit.
    """
    import json

    raw = _impact.stream(load_scene(scene))
    conditions = {
        name: StreamCondition(
            windows=_columns(c["windows"]),
            lumps=_columns(c["lumps"]),
            signal=c.get("signal"),
            signal_rate_hz=c.get("signal_rate_hz"),
            detector=c["detector"],
        )
        for name, c in raw["conditions"].items()
    }
    return StreamResults(results=json.loads(raw["results"]), conditions=conditions)


@dataclass(frozen=True)
class StreamRecording:
    """One stream of a stream study, alone: ``signal`` (one float64 array per channel,
    named as in the report, as recorded: through ``[measurement]`` if the scene has one),
    its ``rate_hz``, and its ``lumps`` as columns (the study's lump columns). For one
    segment of a cut stream, ``segment`` is its number and ``start_s`` the time of its first
    sample in the stream (None and 0 for a whole stream)."""

    signal: dict[str, np.ndarray]
    rate_hz: float
    lumps: Columns
    segment: Optional[int] = None
    start_s: float = 0.0


def stream_recording(
    scene: SceneLike, condition: str, stream: int = 0, segment: Optional[int] = None
) -> StreamRecording:
    """Stream number ``stream`` of the scene's ``[stream]`` study on the support set
    ``condition``, computed alone: its lumps drawn with the seed ``seed + stream``, its
    background from its own stream of random numbers. It is the study's stream of that
    number bit for bit (with ``write_signal``, ``impact stream``'s ``signal.csv`` or
    ``signal.parquet`` is stream 0), so streams can be computed apart, one task each
    (``client.map`` on a Dask cluster of one CPU kind: the FFT picks its SIMD path at run
    time), and put together. Any whole number in [0, 1e9] may be asked for, not only the
    study's ``streams``: each is an independent stream of the same spec.

    Where the scene cuts its streams (``[stream] segment_s``), ``segment`` asks for one
    segment alone: its samples and the lumps that touched within it, the study's own bit for
    bit; :func:`stream_segments` says how many there are, and
    :func:`impact.shards.run_stream` computes them as Dask tasks and puts them together."""
    s = load_scene(scene)
    raw = _impact.stream_recording(s, condition, float(stream), None if segment is None else float(segment))
    start = 0.0
    if segment is not None:
        cut = _impact.stream_segments(s)
        start = 0.0 if cut is None else segment * cut[1]
    return StreamRecording(
        signal=raw["signal"], rate_hz=raw["rate_hz"], lumps=_columns(raw["lumps"]), segment=segment, start_s=start
    )


def stream_segments(scene: SceneLike) -> Optional[tuple[int, float]]:
    """How the scene's ``[stream]`` cuts every stream: (segments, a segment's length in s,
    to a whole ADC sample), or None where each stream runs in one piece (no ``segment_s``)."""
    return _impact.stream_segments(load_scene(scene))


def read_signal(path: Union[str, "os.PathLike[str]"]) -> dict[str, Any]:
    """A recording as ``impact detect`` reads it: the sidecar ``path`` (JSON, format
    ``impact-signal/1``) and the CSV or Parquet file it names beside it. Returns ``channels`` (a list of
    float64 arrays, in the sidecar's ``columns`` order), ``names``, ``rate_hz`` and
    ``onset_s`` (None where the sidecar states none). A detector scores it with
    ``detector.score(r["channels"], r["rate_hz"])``; ``detector.detect(path)`` does both and
    adds the operating answer."""
    return _impact.read_signal(os.fspath(path))


@dataclass(frozen=True)
class DropResults:
    """Recorded drops against the model.

    Attributes:
        results: the run as ``impact drops --json`` prints it (scene, condition, channels,
            rate, modes, realisations, and every drop with its rows).
        rows: one row per drop and quantity (``drop``, ``touch_s``, ``class``, ``quantity``,
            ``unit``, ``measured``, ``predicted``, ``bar``, ``truncation``, ``time_step``,
            ``chain``, ``noise_sd``, ``disagrees``), as ``drops.csv``.
    """

    results: dict[str, Any]
    rows: Columns


def drops(scene: SceneLike, signal: Union[str, "os.PathLike[str]"]) -> DropResults:
    """Every drop the recording's sidecar ``signal`` lists (touch time, point, lump, height;
    docs/guide.md) thrown on the scene's reduced model of the same support set through its
    ``[measurement]`` chain: each channel's peak and spectral centroid, and P_max and t_c where
    measured, beside the model's prediction (the mean over 16 realisations of the chain's
    background) and its bar (modal truncation + contact time step + chain realisation + three
    standard deviations of the noise). The scene needs ``"drops"`` among its analyses. Numbers
    are the command line's, bit for bit."""
    import json

    raw = _impact.drops(load_scene(scene), os.fspath(signal))
    return DropResults(results=json.loads(raw["results"]), rows=_columns(raw["rows"]))


@dataclass(frozen=True)
class TailBeamResults:
    """The scene's lumps on its box-section tail beam (``[tail_beam]``).

    Attributes:
        results: the whole study as JSON (the box, its meshes, frequency, mass, validity of the
            shell model, every impact, and the paper's beam and plate under the same lumps).
        rows: one row per body, velocity and struck point: the compliance ``C_m_per_N`` with
            its error and its shares (membrane, bending, shear, jacks), the three forces
            ``P_max_wave_controlled_N`` (the answer), ``P_max_quasi_static_N`` and
            ``P_max_rigid_target_N``, the jacks' force, ``t_c_per_T_1``, Olsson's ``M_i_per_M_p`` and
            ``regime``, Christoforou and Yigit's ``lambda`` and ``zeta``,
            ``delta_max_per_delta_my`` and the yield velocities; keyed as
            ``tail-beam/impacts.csv``.
    """

    results: dict[str, Any]
    rows: Columns


def tail_beam(scene: SceneLike) -> TailBeamResults:
    """The scene's bodies at its velocities on its ``[tail_beam]``: a welded box of shell walls
    on hinge pins and jacks (docs/guide.md, "The tail beam"). The scene needs ``"tail-beam"``
    among its analyses. Numbers are the command line's (``impact compare``), bit for bit."""
    import json

    raw = _impact.tail_beam(load_scene(scene))
    return TailBeamResults(results=json.loads(raw["results"]), rows=_columns(raw["rows"]))


def ensemble_size(scene: SceneLike) -> int:
    """The number of impacts of the scene's ``[ensemble]`` (0 without one)."""
    return int(load_scene(scene).ensemble_size)
