"""Scenes from Python: the same validation and messages as scene files, errors as SceneError
with the field, the value and the allowed range as attributes; dict and file give the same
scene; a scene survives pickling (how Dask ships it to a worker)."""

from __future__ import annotations

import copy
import pickle

import numpy as np
import pytest

import impact
from conftest import REPO


def test_out_of_range_names_field_value_and_range(paper_dict):
    paper_dict["plate"]["length_mm"] = 1e300
    with pytest.raises(impact.SceneError) as e:
        impact.Scene.from_dict(paper_dict)
    err = e.value
    assert isinstance(err, ValueError)
    assert (err.field, err.value, err.allowed, err.low, err.high, err.unit) == (
        "plate.length_mm", 1e300, "[1, 100000]", 1.0, 1e5, "mm"
    )
    # The command line's message, word for word.
    assert str(err) == "scene <dict>: plate.length_mm = 1e300 is outside the allowed range [1, 100000] mm"


def test_inconsistent_and_unknown_fields_are_named(paper_dict):
    d = dict(paper_dict, points={"x_mm": [1.0], "z_mm": [2.0]})
    with pytest.raises(impact.SceneError, match="z_mm beside x_mm") as e:
        impact.Scene.from_dict(d)
    assert e.value.field == "points.z_mm" and e.value.value is None
    with pytest.raises(impact.SceneError, match="unknown field `lenght_mm`"):
        impact.Scene.from_dict(dict(paper_dict, plate=dict(paper_dict["plate"], lenght_mm=1.0)))
    with pytest.raises(impact.SceneError, match="plate.density_kg_m3 is None") as e:
        impact.Scene.from_dict(dict(paper_dict, plate=dict(paper_dict["plate"], density_kg_m3=None)))
    assert e.value.field == "plate.density_kg_m3"
    with pytest.raises(FileNotFoundError) as e:
        impact.Scene.from_toml(REPO / "no-such-scene.toml")
    assert "cannot read scene file" in str(e.value) and e.value.filename.endswith("no-such-scene.toml")


def test_bad_arguments_are_value_errors_not_scene_errors():
    scene = impact.Scene.default()
    with pytest.raises(ValueError, match="'fem' is not a model"):
        impact.solve(scene, model="fem")
    with pytest.raises(ValueError) as e:
        impact.sweep(scene, count=1)
    assert e.value.field == "count" and e.value.allowed == "[2, 100000]"
    assert not isinstance(e.value, impact.SceneError)
    with pytest.raises(ValueError) as e:
        impact.transient(scene, "coal", "Con 1", 500.0, 180.0, 0.008)
    assert e.value.field == "x_mm" and e.value.high == pytest.approx(458.4)
    with pytest.raises(ValueError, match="'slate' is not in the scene"):
        impact.transient(scene, "slate", "Con 1", 100.0, 180.0, 0.008)
    with pytest.raises(ValueError) as e:
        impact.solve(scene, model="transient", main_contact_share=1.5)
    assert e.value.field == "main_contact_share" and e.value.allowed == "[0, 1]"


def test_dict_and_file_give_the_same_numbers(paper_dict):
    from_file = impact.solve(REPO / "scenes" / "paper-table-1.toml")
    # numpy scalars and arrays are taken as their Python values.
    paper_dict["points"]["x_mm"] = np.asarray(paper_dict["points"]["x_mm"])
    paper_dict["restitution"] = np.float64(paper_dict["restitution"])
    from_dict = impact.solve(paper_dict)
    for k, v in from_file.responses.items():
        np.testing.assert_array_equal(v, from_dict.responses[k])


def test_pickled_scene_is_the_same_scene():
    scene = impact.Scene.from_toml(REPO / "scenes" / "clamped-edge-props.toml")
    back = pickle.loads(pickle.dumps(scene))
    assert back.to_toml_str() == scene.to_toml_str() and back.origin == scene.origin
    assert back.conditions == scene.conditions and back.points_m == scene.points_m


def test_columns_follow_the_conventions():
    r = impact.solve(REPO / "scenes" / "clamped-edge-props.toml", model="beam")
    cols = r.responses
    n = len(cols["model"])
    assert n > 0 and all(len(v) == n for v in cols.values())
    assert all(isinstance(v, np.ndarray) for v in cols.values())
    # NaN only where a quantity does not apply: every not-applicable row has no values, and
    # every applicable row has all of the beam's.
    na = ~cols["applicable"]
    assert na.any() and (~na).any()
    for c in ["contact_force_N", "compression_m", "deflection_m", "plate_ratio", "thin_plate_ratio"]:
        assert np.isnan(cols[c][na]).all() and np.isfinite(cols[c][~na]).all()
    assert all(s.startswith("the beam") or s for s in cols["reason"][na])
    assert r.summary["not_applicable"] == int(na.sum()) + int((~r.yields["applicable"]).sum())
    # A count some rows lack (the not-applicable ones) is float with NaN there; where every
    # row has it, an integer.
    it = cols["solver_iterations"]
    assert it.dtype == np.float64 and np.isnan(it[na]).all() and (it[~na] == np.round(it[~na])).all()
    plate = impact.solve(REPO / "scenes" / "clamped-edge-props.toml", model="plate").responses
    assert plate["solver_iterations"].dtype == np.int64 and (plate["solver_iterations"] > 0).all()


def _set(d, path, value):
    """d with the key at `path` ("plate.length_mm", "bodies[1].name") set to `value`, or
    removed when `value` is `_REMOVE`."""
    keys = path.replace("[", ".").replace("]", "").split(".")
    parent = d
    for k in keys[:-1]:
        parent = parent[int(k)] if k.isdigit() else parent[k]
    if value is _REMOVE:
        del parent[keys[-1]]
    else:
        parent[keys[-1]] = value
    return d


_REMOVE = object()


@pytest.mark.parametrize(
    "path, value, field, allowed, words",
    [
        # Unknown keys, at the top, in a table and in the n-th entry of a list of tables.
        ("colour", "red", "colour", "one of `name`", "unknown field `colour`"),
        ("plate.colour", "red", "plate.colour", "one of `length_mm`, `width_mm`", "unknown field `colour`"),
        ("bodies[1].colour", "red", "bodies[1].colour", "one of `name`, `density_kg_m3`", "unknown field"),
        # Wrong types.
        ("plate.length_mm", "long", "plate.length_mm", "a number", 'invalid type: string "long"'),
        ("bodies[2].radius_mm", [1.0, 2.0], "bodies[2].radius_mm", "a number", "invalid type: sequence"),
        ("velocities.m_per_s", [0.008, "x"], "velocities.m_per_s[1]", "a number", 'string "x"'),
        ("plate.thickness_mm", object(), "plate.thickness_mm", "a number, string, boolean, list or dict", "of type object"),
        # Missing keys, at the top and in a list's entry.
        ("name", _REMOVE, "name", None, "missing field `name`"),
        ("bodies[1].name", _REMOVE, "bodies[1].name", None, "missing field `name`"),
        # None.
        ("plate.thickness_mm", None, "plate.thickness_mm", None, "is None"),
    ],
)
def test_dict_errors_name_the_field_the_user_wrote(paper_dict, path, value, field, allowed, words):
    with pytest.raises(impact.SceneError) as e:
        impact.Scene.from_dict(_set(paper_dict, path, value))
    err = e.value
    assert err.field == field, str(err)
    assert (allowed is None and err.allowed is None) or (allowed is not None and err.allowed.startswith(allowed)), err.allowed
    msg = str(err)
    assert msg.startswith(f"scene <dict>: {field}") and words in msg, msg
    # Not the parser's view of an internal text: no line numbers, no TOML parse error.
    assert "line" not in msg and "TOML" not in msg, msg


def test_an_integer_beyond_a_float_is_a_range_error_naming_its_field(paper_dict):
    for big, shown in ((10**400, "1e400"), (-(12345 * 10**396), "-1.2345e400")):
        with pytest.raises(impact.SceneError) as e:
            impact.Scene.from_dict(_set(copy.deepcopy(paper_dict), "plate.thickness_mm", big))
        err = e.value
        assert (err.field, err.allowed, err.unit, err.value) == ("plate.thickness_mm", "[0.001, 10000]", "mm", big)
        assert str(err) == f"scene <dict>: plate.thickness_mm = {shown} is outside the allowed range [0.001, 10000] mm"
    # Within a float but beyond 64 bits: the ordinary range error.
    with pytest.raises(impact.SceneError) as e:
        impact.Scene.from_dict(_set(paper_dict, "bodies[0].radius_mm", 10**30))
    assert e.value.field == "bodies[0].radius_mm" and e.value.value == 1e30
