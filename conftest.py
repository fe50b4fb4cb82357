"""Collection settings: the shipped solutions and the corpus programs are PLC-subset files, not importable
modules."""

collect_ignore_glob = [
    "exercises/solutions/*",
    "docs/examples/*/solutions/*",
    "tests/corpus/*",
    "notebooks/*",
    "build/*",
]
