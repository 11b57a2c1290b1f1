"""Scene dicts that once killed the interpreter (SIGSEGV by unbounded recursion): cycles,
nesting 100,000 deep, an object whose ``tolist()`` returns itself, numpy's long double; and
every numpy scalar type, each taken as its Python value or refused with a ``TypeError``
naming the field. Each case runs in a child interpreter, so that a crash is a failed test
and not the end of the suite."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import impact

REPO = Path(__file__).resolve().parents[2]

PRELUDE = textwrap.dedent(
    """
    import copy, sys, tomllib
    import numpy as np
    import impact
    sys.setrecursionlimit(1_000_000)
    with open(sys.argv[1], "rb") as f:
        d = tomllib.load(f)
    """
)


def run_child(body: str, scene_path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-c", PRELUDE + textwrap.dedent(body), str(scene_path)],
        capture_output=True,
        text=True,
        timeout=120,
    )


HOSTILE = {
    "self-referential list": "x = [1.0]; x.append(x); d['velocities']['m_per_s'] = x",
    "self-referential dict": "d['plate']['me'] = d['plate']",
    "dict containing the root": "d['plate']['root'] = d",
    "list nested 100,000 deep": "x = 1.0\nfor _ in range(100_000): x = [x]\nd['velocities']['m_per_s'] = x",
    "dict nested 100,000 deep": "x = 1.0\nfor _ in range(100_000): x = {'a': x}\nd['plate']['length_mm'] = x",
    "tolist returns itself": "class T:\n    def tolist(self): return self\nd['plate']['length_mm'] = T()",
    "tolist returns a fresh one": "class T:\n    def tolist(self): return T()\nd['plate']['length_mm'] = T()",
    "list subclass iterating for ever": "class L(list):\n    def __iter__(self):\n        while True: yield 1.0\nd['velocities']['m_per_s'] = L([0.008])",
    "object array holding itself": "a = np.empty(1, dtype=object); a[0] = a; d['velocities']['m_per_s'] = a",
}


@pytest.mark.parametrize("name", sorted(HOSTILE))
def test_hostile_dicts_are_refused_naming_the_field_not_a_crash(name):
    body = HOSTILE[name] + textwrap.dedent(
        """
        try:
            impact.Scene.from_dict(d)
        except impact.SceneError as e:
            print("REFUSED", e.field, "|", e)
        else:
            print("ACCEPTED")
        """
    )
    r = run_child(body, REPO / "scenes" / "paper-table-1.toml")
    assert r.returncode == 0, f"{name}: exit {r.returncode}\n{r.stderr[-2000:]}"
    out = r.stdout.strip()
    if name == "list subclass iterating for ever":
        # Its own items are read, never its __iter__.
        assert out == "ACCEPTED", out
        return
    assert out.startswith("REFUSED"), out
    assert any(k in out for k in ("contains itself", "nested more than 32")), out
    assert "| scene <dict>: " in out and out.split()[1] != "None", out


def test_depth_and_cycle_messages_name_the_path(paper_dict):
    x = [0.008]
    x.append(x)
    paper_dict["velocities"]["m_per_s"] = x
    with pytest.raises(impact.SceneError) as e:
        impact.Scene.from_dict(paper_dict)
    assert e.value.field == "velocities.m_per_s[1]" and "contains itself" in str(e.value)
    deep = 0.008
    for _ in range(40):
        deep = [deep]
    paper_dict["velocities"]["m_per_s"] = deep
    with pytest.raises(impact.SceneError) as e:
        impact.Scene.from_dict(paper_dict)
    assert e.value.field.startswith("velocities.m_per_s[0]") and "nested more than 32" in str(e.value)


# Every numpy scalar type: (value, accepted as) or the words of its refusal.
ACCEPTED = [
    np.float16(0.5), np.float32(0.5), np.float64(0.5), np.longdouble(0.5),
    np.int8(3), np.int16(3), np.int32(3), np.int64(3), np.uint8(3), np.uint16(3), np.uint32(3), np.uint64(3),
    np.array(0.5), np.array(0.5, dtype=np.longdouble),
]
REFUSED = [
    np.complex64(0.5), np.complex128(0.5), np.clongdouble(0.5), complex(0.5, 0.0),
    np.datetime64("2020-01-01"), np.timedelta64(1, "s"), np.bytes_(b"x"), np.void(b"x"),
]


@pytest.mark.parametrize("value", ACCEPTED, ids=lambda v: type(v).__name__ + "-" + str(getattr(v, "dtype", "")))
def test_numpy_numbers_are_their_python_values(paper_dict, value):
    paper_dict["velocities"]["m_per_s"] = [value]
    s = impact.Scene.from_dict(paper_dict)
    assert s.velocities_m_per_s == [float(value)]


@pytest.mark.parametrize("value", ACCEPTED, ids=lambda v: type(v).__name__)
def test_numpy_numbers_out_of_range_name_the_field(paper_dict, value):
    paper_dict["plate"]["thickness_mm"] = value * 0
    with pytest.raises(impact.SceneError) as e:
        impact.Scene.from_dict(paper_dict)
    assert e.value.field == "plate.thickness_mm", str(e.value)


@pytest.mark.parametrize("value", REFUSED, ids=lambda v: type(v).__name__)
def test_other_numpy_scalars_are_type_errors_naming_the_field(paper_dict, value):
    paper_dict["plate"]["thickness_mm"] = value
    with pytest.raises(TypeError) as e:
        impact.Scene.from_dict(paper_dict)
    err = e.value
    assert isinstance(err, impact.SceneError) and isinstance(err, impact.SceneTypeError)
    assert err.field == "plate.thickness_mm" and "of type" in str(err), str(err)


def test_numpy_bools_and_strings(paper_dict):
    paper_dict["name"] = np.str_("numpy name")
    assert impact.Scene.from_dict(paper_dict).name == "numpy name"
    paper_dict["velocities"]["m_per_s"] = np.bool_(True)
    with pytest.raises(impact.SceneError) as e:
        impact.Scene.from_dict(paper_dict)
    assert e.value.field == "velocities.m_per_s"


def test_a_long_double_beyond_a_float_names_its_field(paper_dict):
    big = np.longdouble("1e4000")
    if not np.isfinite(big):
        pytest.skip("this platform's long double is a double")
    paper_dict["plate"]["thickness_mm"] = big
    with pytest.raises(impact.SceneError) as e:
        impact.Scene.from_dict(paper_dict)
    assert e.value.field == "plate.thickness_mm" and "1e+4000" in str(e.value), str(e.value)
