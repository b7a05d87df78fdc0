"""Plot evidence items to inline PNGs with matplotlib (Agg, no display, no pyplot state)."""
from __future__ import annotations

import base64
import io
import math
import warnings

import matplotlib

matplotlib.use("Agg")
from matplotlib.figure import Figure  # noqa: E402  (after choosing the backend)
from matplotlib.ticker import FuncFormatter  # noqa: E402

_STYLE = {
    "line": dict(linestyle="-", linewidth=1.6),
    "dashed": dict(linestyle="--", linewidth=1.6),
    "points": dict(linestyle="none", marker="o", markersize=4.5),
}


def _value(v) -> float:
    """null in the JSON stands for a non-finite value: a gap in the curve."""
    return math.nan if v is None else float(v)


def _tick_text(v: float) -> str:
    if 1e-3 <= abs(v) < 1e4:
        return f"{v:g}"
    mantissa, exponent = f"{v:.0e}".split("e")
    return rf"${mantissa}\times10^{{{int(exponent)}}}$" if mantissa != "1" else rf"$10^{{{int(exponent)}}}$"


def _label_short_log_axis(axis, values: list[float]) -> None:
    """On a log axis spanning less than two decades matplotlib labels only one or two
    powers of ten; label 1, 2, 5 (or every digit when the span is short) in plain numbers."""
    positive = [v for v in values if v > 0 and math.isfinite(v)]
    if not positive:
        return
    span = math.log10(max(positive) / min(positive))
    if span >= 2:
        return
    keep = set(range(1, 10)) if span < 0.7 else {1, 2, 5}

    def label(v, _pos):
        if v <= 0:
            return ""
        lead = round(v / 10 ** math.floor(math.log10(v) + 1e-9))
        return _tick_text(v) if lead in keep else ""

    axis.set_major_formatter(FuncFormatter(label))
    axis.set_minor_formatter(FuncFormatter(label))


def plot_png(spec: dict) -> tuple[str, list[str]]:
    """Render a checked "plot" item; returns (data: URI, notes for the reader).
    matplotlib's warnings (odd data) become notes under the plot instead of stderr noise."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        uri, notes = _draw(spec)
    for w in caught:
        note = f"matplotlib: {w.message}"
        if note not in notes:
            notes.append(note)
    return uri, notes


def _draw(spec: dict) -> tuple[str, list[str]]:
    notes = []
    series = [(s, [_value(v) for v in s["x"]], [_value(v) for v in s["y"]]) for s in spec["series"]]
    log = {}
    for axis in ("x", "y"):
        log[axis] = spec.get(f"{axis}scale") == "log"
        values = [v for _, xs, ys in series for v in (xs if axis == "x" else ys)]
        if log[axis] and not any(v > 0 and math.isfinite(v) for v in values):
            notes.append(f"no positive {axis} values: drawn on a linear {axis} axis instead of log.")
            log[axis] = False

    fig = Figure(figsize=(9.0, 4.8), dpi=110, layout="constrained")
    ax = fig.subplots()
    labelled = False
    shown_x, shown_y = [], []
    for s, xs, ys in series:
        hidden = 0
        for i, (x, y) in enumerate(zip(xs, ys)):
            # A log axis cannot show values ≤ 0; leave a gap and say so below the plot.
            if (log["x"] and x <= 0) or (log["y"] and y <= 0):
                hidden += 1
                xs[i] = ys[i] = math.nan
        shown_x += xs
        shown_y += ys
        label = s.get("label") or None
        labelled |= label is not None
        lines = ax.plot(xs, ys, label=label, **_STYLE[s.get("style", "line")])
        if "ylo" in s:   # error bars (e.g. a confidence interval) in the series' colour
            lo, hi = [_value(v) for v in s["ylo"]], [_value(v) for v in s["yhi"]]
            ax.vlines(xs, lo, hi, colors=lines[0].get_color(), linewidth=1.2)
            shown_y += lo + hi
        if not any(math.isfinite(x) and math.isfinite(y) for x, y in zip(xs, ys)):
            notes.append(f"series “{label or '?'}” has no point to show.")
        elif hidden:
            notes.append(f"{hidden} point(s) of series “{label or '?'}” are ≤ 0 and not shown on the log axis.")
    if log["x"]:
        ax.set_xscale("log")
        _label_short_log_axis(ax.xaxis, shown_x)
    if log["y"]:
        ax.set_yscale("log")
        _label_short_log_axis(ax.yaxis, shown_y)
    linear = [a for a in ("x", "y") if not log[a]]
    if linear:
        # Linear axes: 1e-4 as "1" with a ×10⁻⁴ offset, not as 0.000100.
        ax.ticklabel_format(axis="both" if len(linear) == 2 else linear[0],
                            style="sci", scilimits=(-3, 4), useMathText=True)
    if "xticks" in spec:
        ax.set_xticks(spec["xticks"]["values"], spec["xticks"]["labels"])
        ax.margins(x=0.15)
    ax.set_xlabel(spec.get("xlabel", ""))
    ax.set_ylabel(spec.get("ylabel", ""))
    ax.grid(True, which="major", alpha=0.35)
    if log["x"] or log["y"]:
        ax.grid(True, which="minor", alpha=0.12)
    if labelled:
        ax.legend(fontsize="small", framealpha=0.85)
    buffer = io.BytesIO()
    # No software/date metadata, so the same data gives the same bytes.
    fig.savefig(buffer, format="png", metadata={"Software": None})
    return "data:image/png;base64," + base64.b64encode(buffer.getvalue()).decode("ascii"), notes
