"""Coal or gangue from the support's response: a scikit-learn classifier on the features of
the scene's coal-gangue ensemble, beside the Rust identify report's AUCs and accuracies.

    python python/examples/classify.py [--scene scenes/paper-velocities-ensemble.toml]
        [--condition "Con 2"] [--impact target/release/impact] [--workers 2]

1. Runs `impact identify --json` on the scene (the Rust report: AUC ranking with bootstrap
   intervals, its own cross-validated classifiers).
2. Runs the same ensemble from Python as Dask shards (impact.shards.run_identify) and trains a
   scikit-learn logistic regression on every feature of the named sensors and the corners
   (standardised, log of the scale features), 5-fold stratified cross-validation.
3. Prints sklearn's accuracy beside the report's, and for the report's top features the AUC
   scikit-learn computes from the Python columns beside the report's: the same impacts, so
   the same numbers.
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import tempfile
import tomllib
from pathlib import Path

import numpy as np
from dask.distributed import Client, LocalCluster
from sklearn.linear_model import LogisticRegression
from sklearn.metrics import roc_auc_score
from sklearn.model_selection import StratifiedKFold, cross_val_score
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler

import impact
import impact.shards as shards


def point(channel: str) -> tuple[float, float]:
    """(x, z) in mm of a channel named like "acceleration at (305.6, 360) mm"."""
    m = re.search(r"at \(([-\d.]+), ([-\d.]+)\) mm", channel)
    if m is None:
        raise ValueError(f"no position in the channel name {channel!r}")
    return float(m[1]), float(m[2])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default="scenes/paper-velocities-ensemble.toml")
    ap.add_argument("--condition", default="Con 2")
    ap.add_argument("--impact", default="target/release/impact", help="the impact binary")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--shard-size", type=int, default=300)
    a = ap.parse_args()
    scene = impact.Scene.from_toml(a.scene)

    with tempfile.TemporaryDirectory() as tmp:
        out = subprocess.run(
            [a.impact, "identify", "--scene", a.scene, "--out", str(Path(tmp) / "identify"), "--json"],
            check=True, capture_output=True, text=True,
        )
    report = json.loads(out.stdout)
    rust = next(c for c in report["conditions"] if c["condition"] == a.condition)

    # The scene's named sensors, and the report's top-ranked points (from its placement grid), so
    # that its AUCs can be recomputed from the Python columns.
    named = [tuple(p) for p in tomllib.loads(Path(a.scene).read_text())["signals"]["sensors_mm"]]
    ranked = [point(r["channel"]) for r in rust["ranking"][:8]]
    sensors = list(dict.fromkeys(named + [p for p in ranked if p not in named]))
    with LocalCluster(n_workers=a.workers, threads_per_worker=1, dashboard_address=None) as c, Client(c) as client:
        cols = shards.run_identify(client, scene, a.condition, shard_size=a.shard_size, sensors_mm=sensors)
    y = cols["class"] == "gangue"
    at_named = tuple(f"at ({x:g}, {z:g}) mm" for x, z in named)
    corners = tuple(f"{q} at" for q in ("spring force", "reaction"))
    # The classifier sees the named sensors and the corners, as the report's "every named
    # sensor and corner channel" classifier does.
    features = [k for k in cols if ": " in k and (k.startswith(corners) or any(p in k for p in at_named))]
    x = np.column_stack([cols[k] for k in features])
    # Peaks, RMS and energies span decades: their logarithms are what a linear model can use.
    scale = np.array([any(f"{w} (" in k for w in ("peak", "rms", "energy")) for k in features])
    x[:, scale] = np.log10(np.abs(x[:, scale]) + 1e-300)
    n_coal, n_gangue = int((~y).sum()), int(y.sum())
    print(f"{scene.name} on {a.condition}: {len(y)} impacts ({n_coal} coal, {n_gangue} gangue), "
          f"{len(features)} features; {int(cols['valid'].sum())} inside the elastic range")

    model = make_pipeline(StandardScaler(), LogisticRegression(max_iter=2000))
    acc = cross_val_score(model, x, y, cv=StratifiedKFold(n_splits=5, shuffle=True, random_state=0))
    print(f"scikit-learn logistic regression, all features, 5-fold CV accuracy: {acc.mean():.3f} ± {acc.std():.3f}")
    for cl in rust["classifiers"]:
        r = cl["result"]
        print(f"Rust report's logistic regression ({cl['features']}), {r['folds']}-fold CV accuracy: "
              f"{r['accuracy']:.3f} ± {r['standard_error']:.3f}")

    print("top features of the Rust report: its AUC [95 % bootstrap] | scikit-learn's AUC from the Python columns")
    for rk in rust["ranking"][:8]:
        key = f"{rk['channel']}: {rk['feature'].replace('-', '_')} ("
        col = next((k for k in cols if k.startswith(key)), None)
        ours = roc_auc_score(y, cols[col]) if col else float("nan")
        lo, hi = rk["interval"]
        print(f"  {rk['channel']}: {rk['feature']:<20} {rk['auc']['auc']:.4f} [{lo:.3f}, {hi:.3f}] | {ours:.4f}")
    for name, col in (("force_max", "force_max_N"), ("contact_time", "contact_time_s")):
        rk = rust[name]
        print(f"  {name:<50} {rk['auc']['auc']:.4f} [{rk['interval'][0]:.3f}, {rk['interval'][1]:.3f}] | "
              f"{roc_auc_score(y, np.nan_to_num(cols[col], nan=0.0)):.4f}")


if __name__ == "__main__":
    main()
