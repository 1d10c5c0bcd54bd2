#!/usr/bin/env python3
"""Generates the bad-input corpus of tests/t175_badinput_corpus.cmake (see README.md here).

    python3 tests/badinput/gen_corpus.py [--check build/pdk]

writes, under tests/badinput/:
    base/<name>.yaml    the shipped scenes (scenes/, tests/scenes/) made small: a coarser spacing
                        and a short end time, so `pdk check` builds each in a fraction of a second;
                        every one of them is a valid scene (the test checks that first)
    cases/<id>.yaml     one mutation of a base scene per file (a scene case)
    cases/<id>.rep      a large case written by the test at run time: the file's text with its one
                        @@REPEAT <count> <text>@@ marker replaced by <text> repeated <count> times
    cases.tsv           the manifest: one case per line (format below)

Every case is an input pdk must refuse: exit status 1 or 2 (not a signal, not 0), a message on
stderr (naming the scene file or the override), no sanitizer report, and no file left in the
output folder or the working folder. Fine inputs do not belong here.

Manifest columns (tab-separated; '-' is an empty field):
    id      the case's name, [a-z0-9_]
    rows    issue rows the case exercises (comma-separated), or '-' when it is a guard of
            behaviour that is right today; 'n<k>' rows are findings without a row in the issue
    as      file name to copy cases/<id>.yaml to before running (a bad file stem), or '-'
    names   text stderr must contain (the scene file's name, or the option), or '-'
    msg     CMake regular expression stderr must match, or '-'
    nomsg   CMake regular expression stderr must not match, or '-'
    argv... the pdk command line; @CASE@ is the case file (or its copy), @BASE:<name>@ a base
            scene, @SRC@ the source tree, @CLI@ the pdk executable, @OUT@ a fresh output folder
Fields escape '%', tab, newline, '\\', ';', '[' and ']' (and any byte outside printable ASCII) as
%XX, so the CMake test can read them as lists and get every byte back.

With --check PDK the generator runs `PDK check` on every base (each must be valid and fast) and
prints what every case gives today; it never decides a case's outcome from that run.
"""
import argparse
import math
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.dirname(os.path.dirname(HERE))

# ---- the base scenes -----------------------------------------------------------------------------
# name: (source, [(old, new), ...] substitutions that make it small; each must match exactly once)
BASES = {
    "plate_two_holes": ("scenes/plate_two_holes.yaml",
                        [("spacing: 0.5e-3", "spacing: 2.0e-3"),
                         ("end_time: 2.0e-3", "end_time: 2.0e-5")]),
    "plate_hole": ("scenes/plate_hole.yaml", [("spacing: 0.5e-3", "spacing: 2.0e-3")]),
    "plate_two_holes_close": ("scenes/plate_two_holes_close.yaml",
                              [("spacing: 0.5e-3", "spacing: 2.5e-3"),
                               ("end_time: 2.6e-3", "end_time: 2.0e-5")]),
    "bar_tension": ("scenes/bar_tension.yaml", [("spacing: 1.0e-3", "spacing: 4.0e-3")]),
    "bar_tension_static": ("scenes/bar_tension_static.yaml", []),
    "block_3d": ("scenes/block_3d.yaml", [("spacing: 1.0e-3", "spacing: 5.0e-3")]),
    "bar": ("tests/scenes/t092_bar.yaml", [("solver: {steps: 400}", "solver: {steps: 20}")]),
    "bimaterial": ("tests/scenes/t065_bimaterial.yaml", []),
    "minimal": ("tests/scenes/t060_minimal.yaml", []),
    "static_block": ("tests/scenes/t094_static.yaml", []),
    "taylor_anvil": ("scenes/taylor_anvil.yaml", [("spacing: 0.4e-3", "spacing: 1.6e-3"),
                                                   ("end_time: 80.0e-6", "end_time: 2.0e-6")]),
}


def strip_header(text):
    """Drops the leading comment block (the cases' line numbers then start at the scene)."""
    lines = text.split("\n")
    k = 0
    while k < len(lines) and (lines[k].startswith("#") or not lines[k].strip()):
        k += 1
    return "\n".join(lines[k:])


def make_bases():
    out = {}
    for name, (src, subs) in BASES.items():
        with open(os.path.join(SRC, src), encoding="utf-8") as f:
            text = strip_header(f.read())
        for old, new in subs:
            if text.count(old) != 1:
                sys.exit(f"gen_corpus: '{old}' occurs {text.count(old)} times in {src}")
            text = text.replace(old, new)
        keys = ", ".join(o.split(":")[0] for o, _ in subs)
        note = f"made small for the bad-input corpus: {keys} changed" if subs else "unchanged"
        out[name] = f"# {src}, {note}\n" + text
    return out


# ---- the cases -----------------------------------------------------------------------------------
class Corpus:
    def __init__(self, bases):
        self.bases = bases
        self.cases = []  # dicts
        self.files = {}  # file name under cases/ -> bytes

    def _add(self, cid, rows, argv, as_=None, names=None, msg=None, nomsg=None):
        if not re.fullmatch(r"[a-z0-9_]+", cid):
            sys.exit(f"gen_corpus: bad case id {cid!r}")
        if any(c["id"] == cid for c in self.cases):
            sys.exit(f"gen_corpus: case id {cid} given twice")
        self.cases.append(dict(id=cid, rows=rows, as_=as_, names=names, msg=msg, nomsg=nomsg,
                               argv=argv))

    def scene(self, cid, rows, text, msg=None, nomsg=None, cmd="check", extra=(), as_=None,
              names=None, rep=False):
        """A scene case: text is the whole file (str or bytes)."""
        data = text.encode("utf-8") if isinstance(text, str) else text
        fname = cid + (".rep" if rep else ".yaml")
        self.files[fname] = data
        if names is None:
            names = as_ if as_ else cid + ".yaml"
        elif names is False:  # a failure of the run, not of the scene: no file name required
            names = None
        argv = [cmd, "@CASE@"]
        if cmd == "run":
            argv += ["-o", "@OUT@", "-q"]
        argv += list(extra)
        self._add(cid, rows, argv, as_=as_, names=names, msg=msg, nomsg=nomsg)

    def mut(self, cid, rows, base, old, new, msg=None, **kw):
        """A scene case: base with old (which must occur exactly once) replaced by new."""
        text = self.bases[base]
        if text.count(old) != 1:
            sys.exit(f"gen_corpus: {cid}: '{old}' occurs {text.count(old)} times in base {base}")
        self.scene(cid, rows, text.replace(old, new, 1), msg=msg, **kw)

    def append(self, cid, rows, base, tail, msg=None, **kw):
        self.scene(cid, rows, self.bases[base].rstrip("\n") + "\n" + tail, msg=msg, **kw)

    def override(self, cid, rows, base, sets, msg=None, nomsg=None, cmd="check", names=None):
        """A command-line case: base scene with --set overrides."""
        argv = [cmd, f"@BASE:{base}@"]
        if cmd == "run":
            argv += ["-o", "@OUT@", "-q"]
        for s in sets:
            argv += ["--set", s]
        self._add(cid, rows, argv, names=names or base + ".yaml", msg=msg, nomsg=nomsg)

    def cli(self, cid, rows, argv, names=None, msg=None, nomsg=None):
        self._add(cid, rows, argv, names=names, msg=msg, nomsg=nomsg)


def build(c):
    B = c.bases
    PT, PH, BT, ST, BK, BAR, BM = ("plate_two_holes", "plate_hole", "bar_tension",
                                   "bar_tension_static", "block_3d", "bar", "bimaterial")

    # -- wrong types: a word, a list, a mapping or nothing where another type belongs ------------
    c.mut("type_spacing_word", "-", PT, "spacing: 2.0e-3", "spacing: fine", "geometry.spacing")
    c.mut("type_spacing_list", "-", PT, "spacing: 2.0e-3", "spacing: [2.0e-3]", "spacing")
    c.mut("type_spacing_null", "-", PT, "spacing: 2.0e-3", "spacing:", "spacing")
    c.mut("type_density_string", "-", PT, "density: 7830", 'density: "heavy"', "density")
    c.mut("type_kind_number", "-", PT, "kind: correspondence", "kind: 3", "model.kind")
    c.mut("type_bond_lengths_word", "-", BAR, "critical_stretch: 0.002}",
          "critical_stretch: 0.002, bond_lengths: cached}", "bond_lengths")
    c.mut("type_law_map", "-", PT, "law: jc", "law: {jc: 1}", "law")
    c.mut("type_holes_scalar", "-", PT, "  holes:\n", "  holes: 2\n  unused_holes:\n", "holes")
    c.mut("type_geometry_scalar", "-", BAR, "geometry:\n", "geometry: square\ngeometry_:\n",
          "geometry")
    c.mut("type_box_list", "-", PT, "box: {lo: [0, 0], hi: [0.05, 0.1]}",
          "box: [[0, 0], [0.05, 0.1]]", "box")
    c.mut("type_point_scalar", "-", PT, "lo: [0, 0], hi: [0.05, 0.1]",
          "lo: 0, hi: [0.05, 0.1]", "lo")
    c.mut("type_point_short", "-", PT, "lo: [0, 0], hi: [0.05, 0.1]",
          "lo: [0], hi: [0.05, 0.1]", "lo")
    c.mut("type_point_nested", "-", PT, "lo: [0, 0], hi: [0.05, 0.1]",
          "lo: [[0, 0]], hi: [0.05, 0.1]", "lo")
    c.mut("type_point_3d_short", "-", BT, "hi: [0.1, 0.01, 0.016]", "hi: [0.1, 0.01]", "hi")
    c.mut("type_fields_scalar", "-", PT, "fields: [u, v, eps_p, damage, failed, von_mises]",
          "fields: u", "fields")
    c.mut("type_name_list", "-", PT, "name: plate_two_holes", "name: [plate, two]", "name")
    c.mut("type_bool_list", "-", BAR, "solver: {steps: 20}",
          "solver: {steps: 20, force_dt: [true]}", "force_dt")
    c.mut("type_set_number", "-", BAR, "{set: left, type: displacement, x: 0, y: 0}",
          "{set: 7, type: displacement, x: 0, y: 0}", "set")
    c.scene("type_top_list", "-", "- dimension: 2\n- geometry: {}\n")
    c.scene("type_top_scalar", "-", "a plate with two holes\n")
    c.mut("type_steps_fraction", "-", BAR, "steps: 20", "steps: 20.5", "steps")
    c.mut("type_seed_negative", "-", PT, "thickness: 1.0e-3",
          "thickness: 1.0e-3\n  jitter: 0.1\n  seed: -1", "seed")
    c.mut("type_velocity_gradient_short", "-", BK,
          "velocity_gradient: [[10, 0, 0], [0, 10, 0], [0, 0, 10]]",
          "velocity_gradient: [[10, 0, 0], [0, 10, 0]]", "velocity_gradient")

    # -- out of range ----------------------------------------------------------------------------
    rng = [
        ("range_spacing_zero", PT, "spacing: 2.0e-3", "spacing: 0", "spacing"),
        ("range_spacing_negative", PT, "spacing: 2.0e-3", "spacing: -2.0e-3", "spacing"),
        ("range_spacing_too_big", PT, "spacing: 2.0e-3", "spacing: 1.0", "spacing"),
        ("range_horizon_one", PT, "horizon_factor: 3.015", "horizon_factor: 1", "horizon_factor"),
        ("range_thickness_zero", PT, "thickness: 1.0e-3", "thickness: 0", "thickness"),
        ("range_jitter_half", PT, "thickness: 1.0e-3", "thickness: 1.0e-3\n  jitter: 0.5",
         "jitter"),
        ("range_box_inverted", PT, "hi: [0.05, 0.1]", "hi: [-0.05, 0.1]", "box"),
        ("range_hole_radius_zero", PT, "radius: 0.005}\n    - disk: {center: [0.0325",
         "radius: 0}\n    - disk: {center: [0.0325", "radius"),
        ("range_hole_outside", PT, "center: [0.0175, 0.0425]", "center: [0.5, 0.0425]", "holes"),
        ("range_hole_covers_all", PH, "radius: 0.005", "radius: 5.0", "holes"),
        ("range_density_zero", PT, "density: 7830", "density: 0", "density"),
        ("range_youngs_negative", PT, "youngs_modulus: 200.0e9", "youngs_modulus: -200.0e9",
         "youngs_modulus"),
        ("range_poisson_half", PT, "poisson_ratio: 0.29", "poisson_ratio: 0.5", "poisson_ratio"),
        ("range_jc_n_zero", PT, "n: 0.26", "n: 0", "johnson_cook.n"),
        ("range_jc_a_b_zero", PT, "A: 792.0e6                  # Pa\n    B: 510.0e6",
         "A: 0\n    B: 0", "johnson_cook"),
        ("range_jc_dc_zero", PT, "D_c: 0.3", "D_c: 0", "D_c"),
        ("range_jc_dc_above_one", PT, "D_c: 0.3", "D_c: 1.5", "D_c"),
        ("range_stab_coeff_negative", PT, "stabilization_coefficient: 0.1",
         "stabilization_coefficient: -0.1", "stabilization_coefficient"),
        ("range_safety_zero", PT, "safety: 0.8", "safety: 0", "safety"),
        ("range_safety_above_one", PT, "safety: 0.8", "safety: 1.5", "safety"),
        ("range_end_time_zero", PT, "end_time: 2.0e-5", "end_time: 0", "end_time"),
        ("range_steps_zero", BAR, "steps: 20", "steps: 0", "steps"),
        ("range_dt_negative", BAR, "steps: 20", "steps: 20, dt: -1.0e-7", "dt"),
        ("range_dt_update_interval_auto", BAR, "steps: 20",
         "steps: 20, dt_update: auto, dt_update_interval: 50", "dt_update_interval"),
        ("range_dt_update_interval_default", BAR, "steps: 20",
         "steps: 20, dt_update_interval: 50", "dt_update_interval"),
        ("range_dt_unstable", BAR, "steps: 20", "steps: 20, dt: 1.0e-3", "dt"),
        ("range_threads_huge", BAR, "steps: 20", "steps: 20, threads: 5000", "threads"),
        ("range_field_interval_negative", BAR, "field_interval: 100", "field_interval: -1",
         "field_interval"),
        ("range_history_interval_zero", BAR, "history_interval: 10", "history_interval: 0",
         "history_interval"),
        ("range_critical_stretch_negative", BAR, "critical_stretch: 0.002",
         "critical_stretch: -0.002", "critical_stretch"),
        ("range_load_steps_zero", ST, "load_steps: 5", "load_steps: 0", "load_steps"),
        ("range_galerkin_normals_word", ST,
         "model: {kind: correspondence, law: linear_elastic, influence: constant, stabilization: silling}",
         "model: {kind: galerkin, galerkin: {correction: vc1, surface: held, normals: sphere}}",
         "normals"),
        ("range_galerkin_normals_no_vc1", ST,
         "model: {kind: correspondence, law: linear_elastic, influence: constant, stabilization: silling}",
         "model: {kind: galerkin, galerkin: {normals: box}}", "normals"),
        ("range_load_steps_huge", ST, "load_steps: 5", "load_steps: 2000000", "load_steps"),
        ("range_tolerance_one", ST, "tolerance: 1.0e-6", "tolerance: 1", "tolerance"),
        ("range_load_levels_decreasing", ST, "load_steps: 5", "load_levels: [0.5, 0.25, 1.0]",
         "load_levels"),
        ("range_bc_duration_zero", BAR, "duration: 1.0e-5", "duration: 0", "duration"),
        ("range_lattice_3d_in_2d", PT, "lattice: square", "lattice: cubic", "lattice"),
        ("range_dimension_four", PT, "dimension: 2", "dimension: 4", "dimension"),
        ("range_kind_unknown", PT, "kind: correspondence", "kind: fem", "kind"),
        ("range_field_unknown", BAR, "fields: [u, v]", "fields: [u, v, temperature]", "fields"),
        ("range_set_empty", BAR, "hi: [0.003, 1]", "hi: [-0.5, 1]", "left"),
        ("range_bc_undefined_set", BAR, "{set: left, type: displacement",
         "{set: middle, type: displacement", "middle"),
        ("range_bc_no_component", BAR, "{set: left, type: displacement, x: 0, y: 0}",
         "{set: left, type: displacement}", "boundary_conditions"),
        ("range_bc_z_in_2d", BAR, "{set: left, type: displacement, x: 0, y: 0}",
         "{set: left, type: displacement, x: 0, y: 0, z: 0}", "z"),
        ("range_set_named_all", BAR, "{name: left,", "{name: all,", "all"),
        ("range_set_twice", BAR, "{name: right,", "{name: left,", "left"),
        ("range_reactions_unknown", BAR, "reactions: [left, right]", "reactions: [left, middle]",
         "middle"),
        ("range_precrack_zero_length", PH, "  holes:\n",
         "  precracks:\n    - segment: [[0.03, 0.05], [0.03, 0.05]]\n  holes:\n", "precracks"),
        ("range_static_velocity_bc", ST, "{set: pulled, type: displacement, x: 2.0e-4}",
         "{set: pulled, type: velocity, x: 2.0e-4}", "velocity"),
        ("range_polygon_two_vertices", PH, "    - disk: {center: [0.025, 0.05], radius: 0.005}",
         "    - polygon: {vertices: [[0.02, 0.04], [0.03, 0.06]]}", "polygon"),
        ("range_halfspace_zero_normal", BAR, "{name: right, box: {lo: [0.037, -1], hi: [1, 1]}}",
         "{name: right, halfspace: {point: [0.037, 0], normal: [0, 0]}}", "normal"),
        ("range_cylinder_zero_axis", BK, "box: {lo: [0, 0, 0], hi: [0.04, 0.04, 0.04]}",
         "box: {lo: [0, 0, 0], hi: [0.04, 0.04, 0.04]}\n  notches:\n"
         "    - {cylinder: {axis: [[0.02, 0.02, 0], [0.02, 0.02, 0]], radius: 0.01}, invert: true}",
         r"notches\[0\]\.cylinder\.axis"),
        ("range_cylinder_radius", BK, "box: {lo: [0, 0, 0], hi: [0.04, 0.04, 0.04]}",
         "box: {lo: [0, 0, 0], hi: [0.04, 0.04, 0.04]}\n  notches:\n"
         "    - {cylinder: {axis: [[0.02, 0.02, 0], [0.02, 0.02, 0.04]], radius: 0}, invert: true}",
         r"cylinder\.radius"),
        ("range_wall_zero_normal", "taylor_anvil", "normal: [0, 0, 1]", "normal: [0, 0, 0]",
         r"boundary_conditions\[0\]\.normal"),
        ("range_wall_no_normal", "taylor_anvil", "normal: [0, 0, 1], ", "",
         "normal"),
        ("range_wall_component", "taylor_anvil", "name: anvil}", "name: anvil, z: 0}",
         r"boundary_conditions\[0\]\.z"),
        ("range_wall_function", "taylor_anvil", "name: anvil}", "name: anvil, function: ramp}",
         "function"),
        ("range_wall_bad_name", "taylor_anvil", "name: anvil}", "name: \"an vil\"}", "name"),
        ("range_wall_static", ST, "{set: pulled, type: displacement, x: 2.0e-4}",
         "{set: pulled, type: wall, point: [0, 0], normal: [1, 0]}", "explicit"),
        ("range_point_not_wall", BAR, "{set: left, type: displacement, x: 0, y: 0}",
         "{set: left, type: displacement, x: 0, y: 0, point: [0, 0]}", "point"),
        ("range_cylinder_in_2d", PH, "    - disk: {center: [0.025, 0.05], radius: 0.005}",
         "    - cylinder: {axis: [[0.025, 0.04], [0.025, 0.06]], radius: 0.005}", "cylinder"),
    ]
    for cid, base, old, new, key in rng:
        c.mut(cid, "-", base, old, new, key)

    # -- NaN, infinities, overflow ---------------------------------------------------------------
    nan_keys = [  # (id part, base, old, new-with-{v}, key regex)
        ("spacing", PT, "spacing: 2.0e-3", "spacing: {v}", "spacing"),
        ("horizon", PT, "horizon_factor: 3.015", "horizon_factor: {v}", "horizon_factor"),
        ("thickness", PT, "thickness: 1.0e-3", "thickness: {v}", "thickness"),
        ("box_lo", PT, "lo: [0, 0], hi: [0.05, 0.1]", "lo: [{v}, 0], hi: [0.05, 0.1]", "lo"),
        ("box_hi", PT, "hi: [0.05, 0.1]", "hi: [0.05, {v}]", "hi"),
        ("hole_center", PT, "center: [0.0175, 0.0425]", "center: [0.0175, {v}]", "center"),
        ("hole_radius", PH, "radius: 0.005", "radius: {v}", "radius"),
        ("density", PT, "density: 7830", "density: {v}", "density"),
        ("youngs", PT, "youngs_modulus: 200.0e9", "youngs_modulus: {v}", "youngs_modulus"),
        ("poisson", PT, "poisson_ratio: 0.29", "poisson_ratio: {v}", "poisson_ratio"),
        ("jc_a", PT, "A: 792.0e6", "A: {v}", "A"),
        ("jc_n", PT, "n: 0.26", "n: {v}", "n"),
        ("jc_d3", PT, "D3: -2.12", "D3: {v}", "D3"),
        ("jc_dc", PT, "D_c: 0.3", "D_c: {v}", "D_c"),
        ("stab_coeff", PT, "stabilization_coefficient: 0.1", "stabilization_coefficient: {v}",
         "stabilization_coefficient"),
        ("set_box", PT, "hi: [1, 0.003]", "hi: [1, {v}]", "sets"),
        ("bc_y", PT, "{set: top, type: velocity, x: 0, y: 2.0}",
         "{set: top, type: velocity, x: 0, y: {v}}", "boundary_conditions"),
        ("bc_duration", BAR, "duration: 1.0e-5", "duration: {v}", "duration"),
        ("end_time", PT, "end_time: 2.0e-5", "end_time: {v}", "end_time"),
        ("safety", PT, "safety: 0.8", "safety: {v}", "safety"),
        ("dt", BAR, "steps: 20", "steps: 20, dt: {v}", "dt"),
        ("steps", BAR, "steps: 20", "steps: {v}", "steps"),
        ("critical_stretch", BAR, "critical_stretch: 0.002", "critical_stretch: {v}",
         "critical_stretch"),
        ("initial_velocity", BAR, "solver: {steps: 20}",
         "initial_conditions: {velocity: [0, {v}]}\nsolver: {steps: 20}", "velocity"),
        ("velocity_gradient", BK, "[0, 10, 0], [0, 0, 10]", "[0, {v}, 0], [0, 0, 10]",
         "velocity_gradient"),
        ("tolerance", ST, "tolerance: 1.0e-6", "tolerance: {v}", "tolerance"),
        ("load_level", ST, "load_steps: 5", "load_levels: [0.5, {v}]", "load_levels"),
        ("material_density", BM, "density: 1100", "density: {v}", "density"),
        ("wall_normal", "taylor_anvil", "normal: [0, 0, 1]", "normal: [0, {v}, 1]", "normal"),
        ("cylinder_radius", "taylor_anvil", "radius: 3.2e-3}", "radius: {v}}", "radius"),
    ]
    for part, base, old, new, key in nan_keys:
        c.mut(f"nan_{part}", "-", base, old, new.replace("{v}", "nan"), key)
    for part, base, old, new, key in nan_keys[::14]:
        c.mut(f"dotnan_{part}", "-", base, old, new.replace("{v}", ".nan"), key)
    for part, base, old, new, key in nan_keys[1::7]:
        c.mut(f"inf_{part}", "-", base, old, new.replace("{v}", ".inf"), key)
    for part, base, old, new, key in nan_keys[2::9]:
        c.mut(f"neginf_{part}", "-", base, old, new.replace("{v}", "-.inf"), key)
    for part, base, old, new, key in nan_keys[::10]:
        c.mut(f"overflow_{part}", "-", base, old, new.replace("{v}", "1e999"), key)
    for part, base, old, new, key in [nan_keys[k] for k in (0, 9, 21)]:
        c.mut(f"e308_{part}", "-", base, old, new.replace("{v}", "1e308"), key)

    # -- missing required keys -------------------------------------------------------------------
    def drop_block(text, key):
        """Removes the top-level block 'key:' (its line and the indented lines after it)."""
        out, skip = [], False
        for line in text.split("\n"):
            if line.startswith(key + ":"):
                skip = True
                continue
            if skip and (line.startswith(" ") or line.startswith("\t")):
                continue
            skip = False
            out.append(line)
        return "\n".join(out)

    for key in ("dimension", "geometry", "material", "solver"):
        c.scene(f"missing_{key}", "-", drop_block(B[PT], key), msg=key)
    c.mut("missing_spacing", "-", PT, "  spacing: 2.0e-3               # m\n", "", "spacing")
    c.mut("missing_box", "-", PT, "  box: {lo: [0, 0], hi: [0.05, 0.1]}\n", "", "box")
    c.mut("missing_density", "-", PT, "  density: 7830                 # kg/m^3\n", "", "density")
    c.mut("missing_poisson", "-", PT, "  poisson_ratio: 0.29\n", "", "poisson_ratio")
    c.mut("missing_moduli", "-", BAR, "material: {density: 8000, bulk_modulus: 1.0e9}",
          "material: {density: 8000}", "material")
    c.mut("missing_jc", "-", PH, "law: neo_hooke", "law: jc", "johnson_cook")
    c.mut("missing_jc_a", "-", PT, "    A: 792.0e6                  # Pa\n", "", "A")
    c.mut("missing_jc_dc", "-", PT, "    D_c: 0.3\n", "", "D_c")
    c.mut("missing_set_name", "-", BAR, "{name: left, box:", "{box:", "name")
    c.mut("missing_set_region", "-", BAR, "{name: left, box: {lo: [-1, -1], hi: [0.003, 1]}}",
          "{name: left}", "sets|region")
    c.mut("missing_bc_type", "-", BAR, "{set: left, type: displacement, x: 0, y: 0}",
          "{set: left, x: 0, y: 0}", "type")
    c.mut("missing_bc_duration", "-", BAR, ", function: ramp, duration: 1.0e-5",
          ", function: ramp", "duration")
    c.mut("missing_steps_and_end_time", "-", BAR, "solver: {steps: 20}", "solver: {}",
          "solver")
    c.mut("both_steps_and_end_time", "-", BAR, "solver: {steps: 20}",
          "solver: {steps: 20, end_time: 1.0e-5}", "steps|end_time")
    c.mut("missing_material_name", "-", BM, "{name: soft, box:", "{box:", "name")

    # -- unknown keys and keys in the wrong place ------------------------------------------------
    c.mut("unknown_top", "-", PT, "dimension: 2", "dimension: 2\nsolvr: {steps: 3}", "solvr")
    c.mut("unknown_geometry", "-", PT, "thickness: 1.0e-3", "thickness: 1.0e-3\n  spacng: 1",
          "spacng")
    c.mut("unknown_misspelled_material", "-", PT, "poisson_ratio: 0.29",
          "poisson_ration: 0.29", "poisson_ration")
    c.mut("unknown_wrong_section", "-", PT, "density: 7830", "density: 7830\n  spacing: 1.0e-3",
          "spacing")
    c.mut("unknown_jc", "-", PT, "D_c: 0.3", "D_c: 0.3\n    D6: 1", "D6")
    c.mut("unknown_bc", "-", BAR, "{set: left, type: displacement, x: 0, y: 0}",
          "{set: left, type: displacement, x: 0, y: 0, w: 0}", "w")
    c.mut("unknown_set", "-", BAR, "{name: left, box:", "{name: left, color: red, box:",
          "color")
    c.mut("unknown_region_kind", "-", PT, "- disk: {center: [0.0175", "- circle: {center: [0.0175",
          "circle")
    c.mut("unused_key_pmb", "-", BAR, "model: {kind: pmb, critical_stretch: 0.002}",
          "model: {kind: pmb, critical_stretch: 0.002, law: svk}", "law")
    c.mut("unused_key_static_in_explicit", "-", BAR, "solver: {steps: 20}",
          "solver: {steps: 20, load_steps: 4}", "load_steps")
    c.mut("unused_key_thermal", "-", PT, "D_c: 0.3", "D_c: 0.3\n    T_room: 293", "T_room")

    # -- duplicate keys --------------------------------------------------------------------------
    c.mut("dup_top", "-", PT, "dimension: 2", "dimension: 2\ndimension: 3", "dimension")
    c.mut("dup_geometry", "-", PT, "spacing: 2.0e-3", "spacing: 2.0e-3\n  spacing: 1.0e-3",
          "spacing")
    c.mut("dup_flow", "-", BAR, "material: {density: 8000,", "material: {density: 8000, "
          "density: 9000,", "density")
    c.mut("dup_section", "-", PT, "model:\n", "model: {kind: pmb}\nmodel:\n", "model")

    # -- truncations: each cut leaves a bracket open or a required section out --------------------
    for base, marks in ((PT, ["box: {lo: [0, ", "hi: [0.05, 0.1", "{center: [0.0175, 0.0425],",
                              "fields: [u, v, eps_p", "{set: top, type: velocity, x: 0,"]),
                        (BAR, ["material: {density: 8000", "{name: left, box: {lo: [-1",
                               "output: {field_interval: 100, fields: [u, v], "]),
                        (BT, ["box: {lo: [0, 0, 0], hi: [0.1, 0.01, 0.016]"])):
        for k, m in enumerate(marks):
            text = B[base]
            if text.count(m) != 1:
                sys.exit(f"gen_corpus: truncation mark {m!r} occurs {text.count(m)} times")
            c.scene(f"trunc_{base}_{k}", "-", text[:text.index(m) + len(m)], msg="syntax")
    c.scene("trunc_before_solver", "-", B[PT][:B[PT].index("solver:")], msg="solver")
    c.scene("trunc_mid_key", "-", B[PT][:B[PT].index("solver:") + 3], msg="syntax")
    c.scene("trunc_open_quote", "-", B[BAR].replace("name: bar", 'name: "bar'), msg="syntax")

    # -- junk bytes ------------------------------------------------------------------------------
    pt = B[PT].encode()
    at = pt.index(b"material:")
    junk = [("nul", b"\x00"), ("ff", b"\xff"), ("bad_utf8", b"\xc3\x28"), ("bom_inside",
            b"\xef\xbb\xbf"), ("bell", b"\x07"), ("del", b"\x7f"),
            ("surrogate", b"\xed\xa0\x80")]
    for name, j in junk:
        c.scene(f"junk_{name}", "-", pt[:at] + j + pt[at:])
    c.scene("junk_nul_in_value", "-", pt.replace(b"density: 7830", b"density: 78\x0030"))
    c.scene("junk_tab_indent", "-", B[PT].replace("  spacing: 2.0e-3", "\tspacing: 2.0e-3"),
            msg="tab")
    c.scene("junk_binary_head", "-", bytes(range(256)) + pt)
    c.scene("junk_utf16", "-", B[BAR].encode("utf-16"))

    # -- huge sizes and counts -------------------------------------------------------------------
    c.mut("huge_steps", "-", BAR, "steps: 20", "steps: 1e18", "steps")
    c.mut("huge_steps_beyond_long", "-", BAR, "steps: 20", "steps: 1e300", "steps")
    c.mut("huge_steps_digits", "-", BAR, "steps: 20", "steps: 99999999999999999999999", "steps")
    c.mut("huge_threads", "-", BAR, "steps: 20", "steps: 20, threads: 1e9", "threads")
    c.mut("huge_seed", "-", PT, "thickness: 1.0e-3",
          "thickness: 1.0e-3\n  jitter: 0.1\n  seed: 1e30", "seed")
    c.mut("huge_interval", "-", BAR, "field_interval: 100", "field_interval: 1e300",
          "field_interval")
    c.mut("huge_lattice_points", "-", PT, "spacing: 2.0e-3", "spacing: 1.0e-9", "spacing")
    c.mut("huge_box", "-", BK, "hi: [0.04, 0.04, 0.04]", "hi: [1.0e6, 1.0e6, 1.0e6]",
          "spacing|box")
    c.mut("huge_load_steps", "-", ST, "load_steps: 5", "load_steps: 1e300", "load_steps")
    c.mut("huge_bc_count", "-", BAR, "boundary_conditions:\n",
          "boundary_conditions:\n" +
          "".join("  - {set: all, type: body_force, y: 1}\n" for _ in range(65)),
          "boundary_conditions")
    c.mut("huge_reactions_count", "-", BAR, "reactions: [left, right]",
          "reactions: [" + ", ".join(["left", "right"] * 5) + "]", "reactions")
    c.mut("huge_materials_count", "-", BM, "materials:\n",
          "materials:\n" + "".join(
              f"  - {{name: m{k}, box: {{lo: [0.01, -1], hi: [1, 1]}}, density: 1100, "
              f"youngs_modulus: 2.0e9, poisson_ratio: 0.3}}\n" for k in range(256)),
          "materials")
    c.mut("huge_polygon_4097", "-", PH, "    - disk: {center: [0.025, 0.05], radius: 0.005}",
          "    - polygon: {vertices: [" + ", ".join(
              f"[{0.025 + 0.004 * math.cos(6.283185307179586 * k / 4097):.6f}, "
              f"{0.05 + 0.004 * math.sin(6.283185307179586 * k / 4097):.6f}]"
              for k in range(4097)) + "]}", "polygon|vertices")
    c.mut("huge_name", "-", PT, "name: plate_two_holes", "name: " + "p" * 5000, "name")
    c.mut("huge_key", "-", PT, "dimension: 2", "dimension: 2\n" + "k" * 5000 + ": 1", "syntax|key")
    # 100 000 vertices: the quadratic check took 90 s (row 12); written by the test at run time
    c.scene("huge_polygon_100000", "12",
            B[PH].replace("    - disk: {center: [0.025, 0.05], radius: 0.005}",
                          "    - polygon: {vertices: [@@REPEAT 100000 [0.02, 0.04], @@"
                          "[0.03, 0.06]]}"), msg="vertices|polygon", rep=True)

    # -- deep nesting ----------------------------------------------------------------------------
    c.scene("deep_brackets_100000", "12", "@@REPEAT 100000 [@@\n", msg="deep|nest|level",
            rep=True)
    c.append("deep_description_1000", "-", PT, "description: " + "[" * 1000 + "]" * 1000 + "\n",
             msg="deep|nest|level")
    c.append("deep_flow_maps_500", "-", BAR, "description: " + "{a: " * 500 + "1" + "}" * 500 +
             "\n", msg="deep|nest|level")

    # -- aliases ---------------------------------------------------------------------------------
    bomb = ["  x0: &a0 [lol, lol, lol, lol, lol, lol, lol, lol, lol, lol]"]
    for k in range(1, 9):
        bomb.append(f"  x{k}: &a{k} [" + ", ".join([f"*a{k - 1}"] * 10) + "]")
    c.append("alias_bomb", "10", PT, "description:\n" + "\n".join(bomb) + "\n",
             msg="alias", nomsg="out of memory")
    c.append("alias_bomb_unknown_key", "10", PT, "lol:\n" + "\n".join(bomb) + "\n", msg="lol|alias",
             nomsg="out of memory")
    c.append("alias_recursive", "-", PT, "description: &a [*a]\n", msg="description")
    c.mut("alias_undefined", "-", PT, "density: 7830", "density: *heavy", msg="heavy|alias")
    c.scene("alias_map_for_number", "-",
            B[PT].replace("box: {lo: [0, 0], hi: [0.05, 0.1]}",
                          "box: &b {lo: [0, 0], hi: [0.05, 0.1]}")
                 .replace("density: 7830", "density: *b"), msg="density")

    # -- numbers with trailing text (row 1) ------------------------------------------------------
    trailing = [
        ("density_kg", PT, "density: 7830", "density: 7830kg", "density"),
        ("density_underscore", PT, "density: 7830", "density: 7_830", "density"),
        ("poisson_comma", PT, "poisson_ratio: 0.29", "poisson_ratio: 0,29", "poisson_ratio"),
        ("spacing_unit", PT, "spacing: 2.0e-3", "spacing: 2.0e-3m", "spacing"),
        ("youngs_gpa", PT, "youngs_modulus: 200.0e9", "youngs_modulus: 200GPa",
         "youngs_modulus"),
        ("two_dots", PT, "n: 0.26", "n: 0.26.1", "n"),
        ("exponent_cut", PT, "A: 792.0e6", "A: 792.0e", "A"),
        ("end_time_unit", PT, "end_time: 2.0e-5", "end_time: 2.0e-5s", "end_time"),
        ("steps_suffix", BAR, "steps: 20", "steps: 20x", "steps"),
        ("steps_underscore", BAR, "steps: 20", "steps: 2_0", "steps"),
        ("point_comma", PT, "center: [0.0175, 0.0425]", "center: [0.0175, 0,0425]", "center"),
        ("bc_value_unit", BAR, "x: 0.5,", "x: 0.5m/s,", "x"),
        ("hole_radius_mm", PH, "radius: 0.005", "radius: 5mm", "radius"),
        ("load_level_pct", ST, "load_steps: 5", "load_levels: [50%, 1.0]", "load_levels"),
        ("number_space", PT, "density: 7830", "density: 7 830", "density"),
    ]
    for part, base, old, new, key in trailing:
        c.mut(f"trailing_{part}", "1", base, old, new, key)

    # -- booleans that are not booleans (row 2) --------------------------------------------------
    booleans = [
        ("force_dt_flase", BAR, "steps: 20", "steps: 20, force_dt: flase", "force_dt"),
        ("force_dt_ture", BAR, "steps: 20", "steps: 20, force_dt: ture", "force_dt"),
        ("partial_volume_2", BAR, "critical_stretch: 0.002",
         "critical_stretch: 0.002, partial_volume: 2", "partial_volume"),
        ("extrapolate_maybe", ST, "load_steps: 5", "load_steps: 5\n  extrapolate: maybe",
         "extrapolate"),
        ("invert_half", BAR, "{name: right, box:", "{name: right, invert: 0.5, box:", "invert"),
        ("jc_damage_nope", PT, "D_c: 0.3", "D_c: 0.3\n    damage: nope", "damage"),
        ("failed_keeps_bonds_fasle", PT, "connectivity: tl",
         "connectivity: tl\n  failed_keeps_bonds: fasle", "failed_keeps_bonds"),
        ("reuse_tangent_truee", ST, "type: adr\n  load_steps: 5\n  tolerance: 1.0e-6",
         "type: newton\n  load_steps: 5\n  reuse_tangent: truee", "reuse_tangent"),
        ("galerkin_bond_maybe", ST,
         "model: {kind: correspondence, law: linear_elastic, influence: constant, stabilization: silling}",
         "model: {kind: galerkin, law: linear_elastic, galerkin: {bond: maybe}}", "bond"),
    ]
    for part, base, old, new, key in booleans:
        c.mut(f"bool_{part}", "2", base, old, new, key)

    # -- names that reach file names and plot scripts --------------------------------------------
    c.mut("name_newline", "-", PT, "name: plate_two_holes", 'name: "plate\\nsystem(\'touch X\')"',
          "name")
    c.mut("name_slash", "-", PT, "name: plate_two_holes", "name: ../plate", "name")
    c.mut("name_double_quote", "-", PT, "name: plate_two_holes", "name: plate\"x", "name")
    c.mut("name_single_quote", "-", PT, "name: plate_two_holes", "name: \"plate'x\"", "name")
    c.mut("name_space", "-", PT, "name: plate_two_holes", "name: plate two", "name")
    c.mut("name_empty", "-", PT, "name: plate_two_holes", 'name: ""', "name")
    c.mut("name_dollar", "-", PT, "name: plate_two_holes", "name: $(touch X)", "name")
    c.mut("name_backtick", "-", PT, "name: plate_two_holes", "name: \"`touch X`\"", "name")
    c.mut("name_leading_dash", "13", PT, "name: plate_two_holes", "name: -rf", "name")
    c.mut("name_leading_dash_run", "13", BAR, "name: bar", "name: -rf", "name", cmd="run")
    c.mut("set_name_slash", "-", BAR, "{name: left,", "{name: a/b,", "name")
    c.mut("set_name_newline", "-", BAR, "{name: left,", '{name: "a\\nb",', "name")
    c.mut("material_name_quote", "-", BM, "{name: soft,", "{name: 'so\"ft',", "name")
    # the file's stem names the output when the scene has no name (row 3)
    no_name = B[BAR].replace("name: bar\n", "")
    stem = 'm\nsystem("touch X")\n#.yaml'
    c.scene("stem_newline", "3", no_name, as_=stem, names="touch X", msg="name")
    c.scene("stem_newline_run", "3", no_name, cmd="run", as_=stem, names="touch X", msg="name")
    c.scene("stem_quote", "3", no_name, as_='pl"ate.yaml', names='pl"ate', msg="name")
    c.scene("stem_leading_dash", "3,13", no_name, as_="-rf.yaml", names="-rf", msg="name")
    c.scene("stem_dollar", "3", no_name, as_="$(touch X).yaml", names="touch X", msg="name")

    # -- several documents, directives, complex keys ---------------------------------------------
    c.scene("multidoc_two_scenes", "-", B[BAR] + "---\n" + B[PT], msg="document")
    c.scene("multidoc_junk_after_end", "-", B[BAR] + "...\n--- just text\n", msg="document")
    c.scene("multidoc_directive", "-", "%YAML 1.1\n---\n" + B[BAR] + "---\n" + B[BAR],
            msg="document")
    c.scene("directive_unknown_version", "-", "%YAML 2.0\n---\n" + B[BAR], msg="YAML|version")
    c.append("complex_key_top", "18", BAR, "? [a, b]\n: 1\n", msg="key", nomsg="Internal error")
    c.mut("complex_key_geometry", "18", PT, "  thickness: 1.0e-3",
          "  ? {spacing: 1}\n  : 2\n  thickness: 1.0e-3", msg="key|geometry",
          nomsg="Internal error")
    c.mut("complex_key_flow", "18", BAR, "material: {density: 8000,",
          "material: {[density]: 8000,", msg="key|material", nomsg="Internal error")
    c.mut("key_null", "-", BAR, "dimension: 2", "dimension: 2\n: 3", msg="key|syntax")
    c.mut("key_number", "-", BAR, "dimension: 2", "dimension: 2\n3: 3", msg="3")
    c.mut("tag_binary", "-", PT, "density: 7830", "density: !!binary AAAA", msg="density")
    c.scene("empty_file", "-", "", msg="empty")
    c.scene("only_comments", "-", "# nothing but a comment\n", msg="empty")
    c.scene("only_document_marker", "-", "---\n...\n", msg="scene")

    # -- a static run whose load drives the residual to infinity (row 14) ------------------------
    c.mut("static_bc_1e200", "14", ST, "{set: pulled, type: displacement, x: 2.0e-4}",
          "{set: pulled, type: displacement, x: 1.0e200}", "particle [0-9]", cmd="run",
          names=False, nomsg="particle -1")

    # -- overrides (--set) -----------------------------------------------------------------------
    o = c.override
    o("ovr_no_equals", "-", BAR, ["geometry.spacing"], "geometry.spacing")
    o("ovr_empty_key", "-", BAR, ["=1"], "--set")
    o("ovr_empty", "-", BAR, [""], "--set")
    o("ovr_empty_value", "-", BAR, ["geometry.spacing="], "spacing")
    o("ovr_double_dot", "-", BAR, ["geometry..spacing=1e-3"], "geometry")
    o("ovr_trailing_dot", "-", BAR, ["geometry.=1e-3"], "geometry")
    o("ovr_index_missing", "-", BAR, ["sets[9].name=x"], "sets")
    o("ovr_index_negative", "-", BAR, ["sets[-1].name=x"], "sets")
    o("ovr_index_word", "-", BAR, ["sets[x].name=x"], "sets")
    o("ovr_index_huge", "-", BAR, ["sets[99999999999999999999].name=x"], "sets")
    o("ovr_index_unclosed", "-", BAR, ["sets[0.name=x"], "sets")
    o("ovr_index_on_map", "-", BAR, ["geometry[0]=1"], "geometry")
    o("ovr_key_on_list", "-", BAR, ["sets.name=x"], "sets")
    o("ovr_unbalanced_value", "-", BAR, ["geometry.box.lo=[0"], "lo")
    o("ovr_unknown_key", "-", BAR, ["geometry.spacng=1e-3"], "spacng")
    o("ovr_scalar_over_map", "-", BAR, ["geometry=1"], "geometry")
    o("ovr_map_over_scalar", "-", BAR, ["geometry.spacing.value=1"], "spacing")
    o("ovr_wrong_type", "-", BAR, ["geometry.spacing=[1, 2]"], "spacing")
    o("ovr_out_of_range", "-", BAR, ["material.density=-1"], "density")
    o("ovr_nan", "-", BAR, ["material.density=nan"], "density")
    o("ovr_inf", "-", BAR, ["solver.steps=.inf"], "steps")
    o("ovr_bad_yaml", "-", BAR, ["material.density={"], "density")
    o("ovr_tab", "-", BAR, ["material.density=\t8000\t1"], "density")
    o("ovr_newline_value", "1", BAR, ["material.density=8000\n9000"], "density")
    o("ovr_density_kg", "1", BAR, ["material.density=8000kg"], "density")
    o("ovr_poisson_comma", "1", PT, ["material.poisson_ratio=0,29"], "poisson_ratio")
    o("ovr_spacing_underscore", "1", BAR, ["geometry.spacing=1_0e-3"], "spacing")
    o("ovr_steps_suffix", "1", BAR, ["solver.steps=10k"], "steps")
    o("ovr_force_dt_flase", "2", BAR, ["solver.dt=1e-6", "solver.force_dt=flase"], "force_dt")
    o("ovr_name_dash", "13", BAR, ["name=-rf"], "name")
    o("ovr_name_newline", "-", BAR, ["name=a\nb"], "name")
    o("ovr_recursive_alias", "16", BAR, ["description=&a [*a]"], "description|alias",
      nomsg="out of memory")
    o("ovr_second_document", "16", BAR, ["description=a\n---\nb"], "description|document")
    o("ovr_complex_key", "18", BAR, ["material={? [a]: 1}"], "material", nomsg="Internal error")
    o("ovr_undefined_alias", "-", BAR, ["material.density=*x"], "density|alias")
    o("ovr_too_many", "-", BAR, ["solver.steps=10"] * 65, "64", names="--set")
    o("ovr_dimension_3", "-", BAR, ["dimension=3"], "dimension|point|lo|hi")
    o("ovr_sets_empty_list", "-", BAR, ["sets=[]"], "left|set")

    # -- Gmsh meshes (geometry.mesh): the mesh beside the case ---------------------------------
    HEAD = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
    NODES = ("$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n0 0 0\n1e-3 0 0\n1e-3 1e-3 0\n"
             "0 1e-3 0\n$EndNodes\n")
    def mesh_case(cid, mesh, msg, geom=""):
        c.files[cid + ".msh"] = mesh.encode()
        c.scene(cid, "-", "dimension: 2\ngeometry:\n  spacing: 0.001\n"
                f"  mesh: {cid}.msh\n{geom}"
                "material: {density: 7800, youngs_modulus: 200.0e9, poisson_ratio: 0.3}\n"
                "model: {kind: correspondence, law: linear_elastic}\n"
                "boundary_conditions:\n  - {set: all, type: displacement, x: 0}\n"
                "solver: {steps: 5}\n", msg)
    mesh_case("range_mesh_binary", "$MeshFormat\n4.1 1 8\n", "binary")
    mesh_case("range_mesh_version", "$MeshFormat\n3.0 0 8\n", "version 3.0")
    mesh_case("range_mesh_element_type", HEAD + NODES
              + "$Elements\n1 1 1 1\n2 1 9 1\n1 1 2 3 4 1 2\n$EndElements\n", "element type 9")
    mesh_case("type_mesh_coordinate", HEAD + "$Nodes\n1 1 1 1\n2 1 0 1\n1\n0 0.0x1 0\n"
              "$EndNodes\n", "0.0x1")
    mesh_case("missing_mesh_nodes", HEAD, "no .Nodes section")
    mesh_case("range_mesh_undefined_node", HEAD + NODES
              + "$Elements\n1 1 1 1\n2 1 3 1\n1 1 2 3 7\n$EndElements\n", "node 7")
    mesh_case("range_mesh_3d_element", HEAD + NODES
              + "$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n", "3-D element")
    mesh_case("trunc_mesh_nodes", HEAD + "$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n", "file ends")
    mesh_case("range_mesh_with_box", HEAD + NODES
              + "$Elements\n1 1 1 1\n2 1 3 1\n1 1 2 3 4\n$EndElements\n", "geometry.box",
              geom="  box: {lo: [0, 0], hi: [1, 1]}\n")

    # -- boundary conditions along a direction (a roller on an inclined face) --------------------
    LEFT = "{set: left, type: displacement, x: 0, y: 0}"
    for cid, new, msg in [
            ("range_bc_direction_zero", "{set: left, type: displacement, direction: [0, 0], "
             "value: 0}", "direction"),
            ("range_bc_direction_nan", "{set: left, type: displacement, direction: [.nan, 1], "
             "value: 0}", "direction"),
            ("range_bc_direction_with_x", "{set: left, type: displacement, direction: [1, 1], "
             "value: 0, x: 0}", "boundary_conditions.0..x"),
            ("missing_bc_direction_value", "{set: left, type: displacement, direction: [1, 1]}",
             "value"),
            ("range_bc_value_alone", "{set: left, type: displacement, value: 0}", "value"),
            ("range_bc_direction_body_force", "{set: left, type: body_force, direction: [1, 0], "
             "value: 1}", "direction"),
            ("type_bc_direction_length", "{set: left, type: displacement, direction: [1, 0, 0], "
             "value: 0}", "direction"),
            ("type_bc_direction_scalar", "{set: left, type: displacement, direction: 1, value: 0}",
             "direction"),
            ("range_bc_direction_overlap", "{set: left, type: displacement, direction: [1, 1], "
             "value: 0}\n  - {set: all, type: displacement, y: 0}", "along a direction")]:
        c.mut(cid, "-", BAR, LEFT, new, msg, cmd="run" if cid.endswith("overlap") else "check")

    # -- point clouds (geometry.points) with a material column: the cloud beside the case -------
    def cloud_case(cid, cells, msg, materials=True, region=""):
        rows = "".join(f"{0.0005 + 0.001 * i:g}, 0.0005, 1e-6, {m}, {1 if i < 2 else 0}\n"
                       for i, m in enumerate(cells))
        c.files[cid + ".csv"] = ("x, y, area, material, set:left\n" + rows).encode()
        mats = ("materials:\n  - {name: soft, density: 1100, youngs_modulus: 2.0e9, "
                f"poisson_ratio: 0.3{region}}}\n") if materials else ""
        c.scene(cid, "-", "dimension: 2\ngeometry:\n  spacing: 0.001\n"
                f"  points: {cid}.csv\n"
                "material: {density: 7800, youngs_modulus: 200.0e9, poisson_ratio: 0.3}\n"
                + mats + "model: {kind: correspondence, law: linear_elastic}\n"
                "boundary_conditions:\n  - {set: left, type: displacement, x: 0, y: 0}\n"
                "solver: {steps: 5}\n", msg)
    cloud_case("range_points_material_unknown", ["0", "0", "soft", "hard"], "'hard'")
    cloud_case("range_points_material_index", ["0", "0", "1", "2"], "index 2")
    cloud_case("type_points_material_cell", ["0", "0", "soft", "so ft"], "'so ft'")
    cloud_case("range_points_material_no_list", ["0", "0", "1", "1"], "no materials list",
               materials=False)
    cloud_case("range_points_material_region", ["0", "0", "1", "1"], "gives a region",
               region=", box: {lo: [0, 0], hi: [1, 1]}")
    cloud_case("range_points_material_unused", ["0", "0", "0", "0"], "no particle")

    # -- the command line ------------------------------------------------------------------------
    bar = "@BASE:bar@"
    c.cli("cli_no_command", "-", [], msg="usage")
    c.cli("cli_unknown_command", "-", ["chek", bar], names="chek")
    c.cli("cli_no_scene", "-", ["check"], msg="no scene")
    c.cli("cli_two_scenes", "-", ["check", bar, bar], names="bar.yaml", msg="more than one")
    c.cli("cli_unknown_option", "-", ["check", bar, "--frobnicate"], names="--frobnicate")
    c.cli("cli_set_without_value", "-", ["check", bar, "--set"], names="--set")
    c.cli("cli_run_option_in_check", "-", ["check", bar, "-o", "@OUT@"], names="-o")
    c.cli("cli_threads_zero", "-", ["run", bar, "-o", "@OUT@", "--threads", "0"],
          names="--threads")
    c.cli("cli_threads_word", "-", ["run", bar, "-o", "@OUT@", "--threads", "two"],
          names="--threads")
    c.cli("cli_threads_huge", "-", ["run", bar, "-o", "@OUT@", "--threads", "99999999999"],
          names="--threads")
    c.cli("cli_threads_trailing", "-", ["run", bar, "-o", "@OUT@", "--threads", "2x"],
          names="--threads")
    c.cli("cli_info_unknown_option", "-", ["info", "--frobnicate"], names="--frobnicate")
    c.cli("cli_info_threads_zero", "-", ["info", "--threads", "0"], names="--threads")
    c.cli("cli_scene_missing", "-", ["check", "@SRC@/tests/badinput/no_such_scene.yaml"],
          names="no_such_scene.yaml")
    c.cli("cli_scene_empty_path", "-", ["check", ""], msg="scene")
    c.cli("cli_scene_directory", "-", ["check", "@SRC@/scenes"], names="scenes")
    c.cli("cli_scene_directory_slash", "-", ["check", "@SRC@/scenes/"], names="scenes")
    c.cli("cli_scene_dev_null", "-", ["check", "/dev/null"], names="/dev/null")
    c.cli("cli_scene_executable", "-", ["check", "@CLI@"], msg="NUL|YAML|UTF|character")
    c.cli("cli_scene_dev_zero", "9", ["check", "/dev/zero"], names="/dev/zero",
          msg="limit|large|size|at most", nomsg="out of memory")
    c.cli("cli_scene_dev_urandom", "9", ["check", "/dev/urandom"], names="/dev/urandom",
          nomsg="out of memory")
    c.cli("cli_run_scene_missing", "-", ["run", "@SRC@/tests/badinput/no_such_scene.yaml", "-o",
                                        "@OUT@"], names="no_such_scene.yaml")
    # -o
    c.cli("cli_output_empty", "15", ["run", bar, "-o", ""], msg="-o|output", nomsg="Success")
    c.cli("cli_output_too_long", "15",
          ["run", bar, "-o", "@OUT@/" + "/".join(["d" * 200] * 21)], msg="long|4095|4096|length",
          nomsg="HDF5 call")
    c.cli("cli_output_is_file", "-", ["run", bar, "-o", "/dev/null"], names="/dev/null")
    c.cli("cli_output_under_file", "-", ["run", bar, "-o", "@SRC@/README.md/out"],
          names="README.md")
    c.cli("cli_output_in_proc", "-", ["run", bar, "-o", "/proc/pdk_badinput"],
          names="/proc/pdk_badinput")
    # --restart with what is not a checkpoint
    c.cli("cli_restart_scene_file", "18", ["run", bar, "-o", "@OUT@", "--restart", bar],
          names="bar.yaml", nomsg="H5Fopen\\(|HDF5 call")
    c.cli("cli_restart_missing", "18", ["run", bar, "-o", "@OUT@", "--restart",
                                        "@SRC@/tests/badinput/no_such_checkpoint.h5"],
          names="no_such_checkpoint.h5", nomsg="H5Fopen\\(|HDF5 call")
    c.cli("cli_restart_dev_null", "18", ["run", bar, "-o", "@OUT@", "--restart", "/dev/null"],
          names="/dev/null", nomsg="H5Fopen\\(|HDF5 call")
    c.cli("cli_restart_directory", "18", ["run", bar, "-o", "@OUT@", "--restart", "@SRC@/scenes"],
          names="scenes", nomsg="H5Fopen\\(|HDF5 call")
    c.cli("cli_restart_static", "-", ["run", "@BASE:static_block@", "-o", "@OUT@", "--restart",
                                      bar], msg="static")
    c.cli("cli_restart_empty", "-", ["run", bar, "-o", "@OUT@", "--restart", ""], msg="restart|checkpoint")


# ---- writing -------------------------------------------------------------------------------------
SPECIAL = set(b"%\t\n\r\\;[]")


def esc(s):
    out = []
    for b in s.encode("utf-8"):
        if b in SPECIAL or b < 0x20 or b > 0x7E:
            out.append("%%%02X" % b)
        else:
            out.append(chr(b))
    return "".join(out) if out else ""


def field(s):
    if s is None:
        return "-"
    if s == "-" or s == "":
        sys.exit(f"gen_corpus: a field cannot be '{s}'")
    return esc(s)


def write(corpus):
    base_dir = os.path.join(HERE, "base")
    case_dir = os.path.join(HERE, "cases")
    for d in (base_dir, case_dir):
        os.makedirs(d, exist_ok=True)
        for f in os.listdir(d):
            os.remove(os.path.join(d, f))
    for name, text in corpus.bases.items():
        with open(os.path.join(base_dir, name + ".yaml"), "w", encoding="utf-8") as f:
            f.write(text)
    for fname, data in corpus.files.items():
        with open(os.path.join(case_dir, fname), "wb") as f:
            f.write(data)
    lines = ["# Bad-input corpus: written by tests/badinput/gen_corpus.py (edit that, not this).",
             "# id\trows\tas\tnames\tmsg\tnomsg\targv... (README.md)"]
    for cs in corpus.cases:
        # an empty argument stays an empty field: '%' with nothing after it reads as ''
        argv = [esc(a) if a != "" else "%" for a in cs["argv"]]
        lines.append("\t".join([cs["id"], cs["rows"], field(cs["as_"]), field(cs["names"]),
                                field(cs["msg"]), field(cs["nomsg"])] + argv))
    with open(os.path.join(HERE, "cases.tsv"), "w", encoding="ascii", newline="\n") as f:
        f.write("\n".join(lines) + "\n")


def check(corpus, pdk):
    """Runs each base (must be valid and fast) and reports what the cases give today."""
    bad = 0
    for name in corpus.bases:
        path = os.path.join(HERE, "base", name + ".yaml")
        t0 = time.time()
        r = subprocess.run([pdk, "check", path], capture_output=True, text=True)
        dt = time.time() - t0
        print(f"base {name}: exit {r.returncode}, {dt:.2f} s")
        if r.returncode != 0 or dt > 2.0:
            print(r.stderr)
            bad += 1
    return bad


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--check", metavar="PDK", help="run `PDK check` on every base scene")
    args = ap.parse_args()
    corpus = Corpus(make_bases())
    build(corpus)
    write(corpus)
    print(f"gen_corpus: {len(corpus.bases)} base scenes, {len(corpus.cases)} cases, "
          f"{len(corpus.files)} case files")
    if args.check and check(corpus, args.check):
        sys.exit("gen_corpus: a base scene is not valid or not fast")


if __name__ == "__main__":
    main()
