"""Plot evidence items to inline PNGs with matplotlib (Agg, no display, no pyplot state)."""
from __future__ import annotations

import base64
import io
import math

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
    """Render a checked "plot" item; returns (data: URI, notes for the reader)."""
    notes = []
    xlog = spec.get("xscale") == "log"
    ylog = spec.get("yscale") == "log"
    fig = Figure(figsize=(9.0, 4.8), dpi=110, layout="constrained")
    ax = fig.subplots()
    labelled = False
    all_x, all_y = [], []
    for s in spec["series"]:
        xs, ys, hidden = [], [], 0
        for x, y in zip(s["x"], s["y"]):
            x, y = _value(x), _value(y)
            # A log axis cannot show values ≤ 0; leave a gap and say so below the plot.
            if (xlog and x <= 0) or (ylog and y <= 0):
                hidden += 1
                x = y = math.nan
            xs.append(x)
            ys.append(y)
        all_x += xs
        all_y += ys
        label = s.get("label") or None
        labelled |= label is not None
        ax.plot(xs, ys, label=label, **_STYLE[s.get("style", "line")])
        if hidden:
            notes.append(f"{hidden} point(s) of series “{label or '?'}” are ≤ 0 and not shown on the log axis.")
    if xlog:
        ax.set_xscale("log")
        _label_short_log_axis(ax.xaxis, all_x)
    if ylog:
        ax.set_yscale("log")
        _label_short_log_axis(ax.yaxis, all_y)
    if not (xlog and ylog):
        # Linear axes: 1e-4 as "1" with a ×10⁻⁴ offset, not as 0.000100.
        ax.ticklabel_format(axis="both" if not (xlog or ylog) else ("y" if xlog else "x"),
                            style="sci", scilimits=(-3, 4), useMathText=True)
    ax.set_xlabel(spec.get("xlabel", ""))
    ax.set_ylabel(spec.get("ylabel", ""))
    ax.grid(True, which="major", alpha=0.35)
    if xlog or ylog:
        ax.grid(True, which="minor", alpha=0.12)
    if labelled:
        ax.legend(fontsize="small", framealpha=0.85)
    buffer = io.BytesIO()
    # No software/date metadata, so the same data gives the same bytes.
    fig.savefig(buffer, format="png", metadata={"Software": None})
    return "data:image/png;base64," + base64.b64encode(buffer.getvalue()).decode("ascii"), notes
