/* Run output: one HDF5 file per run with an XDMF file beside it for ParaView, histories as CSV,
 * a PNG plot of the histories (when gnuplot is present), and checkpoints for restart.
 *
 * HDF5 layout of <dir>/<name>.h5:
 *   /                       attributes: pdk_version, scene (text), dimension, num_particles
 *   /static/id              int64 [n]      original particle ids
 *   /static/X               f64   [n][3]   reference positions (z = 0 in 2-D)
 *   /static/volume          f64   [n]
 *   /static/sets/<name>     uint8 [n]      set membership
 *   /steps/<k>/             attributes: step, time
 *   /steps/<k>/<field>      f64 [n] or [n][3] (vectors padded to 3 for ParaView), chunked
 *   /history/<column>       f64 [rows], chunked and extensible
 * <dir>/<name>.xmf: a temporal collection of polyvertex grids referencing those datasets.
 * <dir>/<name>_history.csv: one row per history record, header names the columns with units.
 * <dir>/<name>_history.png: reaction force vs prescribed displacement and energies vs time.
 *
 * Crash safety: every file is written under a temporary name (<file>.part), flushed, and renamed
 * to its final name by pdk_output_close(..., success = 1). A killed run leaves only .part files,
 * never a file that looks complete.
 */
#ifndef PDK_OUTPUT_H
#define PDK_OUTPUT_H

#include "pdk/explicit.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pdk_output pdk_output;

typedef struct pdk_output_opts {
  const char *dir;          /* created if missing */
  const char *name;         /* file stem */
  const char *scene_text;   /* stored as an attribute (may be NULL) */
  const char *const *reaction_sets; /* names for the history columns, [num_reaction_sets] */
  int num_reaction_sets;
  int plot;                 /* 1: make the PNG when gnuplot is on the PATH */
} pdk_output_opts;

int pdk_output_open(pdk_ctx *ctx, const pdk_output_opts *opts, pdk_particles *p, pdk_output **out);
/* Writes the listed particle fields at this step. A name that is not a registered field is an
 * error naming it and listing the fields that exist. */
int pdk_output_write_fields(pdk_output *o, pdk_particles *p, long step, double time,
                            const char *const *fields, int num_fields);
int pdk_output_write_history(pdk_output *o, const pdk_history *h);
/* success = 1: finish the XDMF, CSV and PNG and rename every file to its final name;
 * success = 0: remove the temporary files. Always frees. */
int pdk_output_close(pdk_output **o, int success);

/* Checkpoint: every registered particle field, the model's bond state and history, and the
 * solver's scalars, in one HDF5 file (written as .part, then renamed). Restoring into a
 * simulation built from the same scene continues bitwise as if never interrupted. */
int pdk_checkpoint_write(pdk_ctx *ctx, const char *path, pdk_explicit *e, const char *scene_text);
int pdk_checkpoint_read(pdk_ctx *ctx, const char *path, pdk_explicit *e);

#ifdef __cplusplus
}
#endif
#endif
