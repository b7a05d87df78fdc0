#!/usr/bin/python3
"""Render pdmpm's verification results as one self-contained HTML page.

    /usr/bin/python3 reports/make_report.py [--results build/results] [--out build/report/index.html]

Reads <results>/gates/*.json, <results>/data/<problem>/*.json, <results>/provenance.json,
<results>/bench/*.json, the problem descriptions in reports/problems/*.toml, the papers'
claims in reports/claims.toml (shown first) and the bibliography docs/references.md (every gate's source cites a work by its [key]).
The page is written in every case (bad or missing input is marked on it).
Exit status: 0 all gates pass and nothing is malformed or missing; 1 a gate failed or
something is malformed/missing (or the page could not be written); 2 bad command line.
"""
from __future__ import annotations

import argparse
import html
import sys
import traceback
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from pdreport import claims, load, render  # noqa: E402


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog="make_report.py",
        description="Render the pdmpm verification report (one self-contained HTML page).")
    parser.add_argument("--results", type=Path, default=Path("build/results"), metavar="DIR",
                        help="results directory written by the gates (default: %(default)s)")
    parser.add_argument("--out", type=Path, default=Path("build/report/index.html"), metavar="FILE",
                        help="page to write (default: %(default)s)")
    parser.add_argument("--problems", type=Path, default=HERE / "problems", metavar="DIR",
                        help="problem descriptions, <problem>.toml (default: reports/problems)")
    parser.add_argument("--references", type=Path, default=HERE.parent / "docs" / "references.md", metavar="FILE",
                        help="bibliography every gate source cites by [key] (default: docs/references.md)")
    parser.add_argument("--claims", type=Path, default=HERE / "claims.toml", metavar="FILE",
                        help="published claims shown first, each judged by a gate (default: reports/claims.toml)")
    parser.add_argument("--allow-missing", action="store_true",
                        help="MISSING items are shown but do not make the exit status 1 "
                             "(for partial runs, e.g. the fast tier); FAIL and MALFORMED still do")
    args = parser.parse_args(argv)
    if args.out.exists() and args.out.is_dir():
        parser.error(f"--out {args.out} is a directory; give the file name of the page")
    if args.problems.exists() and not args.problems.is_dir():
        parser.error(f"--problems {args.problems} is not a directory")
    return args


def fallback_page(message: str) -> str:
    """Used only if rendering itself breaks: still leave a page that says so."""
    return ("<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>pdmpm report: error</title></head>"
            "<body><h1>pdmpm verification report could not be rendered</h1>"
            f"<pre>{html.escape(message)}</pre></body></html>\n")


def main(argv=None) -> int:
    args = parse_args(argv)
    try:
        results = load.load_results(args.results, args.problems, args.references)
        results.claims = claims.load_claims(args.claims, results)
        render.render_plots(results)
        summary = render.summary(results, allow_missing=args.allow_missing)
        page = render.render_page(results, summary, args.problems)
    except Exception as e:  # a bug in the report, not in the results: say so, keep a page
        traceback.print_exc()
        message = f"internal error while rendering: {type(e).__name__}: {e}"
        print(f"make_report: {message}", file=sys.stderr)
        try:
            render.write_atomic(args.out, fallback_page(message))
        except OSError:
            pass
        return 1

    for issue in results.issues:
        print(issue.line(), file=sys.stderr)
    for gate in results.gates:
        if gate.status == load.FAIL:
            print(f"make_report: FAIL: {gate.file}: {gate.claim}", file=sys.stderr)
    try:
        render.write_atomic(args.out, page)
    except OSError as e:
        print(f"make_report: cannot write {args.out}: {e.strerror or e}", file=sys.stderr)
        return 1
    status = "PASS" if summary["ok"] else "FAIL"
    print(f"make_report: {status}: {render.summary_line(summary)}")
    print(f"make_report: wrote {args.out}")
    return 0 if summary["ok"] else 1


if __name__ == "__main__":
    sys.exit(main())
