"""Coal or gangue from the plate's response: a scikit-learn classifier on ensemble features.

    python python/examples/classify.py [--n 400] [--workers 2]

Runs a random impact ensemble (impact.ensemble over the transient model, sharded on a Dask
LocalCluster), keeps only what a sensor could measure (the contact force peak, the contact
time, the deflection, the impulse, the rebound), and prints per feature the ROC AUC of
coal against gangue, then the 5-fold cross-validated accuracy of a logistic regression on
all of them together. The ground truth the ensemble drew (radius, mass, velocity) is not a
feature.
"""

from __future__ import annotations

import argparse

import numpy as np
from dask.distributed import Client, LocalCluster
from sklearn.linear_model import LogisticRegression
from sklearn.metrics import roc_auc_score
from sklearn.model_selection import StratifiedKFold, cross_val_score
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler

import impact
import impact.shards as shards

FEATURES = ["peak_force_n", "contact_time_s", "deflection_m", "impulse_n_s", "apparent_restitution"]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=400, help="impacts (half coal, half gangue)")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--seed", type=int, default=2026)
    a = ap.parse_args()
    scene = impact.Scene.default()
    kw = dict(
        condition="Con 2",
        families=["coal", "gangue 1"],  # gangue 1 has the coal sphere's mass (Table 1)
        seed=a.seed,
        velocity_m_per_s=(0.002, 0.02),
        radius_spread=0.2,
        elements=12,
        steps_per_contact=100.0,
    )
    with LocalCluster(n_workers=a.workers, threads_per_worker=1, dashboard_address=None) as c, Client(c) as client:
        cols = shards.run_ensemble(client, scene, n=a.n, shard_size=25, **kw)
    y = cols["family"] != "coal"
    x = np.column_stack([cols[f] for f in FEATURES])
    keep = np.isfinite(x).all(axis=1)
    print(f"{a.n} impacts on {kw['condition']}, {int(keep.sum())} with every feature; "
          f"{int(cols['valid'].sum())} inside every validity criterion")
    print("ROC AUC, gangue against coal, per feature:")
    for j, f in enumerate(FEATURES):
        auc = roc_auc_score(y[keep], x[keep, j])
        print(f"  {f:<22} {max(auc, 1 - auc):.3f}")
    model = make_pipeline(StandardScaler(), LogisticRegression(max_iter=1000))
    folds = StratifiedKFold(n_splits=5, shuffle=True, random_state=0)
    acc = cross_val_score(model, x[keep], y[keep], cv=folds)
    print(f"logistic regression on all features, 5-fold CV accuracy: {acc.mean():.3f} ± {acc.std():.3f}")


if __name__ == "__main__":
    main()
