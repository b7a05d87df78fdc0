"""The bibliography (docs/references.md) and the citations gates and problems make.

A work is cited by its key in square brackets, "[gu-zhou2017] §5.1"; references.md
gives each work an anchor `<a id="gu-zhou2017"></a>` followed by its entry. The
report links every cited key to the full entry, which it lists at the end of the page.
"""
from __future__ import annotations

import html
import re
from dataclasses import dataclass
from pathlib import Path

from markupsafe import Markup

KEY = re.compile(r"\[([a-z][a-z0-9]*(?:-[a-z0-9]+)*)\]")
_ANCHOR = re.compile(r'<a\s+id="([^"]+)"\s*>\s*</a>')
_MD_LINK = re.compile(r"\[([^\]]+)\]\([^)]+\)")


@dataclass
class Reference:
    key: str
    text: str       # the entry as plain text (Markdown emphasis and links removed)


def plain(markdown: str) -> str:
    text = _MD_LINK.sub(r"\1", markdown)
    text = re.sub(r"\*\*?|__?|`", "", text)
    return " ".join(text.split())


def load_bibliography(path: Path) -> dict[str, Reference]:
    """Key → entry for every anchored entry of references.md (OSError if unreadable)."""
    source = path.read_text(encoding="utf-8")
    refs: dict[str, Reference] = {}
    anchors = list(_ANCHOR.finditer(source))
    for n, m in enumerate(anchors):
        end = anchors[n + 1].start() if n + 1 < len(anchors) else len(source)
        body = source[m.end():end]
        # The entry runs to the first blank line or heading after the anchor.
        lines = []
        for line in body.lstrip("\n").splitlines():
            if not line.strip() or line.startswith("#"):
                break
            lines.append(line)
        entry = plain(" ".join(lines))
        # The entry's own bold label ("[key]" or "key —"): the page shows the key separately.
        entry = re.sub(r"^\[?" + re.escape(m.group(1)) + r"\]?\s*(—\s*)?", "", entry)
        refs[m.group(1)] = Reference(m.group(1), entry)
    return refs


def cited_keys(text: str, refs: dict[str, Reference] | None = None) -> list[str]:
    """Keys cited in `text`, in order of first appearance. With `refs`, a bracketed word is
    a citation only if it is a known key or looks like one (has a year): "[m]" is a unit."""
    seen: list[str] = []
    for key in KEY.findall(text):
        if refs is not None and key not in refs and not any(c.isdigit() for c in key):
            continue
        if key not in seen:
            seen.append(key)
    return seen


def link_citations(text: str, refs: dict[str, Reference], escape_text: bool = True) -> Markup:
    """`text` with each known [key] turned into a link to its entry on the page."""
    body = html.escape(text, quote=False) if escape_text else text

    def link(m: re.Match) -> str:
        key = m.group(1)
        if key not in refs:
            return m.group(0)
        return f'<a class="cite" href="#ref-{key}" title="{html.escape(refs[key].text)}">[{key}]</a>'

    return Markup(KEY.sub(link, body))
