"""Turn loaded results into one self-contained HTML page, and write it atomically."""
from __future__ import annotations

import os
import re
import tempfile
from pathlib import Path

import jinja2
from markupsafe import Markup, escape

from . import numfmt
from .bibliography import cited_keys, link_citations
from .load import FAIL, MALFORMED, MISSING, OK, PASS, SKIPPED, Issue, Results, external_references
from .plots import plot_png

TEMPLATES = Path(__file__).resolve().parent.parent / "templates"


def render_plots(results: Results) -> None:
    """Draw every plot item; one that matplotlib cannot draw is marked MALFORMED."""
    for problem in results.problems:
        for item in problem.evidence:
            if item.status == OK and item.kind == "plot":
                try:
                    item.image, item.notes = plot_png(item.data)
                except Exception as e:  # matplotlib can fail in many ways on odd data
                    item.status = MALFORMED
                    item.message = f"could not be plotted: {type(e).__name__}: {e}"
                    results.issues.append(Issue(MALFORMED, item.path, item.message))


def anchor(name: str) -> str:
    """An HTML id for a problem section ("p-<id>") or an evidence item ("e-...")."""
    name = name if name.startswith("e-") else "p-" + name
    return re.sub(r"[^A-Za-z0-9_.-]", "-", name)


def breakable(name: str) -> Markup:
    """Long dotted ids may wrap after a dot or underscore, never inside a word."""
    return Markup(re.sub(r"([._/])", r"\1<wbr>", str(escape(name))))


def summary(results: Results, allow_missing: bool = False) -> dict:
    """Counts for the summary line and the exit status."""
    gates = results.gates
    counted = [i for i in results.issues if i.status == MALFORMED or not allow_missing]
    s = {
        "gates": len(gates),
        "passed": results.count(PASS),
        "failed": results.count(FAIL),
        "missing": results.count(MISSING),
        "skipped": results.count(SKIPPED),
        "malformed": results.count(MALFORMED),
        "sections_missing": sum(1 for p in results.problems if p.status == MISSING),
        "issues": len(results.issues),
        "blocking_issues": len(counted),
    }
    s["ok"] = s["failed"] == 0 and not counted
    return s


def summary_line(s: dict) -> str:
    line = (f"{s['gates']} gates: {s['passed']} passed, {s['failed']} failed, "
            f"{s['missing']} missing, {s['malformed']} malformed")
    if s["skipped"]:
        line += f"; {s['skipped']} recorded by another command (full tier, benchmarks), not run here"
    if s["sections_missing"]:
        line += f"; {s['sections_missing']} problem section(s) without results"
    if s["issues"]:
        line += f"; {s['issues']} issue(s) with result files"
    return line


def _environment() -> jinja2.Environment:
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(TEMPLATES),
        autoescape=True,
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
    )
    env.filters.update(num=numfmt.num, sortkey=numfmt.sort_key, rate=numfmt.rate,
                       duration=numfmt.duration, anchor=anchor, breakable=breakable,
                       count=lambda n, word: f"{n} {word}{'' if n == 1 else 's'}")
    env.globals.update(PASS=PASS, FAIL=FAIL, MALFORMED=MALFORMED, MISSING=MISSING, OK=OK, SKIPPED=SKIPPED)
    return env


def render_page(results: Results, s: dict, problems_dir: Path) -> str:
    env = _environment()
    refs = results.references
    # Gate sources are plain text (escaped here); problem texts are HTML already.
    def cite_with_entries(text: str) -> Markup:
        entries = "".join(f'<div class="ref">{escape(refs[k].text)}</div>' for k in cited_keys(text) if k in refs)
        return link_citations(text, refs) + Markup(entries)

    env.filters.update(cite=cite_with_entries, cite_html=lambda text: link_citations(text, refs, escape_text=False))
    page = env.get_template("page.html.j2").render(
        r=results,
        s=s,
        summary_line=summary_line(s),
        problems_dir=problems_dir,
        css=(TEMPLATES / "style.css").read_text(encoding="utf-8"),
        js=(TEMPLATES / "sort.js").read_text(encoding="utf-8"),
    )
    # Inputs are checked for network references on the way in; this is the last guard.
    refs = external_references(page)
    if refs:
        raise RuntimeError(f"the rendered page refers to network resources: {refs[:3]}")
    return page


def write_atomic(path: Path, content: str) -> None:
    """Write to a temporary file next to `path`, then rename over it: a reader (or a crash)
    sees the old page or the new one, never half a page."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(content)
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise
