"""Shared fixtures: small CPUs and a helper to run programs against a panel of inputs."""

from __future__ import annotations

import sys

import pytest


@pytest.fixture(autouse=True)
def _sys_path_restored():
    """A test that loads an instructor's folder by path (``load_path`` appends it to ``sys.path``) must not
    leave it there: a later test that hands ``sys.path`` to a child would import that folder's files."""
    saved = list(sys.path)
    yield
    sys.path[:] = saved


@pytest.fixture
def panel_tags():
    """The textbook's panel: TL/TLACIDLO buttons on %I0.x, LED on %Q0.0."""
    from plcsim import Tag

    return {
        "TL": Tag("%I0.0"),
        "TLACIDLO": Tag("%I0.1"),
        "PREPINAC": Tag("%I0.2"),
        "LED": Tag("%Q0.0"),
    }
