"""Number formatting for the page: significant digits, scientific notation as a×10ⁿ."""
from __future__ import annotations

import math

from markupsafe import Markup, escape

MINUS = "\u2212"


def _sci(x: float, sig: int) -> Markup:
    mantissa, exponent = f"{x:.{sig - 1}e}".split("e")
    if "." in mantissa:
        mantissa = mantissa.rstrip("0").rstrip(".")
    exponent = int(exponent)
    mantissa = mantissa.replace("-", MINUS)
    if mantissa in ("1", MINUS + "1"):
        head = "" if mantissa == "1" else MINUS
        return Markup(f"{head}10<sup>{str(exponent).replace('-', MINUS)}</sup>")
    return Markup(f"{mantissa}×10<sup>{str(exponent).replace('-', MINUS)}</sup>")


def num(x, sig: int = 4) -> Markup:
    """A cell value for the page. Integers stay exact; floats get `sig` significant digits,
    plain between 10⁻³ and 10⁶ and scientific outside; strings are escaped as given."""
    if x is None:
        return Markup("—")
    if isinstance(x, bool):
        return Markup("true" if x else "false")
    if isinstance(x, str):
        return escape(x)
    if isinstance(x, int):
        return Markup(str(x).replace("-", MINUS))
    if math.isnan(x):
        return Markup("NaN")
    if math.isinf(x):
        return Markup("∞" if x > 0 else MINUS + "∞")
    if x == 0:
        return Markup("0")
    exponent = math.floor(math.log10(abs(x)))
    if exponent < -3 or exponent >= 6:
        return _sci(x, sig)
    decimals = max(sig - 1 - exponent, 0)
    s = f"{x:.{decimals}f}"
    if "." in s:
        s = s.rstrip("0").rstrip(".")
    return Markup(s.replace("-", MINUS))


def sort_key(x) -> str:
    """What the inline sorter compares: the raw number, or the text."""
    if isinstance(x, bool) or x is None:
        return ""
    if isinstance(x, (int, float)):
        return repr(x) if math.isfinite(x) else ""
    return str(x)


_PREFIXES = [(1e12, "T"), (1e9, "G"), (1e6, "M"), (1e3, "k")]


def rate(x, unit: str = "/s") -> Markup:
    """1.95e9 → 1.95 G/s (for items and bytes per second)."""
    if x is None:
        return Markup("—")
    for scale, prefix in _PREFIXES:
        if abs(x) >= scale:
            return Markup(f"{num(x / scale, 3)} {prefix}{unit}")
    return Markup(f"{num(x, 3)} {unit}")


_TIME_UNITS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def duration(x, unit: str = "ns") -> Markup:
    """Benchmark time in the unit Google Benchmark reported it in (µs written properly)."""
    if x is None:
        return Markup("—")
    shown = "µs" if unit == "us" else unit
    return Markup(f"{num(x, 4)} {escape(shown)}")


def seconds(x, unit: str = "ns") -> float | None:
    return None if x is None else x * _TIME_UNITS.get(unit, 1.0)
