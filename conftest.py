"""Collection settings: the shipped solution programs are PLC-subset files, not importable modules."""

collect_ignore_glob = ["exercises/solutions/*", "notebooks/*", "build/*"]
