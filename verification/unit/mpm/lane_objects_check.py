"""The MPM's lane objects as solver/mpm/lane_set.hpp promises them.

Run by ctest (test `mpm_lane_objects`, label unit) with the solver library's object files:
- no weak (COMDAT) symbol of a lane object is defined by another object too: the linker
  keeps one copy, so an inline function compiled with one instruction set's flags would
  serve every caller (AVX-512 code in the baseline build, or baseline code in the set);
- with --release (the optimised build without sanitizers, whose instrumentation adds both):
  no lane object has a static constructor (.init_array), which would run the AVX-512 set's
  code at start-up on every machine; and the AVX-512 set compares lanes with vector
  instructions, no scalar `comisd`/`ucomisd` (GCC 12 turned mask combinations in templates
  compiled for the baseline set into eight scalar compares each, which cost the plane-stress
  law half its time).
Exits 1 naming what it found; 0 otherwise.
"""
import pathlib
import subprocess
import sys

SETS = ("lanes_sse2", "lanes_avx2", "lanes_avx512")


def weak_symbols(obj):
    out = subprocess.run(["nm", "--defined-only", obj], capture_output=True, text=True, check=True).stdout
    fields = (line.split() for line in out.splitlines())
    # (DW.ref.__gxx_personality_v0: the exception personality's address, the same in every object)
    return {f[2] for f in fields if len(f) == 3 and f[1] in ("W", "V", "u") and not f[2].startswith("DW.ref.")}


def main(args):
    release = "--release" in args
    objects = [o for a in args if a != "--release" for o in a.split(";") if o]
    lane = {s: [o for o in objects if pathlib.Path(o).name.startswith(s + ".")] for s in SETS}
    problems = [f"object of {s} not among the library's objects" for s, found in lane.items() if len(found) != 1]
    if problems:
        print("\n".join(problems))
        return 1
    weak = {o: weak_symbols(o) for o in objects}
    for s, (obj,) in lane.items():
        for other in objects:
            if other != obj:
                problems += [f"{s}: {name} also defined by {pathlib.Path(other).name}" for name in
                             sorted(weak[obj] & weak[other])]
    if release:
        for s, (obj,) in lane.items():
            sections = subprocess.run(["objdump", "-h", obj], capture_output=True, text=True, check=True).stdout
            if ".init_array" in sections:
                problems.append(f"{s}: a static constructor (.init_array)")
        listing = subprocess.run(["objdump", "-d", lane["lanes_avx512"][0]], capture_output=True, text=True,
                                 check=True).stdout
        scalar = sum(1 for line in listing.splitlines() if "comisd" in line)
        if scalar:
            problems.append(f"lanes_avx512: {scalar} scalar compares (comisd) where the lanes compare as vectors")
    print("\n".join(problems[:20]) if problems else f"lane objects: no shared weak symbols among {len(objects)} objects"
          + (", no static constructor, vector compares" if release else ""))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
