"""Shared fixtures: the repository's files (scenes, the paper's printed tables, the
scikit-fem reference data) and the command-line binary."""

from __future__ import annotations

import copy
import os
import tomllib
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


def paper_scene_dict() -> dict:
    """The embedded default scene (the paper's Table 1) as a dict, to modify per test."""
    with open(REPO / "scenes" / "paper-table-1.toml", "rb") as f:
        return tomllib.load(f)


@pytest.fixture
def paper_dict() -> dict:
    return copy.deepcopy(paper_scene_dict())


def impact_binary() -> Path | None:
    """The `impact` binary: $IMPACT_BIN, else the release build of this clone."""
    given = os.environ.get("IMPACT_BIN")
    path = Path(given) if given else REPO / "target" / "release" / "impact"
    return path if path.is_file() else None
