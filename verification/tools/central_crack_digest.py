"""Digests a paper-resolution central-crack run into the small JSON the report reads.

    /usr/bin/python3 verification/tools/central_crack_digest.py RUN_DIR OUT.json "HOW"

RUN_DIR is the --out directory of `pdmpm run verification/scenes/central_crack/paper_<mode>.toml`
(summary.json, history.csv, fields.h5); HOW is the command and machine, stored verbatim. The runs
take 1-2 hours each, so CI reads their digests (verification/measured/central_crack_paper/, test
FastCentralCrack.PaperResolutionRunsBesideThePapersTable) instead of running them.

Per field frame: each crack front's distance from the plate's centre and height, as the gates of
verification/gates/central_crack_gate.cpp define it (fronts(): on each side of the centre the
crack-face particle, damage >= 0.35, farthest from the centre along x, in reference coordinates;
its height the mean y of the faces within dx of it), the PD share of the particles, and at the
map times the lattice's particle kinds with crack faces marked, run-length encoded row by row.
Per history row: PD, transition and MPM particle counts, tip count, max damage and the top grip's
reaction. From summary.json: wall time, steps, particle-steps, phase times, events, provenance.
"""
import csv
import json
import math
import sys

import h5py
import numpy as np

CENTRE = 0.05  # m, the plate's centre on both axes
FACE = 0.35  # damage of a crack face (README "Crack observables")
MAP_TIMES = [100e-6, 120e-6, 140e-6, 400e-6, 1.6e-3]  # s: before the start, growth, branching, late, end
SUMMARY_KEYS = ["scene", "mode", "status", "steps", "steps_requested", "threads", "wall_time_s", "particles",
                "particle_steps", "wall_time_phases", "events", "final_counts", "spacing", "dt", "end_time",
                "peak_memory_bytes", "provenance"]
HISTORY_KEYS = ["time", "pd_particles", "transition_particles", "mpm_particles", "tips", "max_damage",
                "reaction_top_y"]


def fronts(x0, phi, dx):
    face = phi >= FACE
    x = x0[face, 0] - CENTRE
    y = x0[face, 1] - CENTRE
    out = {}
    for side, sel in (("left", x < 0), ("right", x >= 0)):
        d = np.abs(x[sel])
        if d.size == 0:
            out[side], out[side + "_y"] = 0.0, 0.0
            continue
        far = d.max()
        out[side] = float(far)
        out[side + "_y"] = float(y[sel][d > far - dx].mean())
    return out


def kinds_rle(x0, kind, phi, dx):
    """Rows of the lattice (bottom to top) as [code, count] runs; code = kind + 4 * (crack face)."""
    ij = np.rint((x0[:, :2] - x0[:, :2].min(axis=0)) / dx).astype(int)
    nx, ny = ij[:, 0].max() + 1, ij[:, 1].max() + 1
    if nx * ny != len(kind):
        raise SystemExit(f"central_crack_digest: the particles are not a full {nx} x {ny} lattice")
    code = np.empty((ny, nx), dtype=int)
    code[ij[:, 1], ij[:, 0]] = kind.astype(int) + 4 * (phi >= FACE)
    runs = []
    for row in code:
        edges = np.flatnonzero(np.diff(row)) + 1
        starts = np.concatenate(([0], edges))
        ends = np.concatenate((edges, [len(row)]))
        runs.append([[int(row[s]), int(e - s)] for s, e in zip(starts, ends)])
    return {"nx": int(nx), "ny": int(ny), "rows": runs}


def main():
    if len(sys.argv) != 4:
        raise SystemExit(__doc__)
    run, out_path, how = sys.argv[1:]
    with open(f"{run}/summary.json") as f:
        summary = json.load(f)
    if summary.get("status") != "completed":
        raise SystemExit(f"central_crack_digest: {run}/summary.json: status {summary.get('status')!r}, not completed")
    dx = summary["spacing"]
    digest = {"how": how, "summary": {k: summary[k] for k in SUMMARY_KEYS if k in summary}, "frames": []}
    with h5py.File(f"{run}/fields.h5", "r") as h5:
        names = sorted(h5["frames"].keys())
        times = [float(h5["frames"][n].attrs["time"]) for n in names]
        map_frames = {min(range(len(times)), key=lambda k: abs(times[k] - t)) for t in MAP_TIMES}
        for k, name in enumerate(names):
            g = h5["frames"][name]
            x0 = g["position"][:, :2] - g["displacement"][:, :2]
            phi = g["damage"][:].reshape(-1)
            kind = g["method"][:].reshape(-1)
            frame = {"t": times[k], **fronts(x0, phi, dx), "pd_share": float(np.mean(kind == 0))}
            if k in map_frames:
                frame["map"] = kinds_rle(x0, kind, phi, dx)
            digest["frames"].append(frame)
    with open(f"{run}/history.csv") as f:
        rows = list(csv.DictReader(f))
    missing = [k for k in HISTORY_KEYS if k not in rows[0]]
    if missing:
        raise SystemExit(f"central_crack_digest: {run}/history.csv has no column {missing}")
    digest["history"] = {k: [float(r[k]) for r in rows] for k in HISTORY_KEYS}
    for k, v in digest["history"].items():
        if any(not math.isfinite(x) for x in v):
            raise SystemExit(f"central_crack_digest: {run}/history.csv: non-finite {k}")
    with open(out_path, "w") as f:
        json.dump(digest, f, separators=(",", ":"))
        f.write("\n")
    print(f"central_crack_digest: {out_path}: {len(digest['frames'])} frames, {len(rows)} history rows")


if __name__ == "__main__":
    main()
