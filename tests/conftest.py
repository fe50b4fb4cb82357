"""Shared fixtures: small CPUs and a helper to run programs against a panel of inputs."""

from __future__ import annotations

import pytest


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
