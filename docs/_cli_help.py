"""An mkdocs hook for the API site (``mkdocs.yml``): the command-line page shows the ``--help`` of
``plcsim`` and of each subcommand, taken from the parser when the site is built, so it cannot drift.

A page asks for it with the line ``<!-- plcsim --help -->``.
"""

from __future__ import annotations

import argparse
from typing import Any

MARK = "<!-- plcsim --help -->"


def cli_help() -> str:
    """Markdown: the help of ``plcsim`` and of every subcommand, as code blocks 80 columns wide (the page's)."""
    from plcsim.apps.cli import build_parser

    parser = build_parser()
    sections = [("plcsim", parser)]
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            sections += [(f"plcsim {name}", sub) for name, sub in action.choices.items()]
    out = []
    for title, command in sections:
        command.formatter_class = lambda prog: argparse.HelpFormatter(prog, width=80)
        out += [f"## `{title}`", "", "```text", command.format_help().rstrip(), "```", ""]
    return "\n".join(out)


def on_page_markdown(markdown: str, **kwargs: Any) -> str:
    return markdown.replace(MARK, cli_help()) if MARK in markdown else markdown
