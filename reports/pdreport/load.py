"""Reading and checking everything the report shows.

Nothing in this module lets bad input escape as an exception: a file that cannot be
read, or does not have the shape the report needs, becomes an Issue (one line on
stderr) and the item it belongs to is marked MALFORMED or MISSING, so the page can
still be written and says what is wrong.
"""
from __future__ import annotations

import base64
import json
import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from .bibliography import Reference, cited_keys, load_bibliography

PASS, FAIL, MALFORMED, MISSING, OK = "PASS", "FAIL", "MALFORMED", "MISSING", "OK"
# A gate its problem says another command records (the full tier, ci/bench.sh), absent
# from these results: shown, counted apart, not an issue.
SKIPPED = "SKIPPED"
COMPARES = ("abs", "rel", "at_most", "at_least")
PLOT_STYLES = ("line", "points", "dashed")
SCALES = ("linear", "log")

# src=/href= or CSS url()/@import pointing off the page (http:, https:, protocol-relative //).
_EXTERNAL = re.compile(
    r"""(?:\b(?:src|href|srcset|action|poster|data)\s*=\s*["']?\s*(?:[a-z][a-z0-9+.-]*:)?//)"""
    r"""|(?:url\(\s*["']?\s*(?:[a-z][a-z0-9+.-]*:)?//)|(?:@import)""",
    re.IGNORECASE)


def external_references(html: str) -> list[str]:
    """Snippets of `html` that would load something from the network."""
    return [m.group(0) for m in _EXTERNAL.finditer(html)]


class Bad(Exception):
    """A file's content does not have the shape the report needs; the message says how."""


@dataclass
class Issue:
    status: str          # MALFORMED or MISSING
    path: str            # file (or directory) the issue is about, as shown to the user
    message: str

    def line(self) -> str:
        return f"make_report: {self.status}: {self.path}: {self.message}"


@dataclass
class Gate:
    id: str
    file: str
    status: str                 # PASS, FAIL, MALFORMED or MISSING
    claim: str = ""
    measured: float | str | None = None   # a number, "non-finite", or None if unreadable
    expected: float | None = None
    tolerance: float | None = None
    compare: str = ""
    tolerance_reason: str = ""
    source: str = ""
    unit: str = ""
    problem: str = ""
    test: str = ""
    message: str = ""           # why MALFORMED or MISSING

    def deviation(self) -> float | None:
        """The quantity the tolerance applies to: |Δ| (abs), |Δ|/|expected| (rel), or the
        signed margin to the bound (at_most/at_least; negative means the bound is crossed)."""
        if not (is_number(self.measured) and is_number(self.expected)) or not math.isfinite(self.measured):
            return None
        diff = self.measured - self.expected
        if self.compare == "abs":
            return abs(diff)
        if self.compare == "rel":
            return abs(diff) / abs(self.expected) if self.expected != 0 else None
        if self.compare == "at_most":
            return -diff
        if self.compare == "at_least":
            return diff
        return None


@dataclass
class Evidence:
    file: str                   # file name inside data/<problem>/
    path: str                   # path shown in messages
    kind: str = ""
    status: str = OK            # OK, MALFORMED or MISSING
    title: str = ""
    caption: str = ""
    data: dict = field(default_factory=dict)   # the checked JSON object
    image: str = ""             # data: URI of an image or rendered plot
    notes: list[str] = field(default_factory=list)
    message: str = ""


@dataclass
class Problem:
    id: str
    title: str
    has_toml: bool = False
    summary: str = ""
    equations: list[str] = field(default_factory=list)
    parameters: list[tuple[str, object]] = field(default_factory=list)
    order: int = 1000
    expected_gates: list[str] = field(default_factory=list)
    recorded_by: dict[str, str] = field(default_factory=dict)  # gate id → the command that records it
    status: str = OK            # OK, MALFORMED (its toml) or MISSING (no results)
    message: str = ""
    gates: list[Gate] = field(default_factory=list)
    evidence: list[Evidence] = field(default_factory=list)


@dataclass
class BenchFile:
    file: str
    status: str = OK
    message: str = ""
    context: dict = field(default_factory=dict)
    rows: list[dict] = field(default_factory=list)

    def counter_names(self) -> list[str]:
        """User counters over all rows, in first-seen order (one column each)."""
        names: list[str] = []
        for row in self.rows:
            names += [k for k in row["counters"] if k not in names]
        return names


@dataclass
class Results:
    root: Path
    found: bool
    provenance: dict = field(default_factory=dict)
    provenance_status: str = MISSING
    gates: list[Gate] = field(default_factory=list)
    problems: list[Problem] = field(default_factory=list)
    bench: list[BenchFile] = field(default_factory=list)
    issues: list[Issue] = field(default_factory=list)
    references: dict[str, Reference] = field(default_factory=dict)  # the bibliography, by key
    claims: list = field(default_factory=list)  # the published claims (claims.py), judged

    def cited(self) -> list[Reference]:
        """The works the page cites (gate sources, problem texts), in bibliography order."""
        keys = set()
        for g in self.gates:
            keys.update(cited_keys(g.source, self.references))
        for p in self.problems:
            keys.update(cited_keys(p.summary + " ".join(p.equations), self.references))
        keys.update(c.paper for c in self.claims)
        return [ref for key, ref in self.references.items() if key in keys]

    def count(self, status: str) -> int:
        return sum(1 for g in self.gates if g.status == status)


# --- small checks ---------------------------------------------------------------------

def is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def read_json(path: Path):
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        raise Bad("not UTF-8 text") from None
    except OSError as e:
        raise Bad(f"cannot read ({e.strerror or e})") from None
    if not text.strip():
        raise Bad("empty file")
    try:
        return json.loads(text)
    except json.JSONDecodeError as e:
        raise Bad(f"invalid JSON at line {e.lineno} column {e.colno}: {e.msg}") from None
    except RecursionError:
        raise Bad("invalid JSON: nested too deeply") from None


def need_object(obj, what="the file") -> dict:
    if not isinstance(obj, dict):
        raise Bad(f"{what} must be a JSON object, found {type_name(obj)}")
    return obj


def type_name(v) -> str:
    return {dict: "an object", list: "a list", str: "a string", bool: "true/false",
            type(None): "null", int: "a number", float: "a number"}.get(type(v), type(v).__name__)


def text(obj: dict, key: str, required: bool = True, where: str = "") -> str:
    if key not in obj:
        if required:
            raise Bad(f'missing "{key}"{where}')
        return ""
    if not isinstance(obj[key], str):
        raise Bad(f'"{key}"{where} must be a string, found {type_name(obj[key])}')
    return obj[key]


def choice(obj: dict, key: str, allowed, default=None, where: str = "") -> str:
    value = text(obj, key, required=default is None, where=where) or default
    if value not in allowed:
        raise Bad(f'"{key}"{where} is "{value}", expected one of {", ".join(allowed)}')
    return value


def no_external(html: str, what: str) -> str:
    refs = external_references(html)
    if refs:
        raise Bad(f"{what} refers to a network resource ({refs[0]!r}); the report must be self-contained")
    return html


# --- gates ------------------------------------------------------------------------------

def gate_passes(measured, expected: float, tolerance: float, compare: str) -> bool:
    """Same rule as passes() in verification/support/gate.cpp."""
    if not is_number(measured) or not math.isfinite(measured):
        return False
    if compare == "abs":
        return abs(measured - expected) <= tolerance
    if compare == "rel":
        return abs(measured - expected) <= tolerance * abs(expected)
    if compare == "at_most":
        return measured <= expected
    if compare == "at_least":
        return measured >= expected
    return False


def load_gate(path: Path, shown: str) -> Gate:
    gate = Gate(id=path.stem, file=shown, status=MALFORMED)
    try:
        obj = need_object(read_json(path))
        # Keep whatever is readable, so even a malformed row shows what it can.
        for key in ("claim", "compare", "tolerance_reason", "source", "unit", "problem", "test"):
            if isinstance(obj.get(key), str):
                setattr(gate, key, obj[key])
        for key in ("measured", "expected", "tolerance"):
            if is_number(obj.get(key)):
                setattr(gate, key, float(obj[key]))
        if obj.get("measured") == "non-finite":
            gate.measured = "non-finite"

        gate_id = text(obj, "id")
        if gate_id != path.stem:
            raise Bad(f'"id" is "{gate_id}" but the file is named {path.name}')
        for key in ("claim", "tolerance_reason", "source", "unit", "problem", "test"):
            text(obj, key)
        if not gate.claim.strip():
            raise Bad('"claim" is empty')
        if not gate.tolerance_reason.strip():
            raise Bad('"tolerance_reason" is empty (every tolerance needs its reason)')
        if not gate.source.strip():
            raise Bad('"source" is empty')
        if not (is_number(obj.get("measured")) or obj.get("measured") == "non-finite"):
            raise Bad('"measured" must be a number or "non-finite"' if "measured" in obj else 'missing "measured"')
        for key in ("expected", "tolerance"):
            if key not in obj:
                raise Bad(f'missing "{key}"')
            if not is_number(obj[key]) or not math.isfinite(obj[key]):
                raise Bad(f'"{key}" must be a finite number, found {obj[key]!r}')
        if gate.tolerance < 0:
            raise Bad(f'"tolerance" is negative ({gate.tolerance})')
        choice(obj, "compare", COMPARES)
        verdict = choice(obj, "verdict", (PASS, FAIL))
        recomputed = PASS if gate_passes(gate.measured, gate.expected, gate.tolerance, gate.compare) else FAIL
        if verdict != recomputed:
            raise Bad(f"verdict {verdict} disagrees with its own numbers, which give {recomputed}")
        gate.status = verdict
    except Bad as e:
        gate.message = str(e)
    return gate


# --- evidence ---------------------------------------------------------------------------

def check_table(obj: dict) -> None:
    columns = obj.get("columns")
    if not isinstance(columns, list) or not columns:
        raise Bad('"columns" must be a non-empty list')
    if not all(isinstance(c, str) for c in columns):
        raise Bad('"columns" must be strings')
    rows = obj.get("rows")
    if not isinstance(rows, list):
        raise Bad('"rows" must be a list of rows')
    for i, row in enumerate(rows):
        if not isinstance(row, list) or len(row) != len(columns):
            raise Bad(f"row {i} must be a list of {len(columns)} cells, found {type_name(row)}"
                      + (f" of {len(row)}" if isinstance(row, list) else ""))
        for cell in row:
            if not (cell is None or isinstance(cell, (str, int, float, bool))):
                raise Bad(f"row {i} has a cell that is {type_name(cell)}; cells are numbers, strings or null")


def check_plot(obj: dict) -> None:
    for key in ("xlabel", "ylabel"):
        text(obj, key, required=False)
    choice(obj, "xscale", SCALES, default="linear")
    choice(obj, "yscale", SCALES, default="linear")
    series = obj.get("series")
    if not isinstance(series, list) or not series:
        raise Bad('"series" must be a non-empty list')
    for i, s in enumerate(series):
        where = f" in series {i}"
        need_object(s, f"series {i}")
        text(s, "label", required=False, where=where)
        choice(s, "style", PLOT_STYLES, default="line", where=where)
        x, y = s.get("x"), s.get("y")
        if not isinstance(x, list) or not isinstance(y, list):
            raise Bad(f'"x" and "y"{where} must be lists of numbers')
        if len(x) != len(y):
            raise Bad(f'"x" has {len(x)} values but "y" has {len(y)}{where}')
        if not x:
            raise Bad(f"series {i} has no points")
        for v in x + y:
            if v is not None and not is_number(v):   # null stands for a non-finite value
                raise Bad(f"series {i} has a value that is {type_name(v)}; values are numbers or null")
        for key in ("ylo", "yhi"):                   # optional error bar ends, one per point
            if key not in s:
                continue
            bar = s[key]
            if not isinstance(bar, list) or len(bar) != len(y):
                raise Bad(f'"{key}"{where} must be a list as long as "y" ({len(y)} values)')
            if any(v is not None and not is_number(v) for v in bar):
                raise Bad(f'"{key}"{where} must hold numbers or null')
        if ("ylo" in s) != ("yhi" in s):
            raise Bad(f'"ylo" and "yhi"{where} come together')
    xticks = obj.get("xticks")
    if xticks is not None:                            # optional: category labels at given x
        need_object(xticks, '"xticks"')
        values, labels = xticks.get("values"), xticks.get("labels")
        if (not isinstance(values, list) or not isinstance(labels, list) or len(values) != len(labels)
                or not all(is_number(v) for v in values) or not all(isinstance(t, str) for t in labels)):
            raise Bad('"xticks" must have "values" (numbers) and "labels" (strings) of equal length')


_IMAGE_TYPES = {b"\x89PNG\r\n\x1a\n": "image/png", b"\xff\xd8\xff": "image/jpeg"}


def load_image(obj: dict, root: Path) -> str:
    """Returns the image as a data: URI; raises FileNotFoundError if the file is absent."""
    rel = text(obj, "path")
    path = root / rel
    if not path.is_file():
        raise FileNotFoundError(rel)
    try:
        raw = path.read_bytes()
    except OSError as e:
        raise Bad(f"cannot read image {rel} ({e.strerror or e})") from None
    for magic, mime in _IMAGE_TYPES.items():
        if raw.startswith(magic):
            return f"data:{mime};base64,{base64.b64encode(raw).decode('ascii')}"
    raise Bad(f"image {rel} is not a PNG or JPEG file")


def load_evidence(path: Path, shown: str, root: Path) -> Evidence:
    item = Evidence(file=path.name, path=shown, status=MALFORMED)
    try:
        obj = need_object(read_json(path))
        item.kind = text(obj, "kind")
        item.title = text(obj, "title", required=False) or path.stem
        item.caption = text(obj, "caption", required=False)
        if item.kind == "table":
            check_table(obj)
        elif item.kind == "plot":
            check_plot(obj)
        elif item.kind == "image":
            item.image = load_image(obj, root)
        elif item.kind == "text":
            no_external(text(obj, "html"), '"html"')
        else:
            raise Bad(f'unknown "kind" "{item.kind}" (expected table, plot, image or text)')
        item.data = obj
        item.status = OK
    except Bad as e:
        item.message = str(e)
    except FileNotFoundError as e:
        item.status = MISSING
        item.message = f"image file {e.args[0]} not found in the results directory"
    return item


# --- problem descriptions ---------------------------------------------------------------

_TOML_KEYS = {"id", "title", "summary", "equations", "parameters", "order", "gates", "recorded_by"}


def load_problem_toml(path: Path) -> Problem:
    problem = Problem(id=path.stem, title=path.stem, has_toml=True)
    try:
        try:
            with path.open("rb") as f:
                doc = tomllib.load(f)
        except tomllib.TOMLDecodeError as e:
            raise Bad(f"invalid TOML: {e}") from None
        except UnicodeDecodeError:
            raise Bad("not UTF-8 text") from None
        except OSError as e:
            raise Bad(f"cannot read ({e.strerror or e})") from None
        unknown = sorted(set(doc) - _TOML_KEYS)
        if unknown:
            raise Bad(f"unknown key(s) {', '.join(unknown)}; allowed: {', '.join(sorted(_TOML_KEYS))}")
        pid = text(doc, "id")
        if pid != path.stem:
            raise Bad(f'"id" is "{pid}" but the file is named {path.name}')
        problem.title = text(doc, "title")
        problem.summary = no_external(text(doc, "summary", required=False), '"summary"')
        equations = doc.get("equations", [])
        if not isinstance(equations, list) or not all(isinstance(e, str) for e in equations):
            raise Bad('"equations" must be a list of strings')
        problem.equations = [no_external(e, "an equation") for e in equations]
        parameters = doc.get("parameters", [])
        if not isinstance(parameters, list):
            raise Bad('"parameters" must be a list of [name, value] pairs')
        for p in parameters:
            if not (isinstance(p, list) and len(p) == 2 and isinstance(p[0], str)
                    and (isinstance(p[1], str) or is_number(p[1]))):
                raise Bad(f'parameter {p!r} must be [name, value] with a string name and a string or number value')
        problem.parameters = [(p[0], p[1]) for p in parameters]
        order = doc.get("order", 1000)
        if not isinstance(order, int) or isinstance(order, bool):
            raise Bad('"order" must be an integer')
        problem.order = order
        gates = doc.get("gates", [])
        if not isinstance(gates, list) or not all(isinstance(g, str) for g in gates):
            raise Bad('"gates" must be a list of gate ids')
        problem.expected_gates = gates
        recorded_by = doc.get("recorded_by", {})
        if not isinstance(recorded_by, dict) or not all(isinstance(v, str) for v in recorded_by.values()):
            raise Bad('"recorded_by" must be a table of gate id = "the command that records it"')
        strays = sorted(set(recorded_by) - set(gates))
        if strays:
            raise Bad(f'"recorded_by" names gate(s) not in "gates": {", ".join(strays)}')
        problem.recorded_by = recorded_by
    except Bad as e:
        problem.status = MALFORMED
        problem.message = str(e)
    return problem


# --- provenance and benchmarks ---------------------------------------------------------

_PROVENANCE_TEXT = ("git_sha", "tree", "date", "compiler", "flags", "cpu")


def load_provenance(path: Path) -> dict:
    obj = need_object(read_json(path))
    for key in _PROVENANCE_TEXT:
        text(obj, key)
    choice(obj, "tree", ("clean", "dirty", "unknown"))
    text(obj, "simd", required=False)  # results written before it was recorded have none
    if not isinstance(obj.get("threads"), int) or isinstance(obj.get("threads"), bool):
        raise Bad('"threads" must be an integer' if "threads" in obj else 'missing "threads"')
    return obj


# Keys of a Google Benchmark JSON run that are not user counters.
_BENCH_FIELDS = {
    "name", "family_index", "per_family_instance_index", "run_name", "run_type", "repetitions",
    "repetition_index", "threads", "iterations", "real_time", "cpu_time", "time_unit",
    "aggregate_name", "aggregate_unit", "label", "error_occurred", "error_message",
    "items_per_second", "bytes_per_second", "big_o", "rms", "cpu_coefficient", "real_coefficient",
}


def load_bench(path: Path, shown: str) -> BenchFile:
    bench = BenchFile(file=shown, status=MALFORMED)
    try:
        obj = need_object(read_json(path))
        context = obj.get("context", {})
        bench.context = need_object(context, '"context"')
        runs = obj.get("benchmarks")
        if not isinstance(runs, list):
            raise Bad('"benchmarks" must be a list (is this Google Benchmark JSON output?)')
        for i, run in enumerate(runs):
            need_object(run, f"benchmark {i}")
            row = {"name": text(run, "name", where=f" in benchmark {i}"),
                   "run_type": run.get("run_type", ""),
                   "aggregate": run.get("aggregate_name", ""),
                   "aggregate_unit": run.get("aggregate_unit", "time"),
                   "iterations": run.get("iterations"),
                   "threads": run.get("threads"),
                   "time_unit": run.get("time_unit", "ns"),
                   "error": run.get("error_message", "error") if run.get("error_occurred") else "",
                   "label": run.get("label", "")}
            for key in ("real_time", "cpu_time", "items_per_second", "bytes_per_second"):
                value = run.get(key)
                if value is not None and not is_number(value):
                    raise Bad(f'"{key}" in benchmark {i} must be a number')
                row[key] = value
            if not row["error"] and row["real_time"] is None:
                raise Bad(f'benchmark {i} ({row["name"]}) has no "real_time"')
            row["counters"] = {k: v for k, v in run.items() if k not in _BENCH_FIELDS and is_number(v)}
            bench.rows.append(row)
        bench.status = OK
    except Bad as e:
        bench.message = str(e)
        bench.rows = []
    return bench


# --- the whole results directory --------------------------------------------------------

def json_files(directory: Path) -> list[Path]:
    """*.json files of a directory in name order (leftover *.json.tmp files are ignored)."""
    if not directory.is_dir():
        return []
    return sorted(p for p in directory.iterdir() if p.suffix == ".json" and not p.name.startswith("."))


def check_citations(results: Results, references_path: Path) -> None:
    """Every gate's source names a bibliography key, and every key cited anywhere exists."""
    def issue(status: str, path: str, message: str) -> None:
        results.issues.append(Issue(status, path, message))

    try:
        results.references = load_bibliography(references_path)
    except (OSError, UnicodeDecodeError) as e:
        issue(MISSING, str(references_path), f"no bibliography ({getattr(e, 'strerror', None) or e}); "
              "citations are not checked")
        return
    for g in results.gates:
        if g.status not in (PASS, FAIL):  # unreadable, or not recorded here: said already
            continue
        keys = cited_keys(g.source, results.references)
        if not keys:
            issue(MALFORMED, g.file, f'"source" names no bibliography key ([key] of {references_path.name}): '
                  f"{g.source[:80]!r}")
        for key in keys:
            if key not in results.references:
                issue(MALFORMED, g.file, f"source cites [{key}], which {references_path.name} does not list")
    for p in results.problems:
        for key in cited_keys(p.summary + " ".join(p.equations), results.references):
            if key not in results.references:
                issue(MALFORMED, f"{p.id}.toml", f"cites [{key}], which {references_path.name} does not list")


def load_results(root: Path, problems_dir: Path, references_path: Path | None = None) -> Results:
    """Everything the page shows; with `references_path`, citations are checked against it."""
    results = _load_results(root, problems_dir)
    if references_path is not None and results.found:
        check_citations(results, references_path)
    return results


def _load_results(root: Path, problems_dir: Path) -> Results:
    results = Results(root=root, found=root.is_dir())
    problems: dict[str, Problem] = {}

    def issue(status: str, path: str, message: str) -> None:
        results.issues.append(Issue(status, path, message))

    for path in sorted(problems_dir.glob("*.toml")):
        p = load_problem_toml(path)
        problems[p.id] = p
        if p.status == MALFORMED:
            issue(MALFORMED, str(path), p.message)

    def problem(pid: str) -> Problem:
        if pid not in problems:
            problems[pid] = Problem(id=pid, title=pid,
                                    message=f"no description: add {problems_dir.name}/{pid}.toml")
        return problems[pid]

    if not results.found:
        what = "is not a directory" if root.exists() else "does not exist"
        issue(MISSING, str(root), f"results directory {what}; build and run the gates first")
        for p in problems.values():
            if p.status == OK:
                p.status, p.message = MISSING, "no results directory"
        results.problems = sorted(problems.values(), key=lambda p: (p.order, p.id))
        return results

    # Provenance
    prov = root / "provenance.json"
    if prov.exists():
        try:
            results.provenance = load_provenance(prov)
            results.provenance_status = OK
        except Bad as e:
            results.provenance_status = MALFORMED
            issue(MALFORMED, str(prov), str(e))
    else:
        issue(MISSING, str(prov), "no provenance (which build produced these numbers is unknown)")

    # Gates
    for path in json_files(root / "gates"):
        gate = load_gate(path, str(path))
        results.gates.append(gate)
        if gate.status == MALFORMED:
            issue(MALFORMED, gate.file, gate.message)
    if not (root / "gates").is_dir():
        issue(MISSING, str(root / "gates"), "no gates directory; no gate was recorded")
    seen = {g.id for g in results.gates}
    for p in list(problems.values()):
        for gid in p.expected_gates:
            if gid not in seen:
                shown = str(root / "gates" / f"{gid}.json")
                if gid in p.recorded_by:
                    message = f"recorded by {p.recorded_by[gid]}, which these results do not include"
                    results.gates.append(Gate(id=gid, file=shown, status=SKIPPED, problem=p.id, message=message))
                else:
                    message = f"listed in {p.id}.toml but never recorded"
                    results.gates.append(Gate(id=gid, file=shown, status=MISSING, problem=p.id, message=message))
                    issue(MISSING, shown, message)
                seen.add(gid)
    listed_in = {gid: p.id for p in problems.values() for gid in p.expected_gates}
    for gate in results.gates:
        # A gate file too broken to name its problem still shows in the problem that lists it.
        owner = gate.problem or listed_in.get(gate.id)
        if owner:
            problem(owner).gates.append(gate)

    # Evidence
    data = root / "data"
    if data.is_dir():
        for directory in sorted(d for d in data.iterdir() if d.is_dir()):
            for path in json_files(directory):
                item = load_evidence(path, str(path), root)
                problem(directory.name).evidence.append(item)
                if item.status != OK:
                    issue(item.status, item.path, item.message)

    # Problem sections with a description but no results
    for p in problems.values():
        if p.has_toml and p.status == OK and not p.gates and not p.evidence:
            p.status = MISSING
            p.message = "no gates and no data recorded for this problem"
            issue(MISSING, str(problems_dir / f"{p.id}.toml"), p.message)

    # Benchmarks (optional: their absence is noted on the page but is not an error)
    for path in json_files(root / "bench"):
        bench = load_bench(path, str(path))
        results.bench.append(bench)
        if bench.status == MALFORMED:
            issue(MALFORMED, bench.file, bench.message)
        for row in bench.rows:
            if row["error"]:
                issue(MALFORMED, bench.file, f'benchmark {row["name"]} reported an error: {row["error"]}')

    results.gates.sort(key=lambda g: ({FAIL: 0, MALFORMED: 1, MISSING: 2, PASS: 3, SKIPPED: 4}[g.status], g.id))
    for p in problems.values():
        p.gates.sort(key=lambda g: g.id)
    results.problems = sorted(problems.values(), key=lambda p: (p.order, p.id))
    return results
