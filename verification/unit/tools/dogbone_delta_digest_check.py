"""Checks verification/tools/dogbone_delta_digest.py on a run made up here: three particles, a
history whose first failure and peak stress are known, two field frames.

    /usr/bin/python3 verification/unit/tools/dogbone_delta_digest_check.py TOOLS_DIR
"""
import csv
import json
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

COLUMNS = ["time", "failed_particles", "max_von_mises", "max_eq_plastic_strain", "kinetic_energy", "internal_energy",
           "plastic_work", "reaction_pulled_x", "probe_ext_left_ux", "probe_ext_right_ux"]
DX = 0.625e-3


def make_run(root, fail_at_row):
    summary = {"scene": "check", "status": "completed", "steps": 40, "steps_requested": 40, "threads": 1,
               "wall_time_s": 1.0, "particles": 3, "spacing": DX, "dt": 1e-7, "end_time": 40e-7,
               "provenance": {"git_sha": "0" * 40}}
    with open(f"{root}/summary.json", "w") as f:
        json.dump(summary, f)
    with open(f"{root}/history.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(COLUMNS)
        for k in range(40):
            # Rising stress, a higher peak two rows before the failure, a drop after it.
            vm = 1e9 + 1e6 * k + (5e7 if k == fail_at_row - 2 else 0.0) - (9e8 if k > fail_at_row else 0.0)
            w.writerow([k * 1e-7, int(k >= fail_at_row), vm, 0.01 * k, 0, 1, 0, 1e3, 0, 1e-6 * k])
    # Sites at x = 0.3125, 0.9375, 1.5625 mm on one row; particle 1 has the largest ε̄_p.
    x0 = np.array([[0.5, 0.5, 0.0], [1.5, 0.5, 0.0], [2.5, 0.5, 0.0]]) * DX
    with h5py.File(f"{root}/fields.h5", "w") as h5:
        for name, t, failed in (("000000", 0.0, [0, 0, 0]), ("000001", 39e-7, [0, 1, 0])):
            g = h5.create_group(f"frames/{name}")
            g.attrs["time"] = t
            g["position"], g["displacement"] = x0, np.zeros_like(x0)
            g["eq_plastic_strain"] = np.array([0.1, 0.7, 0.3])
            g["triaxiality"], g["von_mises"] = np.array([0.2, 0.4, 0.6]), np.array([1.0, 2.0, 3.0])
            g["failed"] = np.array(failed, dtype=float)


def digest(tools, root):
    out = f"{root}/digest.json"
    subprocess.run([sys.executable, f"{tools}/dogbone_delta_digest.py", root, out, "made up"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(out) as f:
        return json.load(f)


def main():
    tools = sys.argv[1]
    with tempfile.TemporaryDirectory() as root:
        make_run(root, fail_at_row=30)
        d = digest(tools, root)
    ff = d["first_failure"]
    assert abs(ff["time"] - 30e-7) < 1e-15, ff
    assert ff["peak_von_mises"] == 1e9 + 28e6 + 5e7 and abs(ff["peak_time"] - 28e-7) < 1e-15, ff
    b = d["before_failure"]
    assert b["time"] == 0.0 and b["eq_plastic_strain"] == 0.7 and b["triaxiality"] == 0.4, b
    # Δx equals the raster's cell: one cell per site, the sites' values in order, one row.
    assert b["map"]["values"] == [[0.1, 0.7, 0.3]], b["map"]
    assert np.allclose(b["site"], [1.5 * DX, 0.5 * DX]), b["site"]
    # Rows within 50 µs of the failure are all kept (here every row).
    assert len(d["history"]["time"]) == 40
    with tempfile.TemporaryDirectory() as root:
        make_run(root, fail_at_row=99)  # no failure
        d = digest(tools, root)
    assert "first_failure" not in d and d["before_failure"]["time"] == 39e-7, d.keys()
    assert len(d["history"]["time"]) == 4  # every tenth row
    # A run that stopped early is taken after its first failure, refused before it.
    for fail_at_row, taken in ((30, True), (99, False)):
        with tempfile.TemporaryDirectory() as root:
            make_run(root, fail_at_row)
            with open(f"{root}/summary.json") as f:
                summary = json.load(f)
            summary.update(status="failed", message="a particle has left the grid")
            with open(f"{root}/summary.json", "w") as f:
                json.dump(summary, f)
            try:
                d = digest(tools, root)
                assert taken and d["summary"]["status"] == "failed", d["summary"]
            except subprocess.CalledProcessError:
                assert not taken
    print("dogbone_delta_digest: ok")


if __name__ == "__main__":
    main()
