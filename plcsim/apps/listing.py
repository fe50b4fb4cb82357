"""``plcsim list --profiles``: the registered CPU profiles and the front ends whose programs run on each."""

from __future__ import annotations

from rich.console import Console

from plcsim import frontends
from plcsim.controllers.profiles import Profile, all_profiles
from plcsim.core.console_table import print_records


def profile_rows(profiles: list[Profile] | None = None) -> list[dict[str, str]]:
    """One row of plain text per profile (what the table shows)."""
    by_profile: dict[str, list[str]] = {}
    for front in frontends.front_ends():
        by_profile.setdefault(front.profile.lower(), []).append(f"{front.suffix} ({front.language or 'unnamed'})")
    return [
        {
            "profile": p.name,
            "family": p.family,
            "memory": ", ".join(f"{a.name} ({a.examples[0]})" for a in p.areas) + f"; {p.byte_order}-endian",
            "tasks": "; ".join(f"{t.tasks} {t.kind}" for t in p.triggers),
            "restarts": ", ".join(r.name for r in p.restarts),
            "instructions": str(len(p.instructions())),
            "front ends": ", ".join(by_profile.get(p.name.lower(), [])) or "-",
        }
        for p in (all_profiles() if profiles is None else profiles)
    ]


def print_profiles(console: Console | None = None) -> None:
    """Print :func:`profile_rows` as a table (as a list where a table would cut a name)."""
    rows = profile_rows()
    columns = list(rows[0]) if rows else ["profile"]
    print_records(console or Console(), columns, [list(row.values()) for row in rows], title="CPU profiles")
