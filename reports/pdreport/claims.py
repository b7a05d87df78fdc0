"""The published claims the project reproduces (reports/claims.toml), joined with the gates
that measure them: the answers a reader came for, shown at the top of the page."""
from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

from .load import FAIL, MALFORMED, MISSING, PASS, SKIPPED, Bad, Issue, Results, is_number, no_external

REPRODUCED = "reproduced"
EXPLAINED = "deviation explained"
FAILED = "failed"
NOT_RUN = "not run here"
NOT_MEASURED = "not measured"

_KEYS = {"paper", "where", "quantity", "paper_value", "gate", "ours", "scale", "deviation", "section"}
_REQUIRED = ("paper", "where", "quantity", "paper_value")


@dataclass
class Claim:
    paper: str
    where: str
    quantity: str
    paper_value: str
    gate: str = ""
    ours_format: str = "{:.4g}"
    scale: float = 1.0
    deviation: str = ""
    section: str = ""
    ours: str = ""       # the gate's measured value, formatted; "" if there is none
    verdict: str = NOT_MEASURED


def _claim(obj: dict, where: str) -> Claim:
    if not isinstance(obj, dict):
        raise Bad(f"{where}: a [[claim]] table expected")
    unknown = set(obj) - _KEYS
    if unknown:
        raise Bad(f"{where}: unknown key(s) {sorted(unknown)}; allowed: {sorted(_KEYS)}")
    for key in _REQUIRED:
        if not isinstance(obj.get(key), str) or not obj[key].strip():
            raise Bad(f"{where}: '{key}' must be a non-empty string")
    for key in ("gate", "ours", "deviation", "section"):
        if key in obj and not isinstance(obj[key], str):
            raise Bad(f"{where}: '{key}' must be a string")
    scale = obj.get("scale", 1.0)
    if not is_number(scale) or not math.isfinite(scale) or scale == 0:
        raise Bad(f"{where}: 'scale' must be a finite non-zero number")
    fmt = obj.get("ours", "{:.4g}")
    try:
        fmt.format(1.0)
    except (ValueError, IndexError, KeyError) as e:
        raise Bad(f"{where}: 'ours' is not a format for one number: {e}") from None
    for key in ("quantity", "paper_value", "deviation", "where"):
        no_external(obj.get(key, ""), f"{where} '{key}'")
    return Claim(paper=obj["paper"], where=obj["where"], quantity=obj["quantity"], paper_value=obj["paper_value"],
                 gate=obj.get("gate", ""), ours_format=fmt, scale=float(scale), deviation=obj.get("deviation", ""),
                 section=obj.get("section", ""))


def _judge(claim: Claim, results: Results) -> None:
    gate = next((g for g in results.gates if g.id == claim.gate), None) if claim.gate else None
    if gate is not None and is_number(gate.measured) and math.isfinite(gate.measured):
        claim.ours = claim.ours_format.format(gate.measured * claim.scale)
        claim.section = claim.section or gate.problem
    if gate is None or gate.status == MISSING:
        claim.verdict = NOT_MEASURED
    elif gate.status == SKIPPED:
        claim.verdict = NOT_RUN
    elif gate.status == MALFORMED:
        claim.verdict = FAILED
    elif claim.deviation:
        claim.verdict = EXPLAINED
    else:
        claim.verdict = REPRODUCED if gate.status == PASS else FAILED


def load_claims(path: Path, results: Results) -> list[Claim]:
    """The claims of `path`, judged against the results. A missing file gives none (the
    page says so); a malformed one is an issue and gives none."""
    if not path.is_file():
        return []
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
        if set(data) - {"claim"}:
            raise Bad(f"unknown top-level key(s) {sorted(set(data) - {'claim'})}; only [[claim]] tables")
        claims = [_claim(obj, f"claim {i + 1}") for i, obj in enumerate(data.get("claim", []))]
    except (Bad, tomllib.TOMLDecodeError, UnicodeDecodeError) as e:
        results.issues.append(Issue(MALFORMED, str(path), str(e)))
        return []
    for c in claims:
        if c.paper not in results.references and results.references:
            results.issues.append(Issue(MALFORMED, str(path), f"claim '{c.quantity}': unknown paper key [{c.paper}]"))
        _judge(c, results)
    return claims
