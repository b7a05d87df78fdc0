"""Digests one level of the dog-bone's δ-convergence study into the small JSON the report reads.

    /usr/bin/python3 verification/tools/dogbone_delta_digest.py RUN_DIR OUT.json "HOW"

RUN_DIR is the --out directory of `pdmpm run verification/scenes/dogbone/delta_study/mpm_<Δx>.toml`
(summary.json, history.csv, fields.h5); HOW is the command and machine, stored verbatim. The finest
level takes 70 minutes on one core, so CI reads the digests (verification/measured/dogbone_delta/,
test FastDogbone.DeltaConvergenceFromStoredRuns) instead of running them.

The measure (docs/verification/dogbone.md, "δ-convergence"): the peak stress at the first failure,
the largest `max_von_mises` of the history rows up to and including the first row with a failed
particle. Also: the first failure's time and the largest ε̄_p then; at the last field frame before
it, the particle that fails first (of those failed at the next frame, the largest ε̄_p there) with
its triaxiality, and a map of ε̄_p on a fixed raster (RASTER, the largest value over the sites a
cell's square meets) so the levels compare cell by cell; the engineering curve's inputs
(extensometer probes, grip reaction), every row near the failure and every tenth elsewhere.
A run that stopped before its end time is taken if it stopped after its first failure.
"""
import csv
import json
import math
import sys

import h5py
import numpy as np

RASTER = 0.625e-3  # m: the map's cell, the study's second-coarsest spacing
NEAR_FAILURE = 50e-6  # s: rows kept at full density either side of the first failure
SUMMARY_KEYS = ["scene", "status", "message", "steps", "steps_requested", "threads", "wall_time_s", "particles",
                "spacing", "dt", "end_time", "peak_memory_bytes", "provenance"]
CURVE_KEYS = ["time", "reaction_pulled_x", "probe_ext_left_ux", "probe_ext_right_ux"]  # stored
HISTORY_KEYS = CURVE_KEYS + ["failed_particles", "max_von_mises", "max_eq_plastic_strain"]  # read


def fail(message):
    raise SystemExit(f"dogbone_delta_digest: {message}")


def raster(x0, value, dx, lo, hi):
    """Largest value over the sites whose square (side dx) meets each RASTER cell of the box lo-hi;
    -1 where no site's square does (outside the body)."""
    shape = np.ceil((hi - lo) / RASTER).astype(int)
    grid = np.full((shape[1], shape[0]), -1.0)
    a = np.floor((x0 - 0.5 * dx - lo) / RASTER + 1e-9).astype(int)
    b = np.floor((x0 + 0.5 * dx - lo) / RASTER - 1e-9).astype(int)
    a, b = np.clip(a, 0, shape - 1), np.clip(b, 0, shape - 1)
    for i in range(int((b - a)[:, 0].max()) + 1):
        for j in range(int((b - a)[:, 1].max()) + 1):
            cx, cy = np.minimum(a[:, 0] + i, b[:, 0]), np.minimum(a[:, 1] + j, b[:, 1])
            np.maximum.at(grid, (cy, cx), value)
    return grid


def main():
    if len(sys.argv) != 4:
        raise SystemExit(__doc__)
    run, out_path, how = sys.argv[1:]
    with open(f"{run}/summary.json") as f:
        summary = json.load(f)
    dx = summary["spacing"]
    with open(f"{run}/history.csv") as f:
        rows = list(csv.DictReader(f))
    missing = [k for k in HISTORY_KEYS if k not in rows[0]]
    if missing:
        fail(f"{run}/history.csv has no column {missing}")
    h = {k: np.array([float(r[k]) for r in rows]) for k in HISTORY_KEYS}
    for k, v in h.items():
        if not np.all(np.isfinite(v)):
            fail(f"{run}/history.csv: non-finite {k}")
    failed_rows = np.flatnonzero(h["failed_particles"] > 0)
    # A run that stopped early (e.g. a fragment left the grid's node box) still measures the study's
    # quantity if it stopped after its first failure; the digest keeps its status and message.
    if summary.get("status") != "completed" and not failed_rows.size:
        fail(f"{run}/summary.json: status {summary.get('status')!r} before any failure")
    digest = {"how": how, "summary": {k: summary[k] for k in SUMMARY_KEYS if k in summary}}
    if failed_rows.size:
        k = int(failed_rows[0])
        peak = int(np.argmax(h["max_von_mises"][:k + 1]))
        t_fail = float(h["time"][k])
        digest["first_failure"] = {"time": t_fail, "peak_von_mises": float(h["max_von_mises"][peak]),
                                   "peak_time": float(h["time"][peak]),
                                   "max_eq_plastic_strain": float(h["max_eq_plastic_strain"][k])}
        keep = (np.abs(h["time"] - t_fail) <= NEAR_FAILURE) | (np.arange(len(rows)) % 10 == 0)
    else:
        t_fail = math.inf
        keep = np.arange(len(rows)) % 10 == 0
    digest["history"] = {k: h[k][keep].tolist() for k in CURVE_KEYS}

    with h5py.File(f"{run}/fields.h5", "r") as h5:
        names = sorted(h5["frames"].keys(), key=lambda n: float(h5["frames"][n].attrs["time"]))
        times = [float(h5["frames"][n].attrs["time"]) for n in names]
        first = h5["frames"][names[0]]
        x0 = first["position"][:, :2] - first["displacement"][:, :2]
        lo, hi = x0.min(axis=0) - 0.5 * dx, x0.max(axis=0) + 0.5 * dx
        before = max((i for i, t in enumerate(times) if t < t_fail), default=0)
        g = h5["frames"][names[before]]
        ep = g["eq_plastic_strain"][:].reshape(-1)
        # The particle that fails first: of those failed at the next frame, the one with the
        # largest ε̄_p at this one (without a failure, the largest ε̄_p of the last frame).
        candidates = np.ones(ep.size, dtype=bool)
        if before + 1 < len(names) and math.isfinite(t_fail):
            candidates = h5["frames"][names[before + 1]]["failed"][:].reshape(-1) > 0
        p = int(np.flatnonzero(candidates)[np.argmax(ep[candidates])])
        digest["before_failure"] = {
            "time": times[before], "site": x0[p].tolist(), "eq_plastic_strain": float(ep[p]),
            "triaxiality": float(g["triaxiality"][:].reshape(-1)[p]),
            "map": {"cell": RASTER, "min": lo.tolist(), "values": np.round(raster(x0, ep, dx, lo, hi), 4).tolist()}}
    with open(out_path, "w") as f:
        json.dump(digest, f, separators=(",", ":"))
        f.write("\n")
    print(f"dogbone_delta_digest: {out_path}: Δx = {dx * 1e3:g} mm, first failure "
          f"{digest.get('first_failure', {}).get('time', 'none')}, {int(keep.sum())} history rows")


if __name__ == "__main__":
    main()
