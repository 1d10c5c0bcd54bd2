/* Run output: one HDF5 file per run with an XDMF file beside it for ParaView, histories as CSV,
 * a PNG plot of the histories (when gnuplot is present), the last field output as CSV and PNG
 * (in 3-D its mid-plane layer), and checkpoints for restart.
 *
 * HDF5 layout of <dir>/<name>.h5 (n particles, in the store's current order):
 *   /                       attributes: pdk_version, build_type, build_flags, compiler,
 *                           dimension (int), num_particles (int64), scene (text, when given;
 *                           a scene over 60 kB goes to the dataset /scene instead)
 *   /static/id              int64 [n]      original particle ids
 *   /static/X               f64   [n][3]   reference positions (z = 0 in 2-D)
 *   /static/volume          f64   [n]
 *   /static/sets/<name>     uint8 [n]      membership of every "set:<name>" field at open
 *   /static/connectivity    int32 [n]      0 .. n-1: the XDMF polyvertex cells
 *   /steps/<k>/             k = 000000, 000001, ... in output order (six digits, so a listing
 *                           sorted by name is in output order); attributes step (int64), time
 *                           (f64)
 *   /steps/<k>/<field>      the field's own type (f64 for the solver's fields):
 *                             1 component         [n]
 *                             dim components      [n][3]  (vectors, z = 0 in 2-D)
 *                             dim*dim components  [n][9]  (tensors [a][c] at 3a + c; 2-D: zeros
 *                                                         in the z row and column)
 *                             otherwise           [n][num_comp]
 *                           chunked; shuffled and deflated at opts.compression
 *                           (/static is always deflated at level 1: it is written once)
 *                           Every field pdk declares (x, X, u, v, f, volume, von_mises, eps_p,
 *                           damage, ...) has a string attribute "unit" in opts.units ("m",
 *                           "m/s", "N/m^3", "Pa", "1" for a dimensionless one, ... with SI;
 *                           "length", "length/time", ... without units); a caller's own fields,
 *                           ids and set flags have none
 *   /history/<column>       f64 [rows], chunked and extensible; the columns are
 *                             step, time, kinetic, strain, external_work, broken,
 *                             reaction_<set>_<x|y|z>  for every reaction set (dim components),
 *                             disp_<set>_<x|y|z>      mean displacement x - X of the set's
 *                                                     particles, when "set:<set>" and "x" exist
 *                             plastic_work, damage_work, breaking_work   energy dissipated so far
 *                                                     (pdk_history; 0 for models without it)
 *                             dt                      the step size (0 in static solves)
 *                             failed, damage_max      particles failed so far and the largest
 *                                                     Johnson-Cook damage (0 without it)
 * Dataset names are the field names with every character outside [A-Za-z0-9_-] replaced by '_'.
 *
 * <dir>/<name>.xmf: XDMF 2 (ParaView: "Xdmf Reader"), a temporal collection with one polyvertex
 *   grid per field output; the geometry is the current position "x" of that output when it was
 *   written, else the reference position /static/X; every written field is a node attribute
 *   named after the field (Scalar, Vector, Tensor or Matrix), as are id, volume and the sets
 *   ("set:<name>", from /static unless the output writes the field itself). Data paths are
 *   relative, so the directory can be moved. Checked with ParaView 5.11: the Xdmf reader and
 *   both Xdmf3 readers load every step.
 * <dir>/<name>_history.csv: one row per history record; the header names the columns with units.
 * <dir>/<name>_history.png: reaction vs time, reaction vs displacement and energies vs time (with
 *   the dissipated energies and their sum with kinetic and strain when a run dissipated), made by
 *   gnuplot from <dir>/<name>_history.gp (kept, so the plot can be redone or edited).
 * Runs with at least one field output, at close:
 * <dir>/<name>_fields.csv: the last field output, read back from the .h5: one row per particle
 *   (store order), columns id, X, Y (, Z), then every component of every field written (<f> for
 *   a scalar, <f>_x, <f>_y (, <f>_z) for a vector, <f>_xx, <f>_xy, ... for a tensor, <f>_0, ...
 *   otherwise), 10 significant digits. In 3-D only one layer: the particles whose reference z is
 *   within half their size (cube root of the volume) of the reference z nearest the middle of
 *   the body's z extent (on a lattice, the layer nearest the mid-plane).
 * <dir>/<name>_fields.png: one panel per scalar field of that output and |u| (up to 6, in the
 *   order listed), the particles coloured by the value at their current positions (x when it
 *   was written, else X + u when u was, else X), equal axes; the "failed" panel instead at the
 *   reference positions, failed particles drawn over the others (the crack path); made by
 *   gnuplot from <dir>/<name>_fields.gp when the history PNG is made.
 *
 * Crash safety: every file is written under a temporary name (<file>.part) and flushed as it
 * grows; pdk_output_close(..., success = 1) completes every file (the PNGs from the .part data),
 * syncs them to disk, removes an earlier run's files of the same names (its .xmf first) and then
 * renames the new ones to their final names (the .xmf last). A killed run leaves only .part
 * files, never a file that looks complete, and never final files of two runs side by side: a
 * <name>.xmf is there only with its whole set. A write that fails (a full disk) is an error
 * (PDK_ERR_IO) naming the file and the reason. A restart (opts.append) starts its .part files
 * from the earlier run's records up to the checkpoint and appends to them.
 */
#ifndef PDK_OUTPUT_H
#define PDK_OUTPUT_H

#include "pdk/export.h"
#include "pdk/explicit.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pdk_output pdk_output;

typedef struct pdk_output_opts {
  const char *dir;        /* created if missing (with its parents); NULL: "." */
  const char *name;       /* file stem: not empty, no '/', ':' or control character */
  const char *scene_text; /* stored as an attribute (may be NULL) */
  /* Reaction sets, in the order of pdk_explicit_opts.reaction_sets (history.reaction[k]): set
   * names, with or without the "set:" prefix; they name the history columns. At most 8. */
  const char *const *reaction_sets; /* [num_reaction_sets] */
  int num_reaction_sets;
  /* NULL, or [num_reaction_sets] unit directions (zero: none): a set with one also gets the
   * history column reaction_<set>_n, its reaction along the direction (the support force of a
   * boundary condition along a direction, pdk_bc.direction), after all the other columns. */
  const double (*reaction_normals)[3];
  int plot; /* 1: make the PNG when gnuplot is on the PATH */
  /* Rigid walls (PDK_BC_WALL, in the order of pdk_history.wall_impulse): names of the history
   * columns wall_<name>_force (the mean normal force since the previous row: the impulse between
   * the two rows over their time apart; 0 in the first row) and wall_<name>_impulse (so far), and
   * with any wall the column contact_work. At most PDK_MAX_WALLS; 0: no such columns. */
  const char *const *walls;
  int num_walls;
  /* Deflate level 0 (off) .. 9 of the field outputs; default 0: deflate 1 costs about 20 times
   * the uncompressed write (1e6 particles, x v f: 1.1 s vs 0.05 s per output) for 44% less disk. */
  int compression;
  /* Unit labels in the CSV header: NULL: dimensions ("time [time]", "kinetic [energy]");
   * "SI": s, J, N, m; "mm-N-s-tonne": s, mJ, N, mm. Anything else is an error. */
  const char *units;
  /* 2-D: the out-of-plane thickness the particle volumes include (the plots say the reactions
   * act on it); 0: not said. */
  double thickness;
  /* Restart (append = 1): continue the output of an earlier run in dir instead of starting
   * afresh. When <name>.h5, <name>.xmf and <name>_history.csv are there, the new files start with
   * their history rows and field outputs up to and including step append_step (the checkpoint's)
   * and the run's records are appended; later records (written after the checkpoint by the run
   * that stopped) are dropped, so the files equal those of a run that never stopped (the CSV and
   * the XDMF byte for byte, the HDF5 dataset for dataset). The earlier files are replaced only
   * at the final rename, like any output. When none of the three is there the output starts
   * afresh (pdk_output_num_history_rows and pdk_output_num_field_steps tell: 0). Earlier files
   * that do not fit (one of the three missing, other particles or sets, other history columns,
   * another scene than append_scene, files that disagree with one another, or a history that
   * starts after append_step) are an error naming what differs. */
  int append;
  long append_step;
  const char *append_scene; /* the checkpoint's scene text (pdk_checkpoint_info); NULL: any */
} pdk_output_opts;

/* dir ".", name "pdk", plot 1, compression 0, the rest zero/NULL. */
PDK_EXPORT pdk_output_opts pdk_output_opts_default(void);

/* Creates <name>.h5.part, <name>.xmf.part and <name>_history.csv.part in dir and writes the
 * static data. The name must be printable: a control character is an error (PDK_ERR_ARG); any
 * other character is safe in the plot scripts. The store p is borrowed: it must outlive the output and keep its particle order. */
PDK_EXPORT int pdk_output_open(pdk_ctx *ctx, const pdk_output_opts *opts, pdk_particles *p,
                               pdk_output **out);
/* Writes the listed particle fields at this step. A name that is not a registered field is an
 * error naming it and listing the fields that exist; so is a name listed twice. */
PDK_EXPORT int pdk_output_write_fields(pdk_output *o, pdk_particles *p, long step, double time,
                                       const char *const *fields, int num_fields);
/* Appends one history record (a row of every /history column and of the CSV). */
PDK_EXPORT int pdk_output_write_history(pdk_output *o, const pdk_history *h);
/* 1 when pdk_output_close(..., 1) will make the PNG: the plot was asked for and gnuplot was
 * found on the PATH at open. A missing gnuplot is not an error; this is how to tell. */
PDK_EXPORT int pdk_output_will_plot(const pdk_output *o);
/* Number of field outputs and history records written so far. */
PDK_EXPORT int pdk_output_num_field_steps(const pdk_output *o);
PDK_EXPORT long pdk_output_num_history_rows(const pdk_output *o);
/* The step of the last history record and of the last field output so far (also those kept by
 * opts.append); -1 when there is none. */
PDK_EXPORT long pdk_output_last_history_step(const pdk_output *o);
PDK_EXPORT long pdk_output_last_field_step(const pdk_output *o);
/* success = 1: finish the XDMF, CSVs and PNGs and rename every file to its final name;
 * success = 0: remove the temporary files. Always frees (accepts NULL). If gnuplot runs but
 * fails, the data files are still completed and renamed, that PNG is not left, and the error
 * (PDK_ERR_EXTERNAL) names the script to rerun. */
PDK_EXPORT int pdk_output_close(pdk_output **o, int success);
/* Makes a file the caller completed under the temporary name part one of the output's set: the
 * closing phase syncs it, removes the previous file at final with the previous run's files and
 * renames part to final with the new ones (before the .xmf), so a kill leaves it beside files of
 * its own run only. Closing without success removes part. One such file per output; pdk run
 * gives it the checkpoint written at the end of a run or at Ctrl-C. */
PDK_EXPORT int pdk_output_adopt(pdk_output *o, const char *part, const char *final);

/* Checkpoint: every registered particle field, the model's bond state and counters, and the
 * solver's scalars (time, step, dt, strain energy, external work), in one HDF5 file (written as
 * <path>.part, synced, then renamed). Restoring into a simulation built from the same scene
 * continues bitwise as if never interrupted.
 *
 * Layout: a 512-byte HDF5 user block holding the text "pdk checkpoint\nchecksum fnv1a64x:<16 hex
 * digits>\nsize <bytes>\n" and zeros: a 64-bit hash of every byte of the file after the user
 * block, and the file's size (src/io/checkpoint.c), written once the HDF5 file is closed;
 * / attributes kind = "pdk checkpoint", format (int, 2), pdk_version, build_flags,
 * dimension, num_particles, num_bonds, model_kind, scene (text, when given; over 60 kB: the
 * dataset /scene); /solver attributes time, step, dt, dt_created (the step the run was created with), strain,
 * external_work, and the dt_update state dt_stable, dt_step0, dt_time0, est_step, est_broken,
 * num_estimates, num_dt_changes, and with walls wall_impulse_<k> and contact_work;
 * /model attributes num_broken, num_flagged, datasets bond_alive uint8 [num_bonds] and
 * s0 f64 [n] when the model can break bonds (pmb and lps also the breaking energy's pending
 * state: attribute book_has_pending, datasets book_prev uint8 [num_bonds], book_pending f64 [n]);
 * with ul connectivity also attributes ul_rebuilt,
 * ul_num_rebuilds and, after a rebuild, the rebuilt families ul_bond_start i64 [n+1] and
 * ul_bond_j i32; /fields/<name> [num_comp][n] in the field's type, attributes type (pdk_type)
 * and components. */
PDK_EXPORT int pdk_checkpoint_write(pdk_ctx *ctx, const char *path, pdk_explicit *e,
                                    const char *scene_text);
/* Verifies the checkpoint first: a file that is missing, not HDF5, not a pdk checkpoint, of
 * another format (format 1, without a checksum, included) or that does not match its checksum
 * (damaged) is refused (PDK_ERR_IO, PDK_ERR_UNSUPPORTED for the format) with one line naming the
 * file. Then checks it against the simulation (dimension, particle count, bond count, model kind,
 * bond state, every field's type and shape, ids, reference positions and volumes) and changes
 * nothing when they differ: the error (PDK_ERR_ARG) names what differs. Fields in the checkpoint
 * that the simulation lacks are added. The checkpoint's dt is restored as it was; a scene-level
 * restart that reconciles it with the scene's step and end is pdk_sim_restart (pdk/scene.h). */
PDK_EXPORT int pdk_checkpoint_read(pdk_ctx *ctx, const char *path, pdk_explicit *e);
/* What a checkpoint holds before anything is built from it: its step and time, and the scene
 * text it was written with (malloc'd, free() it; NULL when none was stored). Any output pointer
 * may be NULL. The file is verified as by pdk_checkpoint_read. */
PDK_EXPORT int pdk_checkpoint_info(pdk_ctx *ctx, const char *path, long *step, double *time,
                                   char **scene_text);

#ifdef __cplusplus
}
#endif
#endif
