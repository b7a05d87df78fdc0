#!/usr/bin/env python3
"""Writes the broken-scene corpus: one valid base scene and mutations of it,
each of which the solver must reject with exit status 2, a message naming the
key, and no output files. Each file's first line says what the message must
contain: `# expect: <key path> | <message fragment>`.

Regenerate with: /usr/bin/python3 verification/scenes/broken/make_corpus.py
(the cases in HAND_WRITTEN are files of their own and are kept).
"""
from pathlib import Path

BASE = """[scene]
id = "base"

[discretization]
dimension = 2
plane = "strain"
spacing = 1e-3
horizon_ratio = 3.015
thickness = 1e-3

[[shape]]
type = "rectangle"
min = [0.0, 0.0]
max = [0.02, 0.01]

[material]
density = 2500
youngs_modulus = 50e9
poissons_ratio = 0.25
critical_stretch = 0.002

[model]
type = "lps"
influence = "constant"

[time]
end_time = 1e-6

[[boundary]]
name = "left"
kind = "fixed"
region = { type = "box", min = [0.0, 0.0], max = [0.001, 0.01] }
"""


def replace(old, new):
    assert old in BASE, old
    return BASE.replace(old, new, 1)


# The same body as an MPM scene (model type "mpm": no horizon, bonds or critical stretch).
MPM_BASE = replace('type = "lps"\ninfluence = "constant"', 'type = "mpm"').replace("critical_stretch = 0.002\n", "").replace("horizon_ratio = 3.015\n", "")


def mpm(old, new):
    assert old in MPM_BASE, old
    return MPM_BASE.replace(old, new, 1)


# The same material as an elastoplastic PD block (3D; the plain base, 2D, serves the plastic model as well).
PLASTIC_BASE = (replace('type = "lps"\ninfluence = "constant"', 'type = "lps_plastic"')
                .replace('dimension = 2\nplane = "strain"', "dimension = 3").replace("thickness = 1e-3\n", "")
                .replace('type = "rectangle"\nmin = [0.0, 0.0]\nmax = [0.02, 0.01]', 'type = "box"\nmin = [0.0, 0.0, 0.0]\nmax = [0.012, 0.008, 0.008]')
                .replace("min = [0.0, 0.0], max = [0.001, 0.01]", "min = [0.0, 0.0, 0.0], max = [0.001, 0.008, 0.008]")
                .replace("critical_stretch = 0.002", "critical_stretch = 0.002\nyield_stress = 2e8\ntangent_modulus = 1e9"))


def plastic(old, new):
    assert old in PLASTIC_BASE, old
    return PLASTIC_BASE.replace(old, new, 1)


# The same body as an adaptive SBPD–MPM scene: the PD model in [model], the grid in [mpm], a [hybrid] table.
HYBRID_BASE = (replace('type = "lps"\ninfluence = "constant"', 'type = "lps_plastic"')
               .replace("critical_stretch = 0.002", "critical_stretch = 0.002\nyield_stress = 2e8\ntangent_modulus = 1e9")
               + "\n[mpm]\n\n[hybrid]\n")


def hybrid(old, new):
    assert old in HYBRID_BASE, old
    return HYBRID_BASE.replace(old, new, 1)


CASES = {
    "unknown_top_key": ("foo | unknown key", BASE + "\n[foo]\nbar = 1\n"),
    "unknown_material_key": ("material.youngs_modulu | unknown key", replace("density = 2500", "density = 2500\nyoungs_modulu = 1")),
    "missing_density": ("material.density | missing", replace("density = 2500\n", "")),
    "negative_modulus": ("material.youngs_modulus | must be > 0", replace("youngs_modulus = 50e9", "youngs_modulus = -1.0")),
    "zero_density": ("material.density | must be > 0", replace("density = 2500", "density = 0")),
    "lps_incompressible": ("material.poissons_ratio | must be in (-1, 0.5)", replace("poissons_ratio = 0.25", "poissons_ratio = 0.5")),
    "pmb_wrong_poisson": ("material.poissons_ratio | ν = 0.25 only", replace('type = "lps"', 'type = "pmb"').replace("poissons_ratio = 0.25", "poissons_ratio = 0.3")),
    "pmb_plane_stress_poisson": ("material.poissons_ratio | ν = 0.333", replace('type = "lps"', 'type = "pmb"').replace('plane = "strain"', 'plane = "stress"')),
    "horizon_below_spacing": ("discretization.horizon_ratio | must be in [1, 20]", replace("horizon_ratio = 3.015", "horizon_ratio = 0.5")),
    "horizon_in_metres_too_small": ("discretization.horizon | must be ≥ the spacing", replace("horizon_ratio = 3.015", "horizon = 0.5e-3")),
    "both_horizons": ("discretization.horizon_ratio | exactly one", replace("horizon_ratio = 3.015", "horizon_ratio = 3.015\nhorizon = 3e-3")),
    "negative_thickness": ("discretization.thickness | must be > 0", replace("thickness = 1e-3", "thickness = -1e-3")),
    "spacing_wrong_type": ("discretization.spacing | must be a number, got a string", replace("spacing = 1e-3", 'spacing = "1mm"')),
    "dimension_four": ("discretization.dimension | must be 1, 2 or 3", replace("dimension = 2", "dimension = 4")),
    "unknown_plane": ("discretization.plane | \"stress\" or \"strain\"", replace('plane = "strain"', 'plane = "membrane"')),
    "missing_plane": ("discretization.plane | missing", replace('plane = "strain"\n', "")),
    "empty_body": ("shape | contain no lattice site", replace("max = [0.02, 0.01]", "max = [0.0001, 0.0001]")),
    "no_shape": ("shape | at least one [[shape]]", replace('[[shape]]\ntype = "rectangle"\nmin = [0.0, 0.0]\nmax = [0.02, 0.01]\n', "")),
    "shape_wrong_length": ("shape[0].min | exactly 2 numbers", replace("min = [0.0, 0.0]\nmax = [0.02, 0.01]", "min = [0.0, 0.0, 0.0]\nmax = [0.02, 0.01]")),
    "shape_inverted": ("shape[0].max | must be ≥ min", replace("max = [0.02, 0.01]", "max = [-0.02, 0.01]")),
    "unknown_shape": ("shape[0].type | must be one of box", replace('type = "rectangle"', 'type = "hexagon"')),
    "empty_region": ("boundary[0].region | selects no particle", replace("min = [0.0, 0.0], max = [0.001, 0.01]", "min = [0.5, 0.5], max = [0.6, 0.6]")),
    "dt_above_stable": ("time.dt | above the stable step", replace("end_time = 1e-6", "end_time = 1e-6\ndt = 1e-3")),
    "end_time_and_steps": ("time.end_time | exactly one of end_time and steps", replace("end_time = 1e-6", "end_time = 1e-6\nsteps = 10")),
    "no_end": ("time.end_time | exactly one of end_time and steps", replace("end_time = 1e-6", "")),
    "negative_end_time": ("time.end_time | must be > 0", replace("end_time = 1e-6", "end_time = -1e-6")),
    "safety_too_large": ("time.safety_factor | must be in (0, 2]", replace("end_time = 1e-6", "end_time = 1e-6\nsafety_factor = 3.0")),
    "dt_and_safety": ("time.safety_factor | either dt or safety_factor", replace("end_time = 1e-6", "end_time = 1e-6\ndt = 1e-9\nsafety_factor = 0.5")),
    "bad_toml": ("not valid TOML", replace("density = 2500", "density = = 2500")),
    "bad_expression": ("boundary[0].value | at character", replace('kind = "fixed"', 'kind = "displacement"\nvalue = ["1e-3 *", 0]')),
    "unknown_boundary_kind": ("boundary[0].kind | must be one of fixed", replace('kind = "fixed"', 'kind = "glued"')),
    "value_on_fixed": ("boundary[0].value | not used by kind", replace('kind = "fixed"', 'kind = "fixed"\nvalue = [0, 0]')),
    "displacement_without_value": ("boundary[0].value | missing", replace('kind = "fixed"', 'kind = "displacement"')),
    "unknown_influence": ("model.influence | must be one of constant", replace('influence = "constant"', 'influence = "cubic"')),
    "unknown_model": ("model.type | must be one of pmb, lps", replace('type = "lps"', 'type = "bondless"')),
    "unknown_partial_volume": ("discretization.partial_volume | none, seed001, extended", replace("thickness = 1e-3", 'thickness = 1e-3\npartial_volume = "half"')),
    "symmetry_off_lattice": ("symmetry[0].position | lattice sites or midway", BASE + '\n[[symmetry]]\naxis = "x"\nposition = -0.0003\n'),
    "spacing_too_fine": ("discretization.spacing | 32-bit integers", replace("spacing = 1e-3", "spacing = 1e-7")),
    "symmetry_far_away": ("symmetry[0].position | must touch the body", BASE + '\n[[symmetry]]\naxis = "x"\nposition = -1e308\n'),
    "symmetry_through_body": ("symmetry[0] | both sides", BASE + '\n[[symmetry]]\naxis = "x"\nposition = 0.0105\n'),
    "precrack_outside": ("precrack[0] | cuts no bond", BASE + "\n[[precrack]]\nfrom = [0.5, 0.5]\nto = [0.6, 0.5]\n"),
    "probe_outside": ("probe[0].point | not inside the body", BASE + '\n[[probe]]\nname = "p"\npoint = [1.0, 1.0]\n'),
    "negative_critical_stretch": ("material.critical_stretch | must be > 0", replace("critical_stretch = 0.002", "critical_stretch = -0.002")),
    "damage_without_criterion": ("model.damage | needs material.critical_stretch", replace("critical_stretch = 0.002\n", "").replace('influence = "constant"', 'influence = "constant"\ndamage = true')),
    "unknown_output_field": ("output.fields | unknown field", BASE + '\n[output]\nfields = ["damage", "temperature"]\n'),
    "unknown_callback": ("boundary[0].callback | must be one of affine", replace('kind = "fixed"', 'kind = "analytic"\ncallback = "vortex"')),
    "callback_missing_parameter": ("boundary[0].parameters | needs parameter", replace('kind = "fixed"', 'kind = "analytic"\ncallback = "spherical_wave"\nparameters = { r0 = 0.01 }')),
    "empty_file": ("scene | missing", ""),
    "frames_zero": ("output.frames | must be ≥ 1", BASE + "\n[output]\nframes = 0\n"),
    "thickness_in_3d": ("discretization.plane | only for dimension = 2", replace("dimension = 2", "dimension = 3")),
    "crack_threshold_above_one": ("crack.threshold | must be in (0, 1]", BASE + "\n[crack]\nthreshold = 1.5\n"),
    "crack_unknown_key": ("crack.threshhold | unknown key", BASE + "\n[crack]\nthreshhold = 0.5\n"),
    "crack_exclude_outside": ("crack.exclude | selects no particle", BASE + '\n[crack]\nexclude = { type = "box", min = [0.5, 0.5], max = [0.6, 0.6] }\n'),
    "observe_outside": ("observe[0].point | no particle lies within", BASE + '\n[[observe]]\nname = "tip"\npoint = [1.0, 1.0]\n'),
    "observe_same_name": ("observe[1].name | is used by another", BASE + '\n[[observe]]\nname = "tip"\npoint = [0.01, 0.005]\n\n[[observe]]\nname = "tip"\npoint = [0.011, 0.005]\n'),
    "observe_negative_radius": ("observe[0].radius | must be > 0", BASE + '\n[[observe]]\nname = "tip"\npoint = [0.01, 0.005]\nradius = -1e-3\n'),
    "unknown_break_timing": ("model.break_timing | before_force", replace('influence = "constant"', 'influence = "constant"\nbreak_timing = "later"')),
    "unknown_indenter_law": ("indenter.law | force_density", BASE + '\n[indenter]\nradius = 0.002\ncenter = [0.01, 0.012]\nvelocity = [0.0, -10.0]\nstiffness = 1e17\nlaw = "pressure"\n'),
    "frame_times_and_frames": ("output.frame_times | at most one of frames, every and frame_times", BASE + "\n[output]\nframes = 3\nframe_times = [1e-7]\n"),
    "negative_frame_time": ("output.frame_times | must be ≥ 0", BASE + "\n[output]\nframe_times = [-1e-7]\n"),
    "weighted_volume_for_pmb": ("model.weighted_volume | only for type = \"lps\"", replace('type = "lps"', 'type = "pmb"').replace('influence = "constant"', 'influence = "constant"\nweighted_volume = "continuum"').replace("poissons_ratio = 0.25\n", "")),
    "unknown_weighted_volume": ("model.weighted_volume | must be one of discrete, continuum", replace('influence = "constant"', 'influence = "constant"\nweighted_volume = "integral"')),
    "mpm_precrack": ("precrack[0] | pre-cracks cut PD bonds", MPM_BASE + "\n[[precrack]]\nfrom = [0.0, 0.005]\nto = [0.005, 0.005]\n"),
    "mpm_displacement_boundary": ("boundary[0].kind | constrains grid velocities", mpm('kind = "fixed"', 'kind = "displacement"\nvalue = ["0", "0"]')),
    "mpm_disk_region": ("boundary[0].region | as boxes", mpm('region = { type = "box", min = [0.0, 0.0], max = [0.001, 0.01] }', 'region = { type = "disk", center = [0.0, 0.0], radius = 0.002 }')),
    "mpm_region_without_nodes": ("boundary[0].region | contains no grid node", mpm("min = [0.0, 0.0], max = [0.001, 0.01]", "min = [0.0005, 0.0], max = [0.0015, 0.01]")),
    "mpm_symmetry_far_away": ("symmetry[0].position | must lie on a face", MPM_BASE + '\n[[symmetry]]\naxis = "x"\nposition = -1e308\n'),
    "mpm_symmetry_cuts_body": ("symmetry[0].position | cuts the body", MPM_BASE + '\n[[symmetry]]\naxis = "x"\nposition = 0.01\n'),
    "mpm_critical_stretch": ("material.critical_stretch | only for the peridynamic models", mpm("density = 2500", "density = 2500\ncritical_stretch = 0.01")),
    "mpm_yield_without_j2": ("material.yield_stress | only for constitutive", mpm("density = 2500", "density = 2500\nyield_stress = 1e8")),
    "mpm_failure_without_j2": ("material.failure | needs constitutive", MPM_BASE + "\n[material.failure]\nd0 = 0.5\nc = -1.5\n"),
    "mpm_unknown_shape_function": ("mpm.shape_function | cubic", MPM_BASE + '\n[mpm]\nshape_function = "cubic"\n'),
    "mpm_moving_fixed_boundary": ("boundary[0].moving | only for kind = \"velocity\"", mpm('kind = "fixed"', 'kind = "fixed"\nmoving = true')),
    "moving_boundary_for_pd": ("boundary[0].moving | only for MPM and hybrid scenes", replace('kind = "fixed"', 'kind = "velocity"\nvalue = [0.1, "free"]\nmoving = true')),
    "mpm_cfl_above_one": ("time.safety_factor | CFL number", mpm("end_time = 1e-6", "end_time = 1e-6\nsafety_factor = 1.5")),
    "mpm_influence": ("model.influence | only for the peridynamic models", mpm('type = "mpm"', 'type = "mpm"\ninfluence = "constant"')),
    "mpm_table_for_pd": ("mpm | only for model type", BASE + '\n[mpm]\nshape_function = "gimp"\n'),
    "plastic_zero_yield": ("material.yield_stress | must be > 0", plastic("yield_stress = 2e8", "yield_stress = 0")),
    "plastic_missing_yield": ("material.yield_stress | missing", plastic("yield_stress = 2e8\n", "")),
    "plastic_tangent_above_e": ("material.tangent_modulus | must be in [0, 5e+10)", plastic("tangent_modulus = 1e9", "tangent_modulus = 6e10")),
    "plastic_tangent_equal_e": ("material.tangent_modulus | must be in [0, 5e+10)", plastic("tangent_modulus = 1e9", "tangent_modulus = 50e9")),
    "plastic_tangent_negative": ("material.tangent_modulus | must be in [0, 5e+10)", plastic("tangent_modulus = 1e9", "tangent_modulus = -1e9")),
    "plastic_symmetry": ("symmetry[0] | symmetry planes are not supported", PLASTIC_BASE + '\n[[symmetry]]\naxis = "x"\nposition = 0.0\n'),
    "ductile_failure_for_elastic_pd": ("material.failure | acts on the equivalent plastic strain", BASE + "\n[material.failure]\nd0 = 0.5\nc = -1.5\n"),
    "plastic_failure_damage_off": ("material.failure | switches every failure rule off", plastic('type = "lps_plastic"', 'type = "lps_plastic"\ndamage = false') + "\n[material.failure]\nd0 = 0.5\nc = -1.5\n"),
    "plastic_failure_zero_d0": ("material.failure.d0 | must be > 0", PLASTIC_BASE + "\n[material.failure]\nd0 = 0\nc = -1.5\n"),
    "plastic_failure_unknown_rule": ("material.failure.rule | must be one of strain, accumulated", PLASTIC_BASE + "\n[material.failure]\nd0 = 0.5\nc = -1.5\nrule = \"sum\"\n"),
    "yield_for_elastic_pd": ("material.yield_stress | only for the plastic models", replace("critical_stretch = 0.002", "critical_stretch = 0.002\nyield_stress = 2e8")),
    "isotropy_for_elastic_pd": ("model.isotropy | only for the plastic models", replace('influence = "constant"', 'influence = "constant"\nisotropy = "lattice"')),
    "plastic_unknown_isotropy": ("model.isotropy | must be one of corrected, lattice", plastic('type = "lps_plastic"', 'type = "lps_plastic"\nisotropy = "cubic"')),
    "damaged_yield_for_elastic_pd": ("model.damaged_yield | only for the plastic models", replace('influence = "constant"', 'influence = "constant"\ndamaged_yield = "live_bonds"')),
    "plastic_unknown_damaged_yield": ("model.damaged_yield | must be one of reference_family, live_bonds", plastic('type = "lps_plastic"', 'type = "lps_plastic"\ndamaged_yield = "live"')),
    "hybrid_1d": ("discretization.dimension | the hybrid needs dimension = 2 or 3", hybrid('dimension = 2\nplane = "strain"', "dimension = 1").replace("thickness = 1e-3", "area = 1e-6")),
    "hybrid_missing_mpm": ("mpm | a hybrid scene needs the [mpm] table", hybrid("\n[mpm]\n", "")),
    "hybrid_mpm_model": ("model.type | needs the PD model in [model]", hybrid('type = "lps_plastic"', 'type = "mpm"')),
    "hybrid_pmb_model": ("model.type | needs the PD model in [model]", hybrid('type = "lps_plastic"', 'type = "pmb"')),
    "hybrid_unknown_mode": ("hybrid.mode | must be one of pd, expand, expand_shrink", hybrid("[hybrid]\n", '[hybrid]\nmode = "grow"\n')),
    "hybrid_unknown_coupling": ("hybrid.coupling | must be one of paper, full_state", hybrid("[hybrid]\n", '[hybrid]\ncoupling = "consistent"\n')),
    "hybrid_unknown_plastic_transfer": ("hybrid.plastic_transfer | must be one of strain, elastic_state", hybrid("[hybrid]\n", '[hybrid]\nplastic_transfer = "finite"\n')),
    "hybrid_zero_radius": ("hybrid.pd_radius | must be a positive, finite number of horizons", hybrid("[hybrid]\n", "[hybrid]\npd_radius = 0\n")),
    "hybrid_negative_keep_radius": ("hybrid.keep_radius | must be a positive, finite number of horizons", hybrid("[hybrid]\n", "[hybrid]\nkeep_radius = -2\n")),
    "hybrid_trigger_above_radius": ("hybrid.expand_trigger | must be smaller than hybrid.expand_radius", hybrid("[hybrid]\n", "[hybrid]\nexpand_trigger = 7\nexpand_radius = 7\n")),
    "hybrid_unknown_key": ("hybrid.pd_radus | unknown key", hybrid("[hybrid]\n", "[hybrid]\npd_radus = 7\n")),
    "hybrid_shrink_every_zero": ("hybrid.shrink_every | must be an integer in [1, 1000000]", hybrid("[hybrid]\n", "[hybrid]\nshrink_every = 0\n")),
    "hybrid_tips_damage_threshold": ("hybrid.tips.damage_threshold | must be in (0, 1)", HYBRID_BASE + "\n[hybrid.tips]\ndamage_threshold = 1.5\n"),
    "hybrid_tips_ridge_fraction": ("hybrid.tips.ridge_fraction | must be in [0, 1]", HYBRID_BASE + "\n[hybrid.tips]\nridge_fraction = 1.5\n"),
    "hybrid_tips_zero_merge_radius": ("hybrid.tips.merge_radius | must be in (0, 1e+06]", HYBRID_BASE + "\n[hybrid.tips]\nmerge_radius = 0\n"),
    "hybrid_tips_unknown_key": ("hybrid.tips.radius | unknown key", HYBRID_BASE + "\n[hybrid.tips]\nradius = 3\n"),
    "hybrid_symmetry": ("symmetry[0] | not supported in a hybrid scene", HYBRID_BASE + '\n[[symmetry]]\naxis = "x"\nposition = 0.0\n'),
    "hybrid_wrong_constitutive": ("material.constitutive | must be \"j2\" for the hybrid", hybrid("density = 2500", 'density = 2500\nconstitutive = "linear_elastic"')),
    "hybrid_displacement_boundary": ("boundary[0].kind | the hybrid constrains grid velocities", hybrid('kind = "fixed"', 'kind = "displacement"\nvalue = ["0", "0"]')),
    "initial_unknown_key": ("initial[0].velocty | unknown key", BASE + '\n[[initial]]\nvelocty = [1.0, 0.0]\n'),
    "initial_wrong_count": ("initial[0].velocity | exactly 2 components", BASE + '\n[[initial]]\nvelocity = [1.0, 0.0, 0.0]\n'),
    "initial_bad_expression": ("initial[0].displacement | at character", BASE + '\n[[initial]]\ndisplacement = ["1e-6 * sin(x", 0]\n'),
    "initial_uses_time": ("initial[0].velocity | initial values are at t = 0", BASE + '\n[[initial]]\nvelocity = ["10 * t", 0]\n'),
    "initial_without_values": ("initial[0] | needs velocity, displacement or both", BASE + '\n[[initial]]\nregion = { type = "box", min = [0.0, 0.0], max = [0.01, 0.01] }\n'),
    "initial_all_free": ("initial[0].displacement | the table sets nothing", BASE + '\n[[initial]]\ndisplacement = ["free", "free"]\n'),
    "initial_unknown_region_type": ("initial[0].region.type | must be one of box", BASE + '\n[[initial]]\nregion = { type = "hexagon", center = [0.01, 0.005] }\nvelocity = [1.0, 0.0]\n'),
    "initial_empty_region": ("initial[0].region | selects no particle", BASE + '\n[[initial]]\nregion = { type = "disk", center = [0.5, 0.5], radius = 0.01 }\nvelocity = [1.0, 0.0]\n'),
    "initial_velocity_adr": ("initial[0].velocity | not used by integrator = \"adr\"", replace("end_time = 1e-6", 'integrator = "adr"') + '\n[[initial]]\nvelocity = [1.0, 0.0]\n'),
    "mpm_initial_empty_region": ("initial[0].region | selects no particle", MPM_BASE + '\n[[initial]]\nregion = { type = "box", min = [0.5, 0.5], max = [0.6, 0.6] }\ndisplacement = ["1e-6 * x", 0]\n'),
    "hybrid_initial_empty_region": ("initial[0].region | selects no particle", HYBRID_BASE + '\n[[initial]]\nregion = { type = "box", min = [0.5, 0.5], max = [0.6, 0.6] }\nvelocity = [1.0, 0.0]\n'),
    "hybrid_adr": ("time.integrator | the hybrid steps explicitly", hybrid("end_time = 1e-6", 'end_time = 1e-6\nintegrator = "adr"').replace("end_time = 1e-6\n", "", 1)),
}


# Cases written by hand in this directory (their scenes need more than a mutation of
# the bases above); regenerating keeps them.
HAND_WRITTEN = {
    "constitutive_for_lps",
    "hpd_axial_1d_with_poisson_ratio",
    "hpd_j2_without_yield_stress",
    "hpd_overlap_min_points_below_dimension",
    "hpd_stabilization_negative",
    "hpd_symmetry",
    "hpd_too_few_overlap_points",
    "j_integral_empty_ring",
    "j_integral_plastic_pd",
    "j_integral_ring_reversed",
}


def main():
    here = Path(__file__).resolve().parent
    clash = HAND_WRITTEN & CASES.keys()
    if clash:
        raise SystemExit(f"make_corpus.py: generated and hand-written cases share names: {sorted(clash)}")
    for old in here.glob("*.toml"):
        if old.stem not in HAND_WRITTEN:
            old.unlink()
    for name, (expect, text) in sorted(CASES.items()):
        (here / f"{name}.toml").write_text(f"# expect: {expect}\n{text}")
    print(f"wrote {len(CASES)} broken scenes to {here}")


if __name__ == "__main__":
    main()
