"""Random scene dicts into ``Scene.from_dict``: the shipped scenes (the default, a ``[signals]``
scene and an ``[ensemble]`` scene) with subtrees replaced by random values (nesting up to 40
deep, every Python and numpy type a user may hand over, cycles, non-string keys, huge and
non-finite numbers) and random keys added. Each dict is either a scene or refused with an
exception of Python's own hierarchy (``impact.SceneError`` or another ``Exception``), never a
crash: the cases run in a child interpreter, seeded, so that a crash fails the test and every
run sees the same dicts."""

from __future__ import annotations

import subprocess
import sys
import textwrap

from conftest import REPO

CASES = 400

CHILD = textwrap.dedent(
    """
    import math, random, sys, tomllib
    import numpy as np
    import impact

    rng = random.Random(int(sys.argv[1]))
    bases = []
    for path in sys.argv[2:]:
        with open(path, "rb") as f:
            bases.append(tomllib.load(f))

    class Odd:
        def __float__(self):
            raise RuntimeError("no float")

    def leaf():
        return rng.choice([
            lambda: rng.uniform(-1e3, 1e3),
            lambda: rng.choice([math.nan, math.inf, -math.inf, 5e-324, -0.0, 1e308, 0.0]),
            lambda: rng.randint(-(2**70), 2**70),
            lambda: rng.choice([True, False, None]),
            lambda: "".join(rng.choice("ab \\u00e9\\n\\x00[]{}") for _ in range(rng.randint(0, 12))),
            lambda: b"bytes",
            lambda: np.float32(rng.random()),
            lambda: np.int64(rng.randint(-5, 5)),
            lambda: np.array([rng.random(), math.nan]),
            lambda: np.datetime64("2024-01-01"),
            lambda: complex(1.0, 2.0),
            lambda: Odd(),
            lambda: {1, 2},
            lambda: (1.0, 2.0),
        ])()

    def tree(depth):
        if depth <= 0 or rng.random() < 0.3:
            return leaf()
        if rng.random() < 0.5:
            return [tree(depth - 1) for _ in range(rng.randint(0, 3))]
        keys = [rng.choice(["a", "x_mm", "modes", "name", 7, ("t",), ""]) for _ in range(rng.randint(0, 3))]
        return {k: tree(depth - 1) for k in keys}

    def places(d, path=(), seen=None):
        # Every path to a value, each container once (an earlier mutation may have made a cycle).
        seen = set() if seen is None else seen
        yield path
        if id(d) in seen or len(path) > 60:
            return
        if isinstance(d, (dict, list)):
            seen.add(id(d))
        if isinstance(d, dict):
            for k, v in list(d.items()):
                yield from places(v, path + (k,), seen)
        elif isinstance(d, list):
            for i, v in enumerate(d):
                yield from places(v, path + (i,), seen)

    def mutate(d):
        path = rng.choice(list(places(d))[1:])
        parent = d
        for k in path[:-1]:
            parent = parent[k]
        choice = rng.random()
        if choice < 0.6:
            parent[path[-1]] = tree(rng.randint(0, 40))
        elif choice < 0.75 and isinstance(parent, dict):
            del parent[path[-1]]
        elif choice < 0.9 and isinstance(parent, dict):
            parent[rng.choice(["unknown", 3, None])] = tree(3)
        else:
            parent[path[-1]] = parent  # a cycle

    import copy
    counts = {"accepted": 0, "refused": 0}
    for case in range(CASES):
        d = copy.deepcopy(rng.choice(bases))
        for _ in range(rng.randint(1, 3)):
            mutate(d)
        try:
            impact.Scene.from_dict(d)
            counts["accepted"] += 1
        except Exception as e:
            assert str(e), f"case {case}: {type(e).__name__} without a message"
            counts["refused"] += 1
    print(counts["accepted"], counts["refused"])
    """
)


def test_random_dicts_are_scenes_or_python_exceptions_never_a_crash():
    scenes = [REPO / "scenes" / n for n in ("paper-table-1.toml", "paper-signals.toml", "caving-stream.toml")]
    child = subprocess.run(
        [sys.executable, "-c", f"CASES = {CASES}\n" + CHILD, "20240611", *map(str, scenes)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert child.returncode == 0, f"the child interpreter ended with {child.returncode}:\n{child.stderr[-3000:]}"
    accepted, refused = map(int, child.stdout.split())
    assert accepted + refused == CASES
    # The mutations reach both sides: some leave a scene, most break it.
    assert refused > CASES // 2 and accepted > 0, (accepted, refused)
