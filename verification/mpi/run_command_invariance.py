#!/usr/bin/python3
"""`mpirun -n N pdmpm run` writes what `pdmpm run` writes (ctest distributed.run_command.N).

For each scene of verification/mpi/scenes/ the scene runs as one process and as N
processes (oversubscribed on a small machine). history.csv and fields.xdmf must be
equal byte for byte, every dataset and attribute of fields.h5 bit for bit, and
summary.json equal in every key but the machine's (wall times, rates, memory,
processes, halo, ghosts). A run stopped after a step with periodic checkpoints and
resumed under mpirun must write the same outputs (PD, MPM and contact scenes), and a resume
with another process count is refused. Then what a distributed run refuses: a hybrid
scene, symmetry planes with contact, an output directory it cannot write — each with the exit status of one process,
one message, nothing written, and no process left waiting.

Writes one gate per scene and one for the refusals, and a table, into RESULTS_DIR
($PDMPM_RESULTS_DIR if set) for the report's "distributed" section.

Usage: run_command_invariance.py PDMPM PROCESSES RESULTS_DIR SCENE... (exit status 0: all agree)
"""
import json
import os
import pathlib
import subprocess
import sys
import tempfile

import h5py
import numpy as np

# Keys of summary.json that describe the machine and the processes, not the answer.
MACHINE_KEYS = {"wall_time_s", "peak_memory_bytes", "particle_steps_per_second", "force_time_s",
                "contact_time_s", "bond_updates_per_second", "threads", "processes", "halo_particles",
                "ghost_points", "contact_pairs_across_processes", "mirrors_of_halo_particles", "wall_time_phases", "provenance"}
MPIRUN_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
              "OMPI_MCA_rmaps_base_oversubscribe": "1", "OMP_NUM_THREADS": "1"}
TIMEOUT_S = 300  # a process left waiting for another would hang: fail instead
# The scenes also stopped after step 250 and resumed (their models keep the most state;
# the disk strike: the contact list and its ghosts).
RESUMED = {"lps_plastic_notched_2d", "mpm_notched_2d", "pmb_disk_strikes_plate_2d"}

# What a scene is for beyond broken bonds: summary keys of its distributed run that must be
# positive (contact pairs joining two processes' particles, mirrors of halo particles).
EXERCISES = {"pmb_disk_strikes_plate_2d": ["contact_pairs_across_processes"],
             "lps_quarter_hole_symmetry_2d": ["mirrors_of_halo_particles"],
             "pmb_octant_symmetry_3d": ["mirrors_of_halo_particles"]}

failures = []
rows = []


def check(ok, what):
    print(("  ok    " if ok else "  FAIL  ") + what)
    if not ok:
        failures.append(what)
    return ok


def write_json(path, data):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(data, indent=2) + "\n")


def write_gate(results, gate_id, claim, measured, reason):
    write_json(results / "gates" / f"{gate_id}.json", {
        "id": gate_id, "claim": claim, "measured": measured, "expected": 0, "tolerance": 0,
        "compare": "at_most", "tolerance_reason": reason, "source": "[pdmpm] docs/models/distributed.md",
        "unit": "", "problem": "distributed", "verdict": "PASS" if measured <= 0 else "FAIL",
        "test": "verification/mpi/run_command_invariance.py"})


def run(command, processes):
    launcher = ["mpirun", "-n", str(processes), "--oversubscribe"] if processes > 1 else []
    env = dict(os.environ, **MPIRUN_ENV)
    return subprocess.run(launcher + command, env=env, capture_output=True, text=True, timeout=TIMEOUT_S)


def h5_items(path):
    """Every dataset's array and every attribute's value, by name."""
    items = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            for key, value in obj.attrs.items():
                items[f"{name}@{key}"] = np.asarray(value)
            if isinstance(obj, h5py.Dataset):
                items[name] = obj[()]
        for key, value in f.attrs.items():
            items[f"/@{key}"] = np.asarray(value)
        f.visititems(visit)
    return items


def same_bits(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


def compare_outputs(one, many, label, processes):
    """The number of files, datasets, attributes and summary keys that differ."""
    differ = 0
    for name in ("history.csv", "fields.xdmf"):
        differ += not check((one / name).read_bytes() == (many / name).read_bytes(), f"{label}: {name} byte for byte")
    a, b = h5_items(one / "fields.h5"), h5_items(many / "fields.h5")
    differing = sorted(k for k in a.keys() | b.keys() if k not in a or k not in b or not same_bits(a[k], b[k]))
    frames = sum(1 for k in a if k.startswith("frames/") and k.endswith("/position"))
    differ += len(differing) + (frames < 2)
    check(not differing and frames >= 2,
          f"{label}: fields.h5, {len(a)} datasets and attributes in {frames} frames bit for bit"
          + (f" (differ: {differing[:5]})" if differing else ""))
    sa = json.loads((one / "summary.json").read_text())
    sb = json.loads((many / "summary.json").read_text())
    keys = (sa.keys() | sb.keys()) - MACHINE_KEYS
    differing = sorted(k for k in keys if sa.get(k) != sb.get(k))
    differ += len(differing)
    check(not differing, f"{label}: summary.json equal in {len(keys)} keys" + (f" (differ: {differing})" if differing else ""))
    differ += not check(sb.get("processes") == processes and sa.get("processes") == 1, f"{label}: processes recorded")
    history_rows = (one / "history.csv").read_text().count("\n") - 1
    return sa, sb, differ, {"frames": frames, "h5_items": len(a), "history_rows": history_rows, "keys": len(keys)}


def invariance(pdmpm, processes, scene, work, results):
    label = f"{scene.stem}, {processes} processes"
    out = {}
    for p in (1, processes):
        out[p] = work / f"{scene.stem}_{p}"
        r = run([pdmpm, "run", str(scene), "--out", str(out[p]), "--quiet"], p)
        if not check(r.returncode == 0, f"{scene.stem}: run as {p} process(es) exits 0" + (f"\n{r.stderr}" if r.returncode else "")):
            write_gate(results, f"distributed.run_command.{scene.stem}.{processes}", claim(scene, processes), 1, REASON)
            return
    one, many, differ, counts = compare_outputs(out[1], out[processes], label, processes)
    metrics = one.get("metrics", {})
    # The scene must exercise what it is for: bonds that break across the processes' boundaries
    # (PD), grid nodes that points of several processes reach (MPM: ghosts).
    broken = metrics.get("broken_bonds", metrics.get("failed_particles", 0))
    if one["model"] == "mpm":
        differ += not check(many.get("ghost_points", 0) > 0, f"{scene.stem}: {many.get('ghost_points')} ghost points")
    else:
        differ += not check(broken > 0, f"{scene.stem}: {broken} bonds broke")
    for key in EXERCISES.get(scene.stem, []):
        differ += not check(many.get(key, 0) > 0, f"{scene.stem}: {key} = {many.get(key)} (> 0)")
    if "crack" in metrics:
        cracks = metrics["crack"].get("cracks", [])
        extent = max((c["extent"] for c in cracks), default=0)
        differ += not check(extent > 0, f"{scene.stem}: a crack tracked to an extent of {extent:.4g} m")
    write_gate(results, f"distributed.run_command.{scene.stem}.{processes}", claim(scene, processes), differ, REASON)
    rows.append([one["scene"], one["model"], one["dimension"], processes, one["particles"],
                 many.get("halo_particles", many.get("ghost_points", 0)), one["steps"], broken,
                 counts["history_rows"], counts["frames"], counts["h5_items"], counts["keys"], differ])


REASON = ("Bitwise identity is the claim: the run's outputs are made from the same particle states (rank_invariance "
          "gates; MPM: every grid node sums its points in one process's order) and from sums taken in the global "
          "particle (node) order, gathered in that order.")


def claim(scene, processes):
    return (f"`mpirun -n {processes} pdmpm run {scene.name}` shall write history.csv and fields.xdmf byte for byte, "
            "every dataset of fields.h5 bit for bit and summary.json (but its timings) as one process does, with "
            "bonds broken or points failed")


def resumption(pdmpm, processes, scene, work, results):
    """Stopped after step 250 (checkpoints every 100), resumed: the one-process outputs."""
    one, out = work / f"{scene.stem}_1", work / f"{scene.stem}_resumed_{processes}"
    wrong = 0
    r = run([pdmpm, "run", str(scene), "--out", str(out), "--quiet", "--checkpoint-every", "100", "--stop-after", "250"],
            processes)
    files = sorted(p.name for p in out.glob("checkpoint.pdmpm*"))
    wrong += not check(r.returncode == 5 and len(files) == processes,
                       f"{scene.stem}: stopped after step 250 under {processes} processes, status {r.returncode} (5), "
                       f"{len(files)} checkpoint files ({processes})")
    other = processes + 1
    r = run([pdmpm, "resume", str(out), "--quiet"], other)
    errors = [line for line in r.stderr.splitlines() if line.startswith("pdmpm")]
    wrong += not check(r.returncode == 2 and len(errors) == 1 and f"mpirun -n {processes}" in r.stderr,
                       f"{scene.stem}: resumed with {other} processes: status {r.returncode} (2), one message naming "
                       f"{processes}" + ("" if r.returncode == 2 and len(errors) == 1 else f"\n{r.stderr}"))
    r = run([pdmpm, "resume", str(out), "--quiet"], processes)
    if not check(r.returncode == 0, f"{scene.stem}: resumed under {processes} processes exits 0"
                 + (f"\n{r.stderr}" if r.returncode else "")):
        wrong += 1
    else:
        _, _, differ, _ = compare_outputs(one, out, f"{scene.stem} resumed, {processes} processes", processes)
        wrong += differ
        wrong += not check(not list(out.glob("checkpoint.pdmpm*")), f"{scene.stem}: no checkpoint left after resuming")
    write_gate(results, f"distributed.run_command.resume.{scene.stem}.{processes}",
               f"`mpirun -n {processes} pdmpm run {scene.name} --checkpoint-every 100 --stop-after 250`, then "
               f"`mpirun -n {processes} pdmpm resume`, shall write the outputs of an uninterrupted one-process run "
               "byte for byte, refuse a resume with another process count and leave no checkpoint (items that "
               "differ or fail)", wrong, REASON)


def refusals(pdmpm, processes, scenes_dir, work, results):
    wrong = 0
    hybrid = scenes_dir.parent.parent / "scenes" / "central_crack" / "fast_expand_shrink.toml"
    pd_scene = scenes_dir / "lps_plate_crack_2d.toml"
    blocked = work / "a_file"
    blocked.write_text("not a directory\n")
    # Contact with a symmetry plane: a distributed contact list holds no mirrors.
    mirrored_contact = work / "mirrored_contact.toml"
    mirrored_contact.write_text((scenes_dir / "pmb_disk_strikes_plate_2d.toml").read_text()
                                + '\n[[symmetry]]\naxis = "x"\nposition = 0.0\n')
    # (what, command, exit status as one process exits, message fragment, output that must not exist)
    cases = [("a hybrid scene", [pdmpm, "run", str(hybrid), "--out", str(work / "hybrid")], 2, "'hybrid'",
              work / "hybrid"),
             ("symmetry planes with contact", [pdmpm, "run", str(mirrored_contact), "--out", str(work / "mc")], 2,
              "with short-range contact", work / "mc"),
             ("an output directory inside a file", [pdmpm, "run", str(pd_scene), "--out", str(blocked / "out")],
              3, "cannot create output directory", None)]
    for what, command, status, fragment, out in cases:
        r = run(command + ["--quiet"], processes)
        errors = [line for line in r.stderr.splitlines() if line.startswith("pdmpm")]
        ok = r.returncode == status and fragment in r.stderr and len(errors) == 1 and "MPI_ABORT" not in r.stderr
        wrong += not check(ok and (out is None or not out.exists()),
                           f"{what} under {processes} processes: status {r.returncode} ({status}), one message, "
                           "nothing written" + ("" if ok else f"\n{r.stderr}"))
    write_gate(results, f"distributed.run_command.refusals.{processes}",
               f"Under mpirun -n {processes}, a hybrid scene, symmetry planes with contact and an output directory that "
               "cannot be made shall each "
               "stop every process with the one-process exit status, one message and nothing "
               "written (cases that do not)", wrong,
               "Each case either behaves or not; a process left waiting would time out the test.")


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    pdmpm, processes = sys.argv[1], int(sys.argv[2])
    results = pathlib.Path(os.environ.get("PDMPM_RESULTS_DIR") or sys.argv[3])
    scenes = [pathlib.Path(s) for s in sys.argv[4:]]
    with tempfile.TemporaryDirectory(prefix="run_invariance_") as tmp:
        work = pathlib.Path(tmp)
        for scene in scenes:
            invariance(pdmpm, processes, scene, work, results)
        for scene in scenes:
            if scene.stem in RESUMED:
                resumption(pdmpm, processes, scene, work, results)
        refusals(pdmpm, processes, scenes[0].parent, work, results)
    write_json(results / "data" / "distributed" / f"run_command_{processes}.json", {
        "kind": "table",
        "title": f"mpirun -n {processes} pdmpm run against pdmpm run: the outputs",
        "columns": ["scene", "model", "dim", "processes", "particles", "halo particles / ghost points (all processes)", "steps",
                    "bonds broken / points failed", "history rows", "frames", "fields.h5 datasets and attributes",
                    "summary keys compared", "differing"],
        "rows": rows,
        "caption": "verification/mpi/scenes/: history.csv and fields.xdmf compared byte for byte, fields.h5 bit "
                   "for bit, summary.json in every key but timings, rates, memory, processes and halo."})
    print(f"{len(failures)} failure(s)")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
