"""The transient model through the Python package against Hertz's impact on a rigid target.

A soft small sphere (R = 2 mm, E = 1 MPa) at 0.01 m/s on the paper's steel plate with its
edges clamped: the plate takes 2e-5 of the energy, so the impact is Hertz's. With the Hertz
law and e = 1, the rigid-target references are P = K delta_m^{3/2}, delta_m =
(5 m v^2 / 4K)^{2/5}, and t_c = 3.2180 (m^2/(K^2 v))^{1/5} (docs/notation.md), with K from eqs.
3-5 computed here.

Tolerances. The plate's share of the energy at maximum compression (`plate_ratio`) is the
departure from the rigid target: P ∝ delta^{3/2} and the sphere's energy ∝ delta^{5/2}, so P
falls by 3/5 of that share to first order, and t_c grows by at most the share. On top, the
integrator's error at 200 steps per contact time: 3.5e-5 in force and 5.3e-5 in energy,
measured against Hertz and at e = 1 (tests/dynamic.rs); we allow 5e-5 and 1e-4."""

from __future__ import annotations

import math

import numpy as np
import pytest

import impact

R, E, NU, RHO, V = 2e-3, 1e6, 0.45, 1000.0, 0.01
PLATE_E, PLATE_NU = 210e9, 0.3


def soft_sphere_scene(**top_level):
    """The paper's plate with its edges clamped, struck at its centre by the soft sphere at V
    under Hertz's law with e = 1, as a scene dict; `top_level` adds or replaces top-level keys."""
    import tomllib
    from conftest import REPO

    d = tomllib.loads((REPO / "scenes" / "paper-table-1.toml").read_text())
    del d["transient"]
    d.update(restitution=1.0, contact_law="hertz", analyses=["responses"], **top_level)
    d["bodies"] = [
        {
            "name": "soft",
            "density_kg_m3": RHO,
            "youngs_modulus_gpa": E / 1e9,
            "poisson_ratio": NU,
            "cohesion_mpa": 1000.0,
            "friction_angle_deg": 30.0,
            "radius_mm": R * 1e3,
        }
    ]
    d["conditions"] = [{"name": "clamped", "edges": dict.fromkeys(["left", "right", "near", "far"], "clamped")}]
    d["points"] = {"pairs_mm": [[229.2, 180.0]]}
    d["velocities"] = {"m_per_s": [V]}
    return d


@pytest.fixture(scope="module")
def run():
    d = soft_sphere_scene()
    return impact.transient(d, "soft", "clamped", 229.2, 180.0, V, error_estimate=False)


def hertz():
    e_star = 1.0 / ((1 - NU**2) / E + (1 - PLATE_NU**2) / PLATE_E)
    k = 4.0 / 3.0 * math.sqrt(R) * e_star
    m = RHO * 4.0 / 3.0 * math.pi * R**3
    delta = (5.0 * m * V**2 / (4.0 * k)) ** 0.4
    return m, k * delta**1.5, 3.2180 * (m**2 / (k**2 * V)) ** 0.2


def test_force_and_contact_time_meet_hertz(run):
    _, force, time = hertz()
    r = run.response
    share = float(r["plate_ratio"][0])
    assert 0.0 < share < 1e-4, "the plate must be nearly rigid for this sphere"
    assert abs(r["contact_force_N"][0] / force - 1.0) <= 0.6 * share + 5e-5
    assert abs(r["contact_time_s"][0] / time - 1.0) <= share + 5e-5
    # The validity status: inside every criterion, one contact, left for good.
    assert bool(r["valid"][0]) and r["validity_flags"][0] == "" and r["contacts"][0] == 1
    assert run.left_for_good
    # Counts are integers: every row of this table has them.
    for c in ("contacts", "steps"):
        assert r[c].dtype == np.int64, (c, r[c].dtype)
    assert run.contacts["steps"].dtype == np.int64 and run.contacts["steps"][0] > 0


def test_history_conserves_energy_at_e_equal_1(run):
    m, force, _ = hertz()
    h = run.history
    e0 = 0.5 * m * V**2
    stores = h["sphere_kinetic_J"] + h["contact_J"] + h["plate_kinetic_J"] + h["plate_strain_J"] + h["springs_J"]
    assert np.max(np.abs(stores - e0)) / e0 <= 1e-4
    # The history's largest force is the sampled peak, below the interpolated one by at
    # most the integrator's error, and the contacts table has the one contact.
    assert h["force_N"].max() == pytest.approx(force, rel=1e-4)
    assert np.all(np.diff(h["t_s"]) > 0)
    assert len(run.contacts["duration_s"]) == 1


def test_gravity_brings_the_sphere_back_after_the_window(run):
    """Under a weak gravity g = 0.05 m/s² (the scene's ``gravity_m_per_s2``) the nearly rigid
    plate throws the sphere back at about V, and it falls back after 2|v_r|/g ≈ 0.4 s, beyond
    the window of 200 Hertz times (≈ 0.3 s): the run stops at the separation, is not "left
    for good", and gives the earliest return, which the parabola of free flight bounds from
    above (t_c + 2|v_r|/g, the plate's own reach only brings it earlier, by its deflection
    over |v_r|: microns over 0.01 m/s, 1e-3 of it at most)."""
    d = soft_sphere_scene(gravity_m_per_s2=0.05)
    fall = impact.transient(d, "soft", "clamped", 229.2, 180.0, V, error_estimate=False)
    assert not fall.left_for_good and fall.returns_at_s is not None
    t_c = float(fall.contacts["duration_s"][0])
    v_r = abs(float(fall.contacts["rebound_velocity_m_per_s"][0]))
    parabola = t_c + 2.0 * v_r / 0.05
    window = 200 * hertz()[2]
    assert window < fall.returns_at_s <= parabola * (1 + 1e-12)
    assert fall.returns_at_s > (1 - 1e-3) * parabola
    assert run.returns_at_s is None
    d["gravity_m_per_s2"] = -1.0
    with pytest.raises(impact.SceneError, match=r"gravity_m_per_s2 = -1"):
        impact.transient(d, "soft", "clamped", 229.2, 180.0, V, error_estimate=False)
