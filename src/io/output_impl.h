/* Private to the run output (src/output*.c): the output object, its files and history columns,
 * and what crosses the output's files:
 *   output.c           the object: open (history columns, static data), history records, close
 *                      (the closing phase that completes and renames every file)
 *   output_fields.c    field outputs: the HDF5 datasets of a field and the XDMF grids that index
 *                      them (pdk_output_write_fields)
 *   output_restart.c   an appending open: the earlier run's records copied into the new files
 *   output_plot.c      the history plot: its gnuplot script, and running gnuplot
 *   output_snapshot.c  the field snapshot: <name>_fields.csv from the last field output, and its
 *                      gnuplot script
 * src/io/output.c describes the files and the crash-safety rule.
 */
#ifndef PDK_OUTPUT_IMPL_H
#define PDK_OUTPUT_IMPL_H

#include <stdio.h>

#include "core/h5io.h"
#include "pdk/output.h"
#include "pdk/ctx.h"
#include "pdk/particles.h"

enum { OUT_H5 = 0, OUT_XMF, OUT_CSV, OUT_GP, OUT_PNG, OUT_FCSV, OUT_FGP, OUT_FPNG, OUT_NUM_FILES };

#define OUT_CHUNK_ROWS 32768 /* rows per field chunk: 256 kB for f64 scalars, 768 kB for vectors   \
                              */
#define OUT_HIST_CHUNK 1024  /* rows per history chunk */
/* Deflate level of the static datasets, written once: ids and sets shrink many times over.
 * Field outputs use opts.compression, off by default: measured on this machine (1e6 particles,
 * x, v, f in 3-D, HDF5 1.10), shuffle + deflate 1 takes 1.08 s per output against 0.05 s
 * uncompressed, for files 44% smaller; that is not cheap next to a force pass. */
#define OUT_STATIC_DEFLATE 1
/* Field output k's group: zero-padded, so listings (h5ls) sort them in output order. */
#define OUT_STEP_GROUP "/steps/%06ld"
#define OUT_MAX_REACTION 8 /* = the size of pdk_history.reaction */
#define OUT_MAX_COLS (6 + 2 * OUT_MAX_REACTION * 3 + 6 + OUT_MAX_REACTION + 2 * PDK_MAX_WALLS + 1)
#define OUT_NAME_MAX (PDK_FIELD_NAME_MAX + 16)
#define OUT_COL_MAX (OUT_NAME_MAX + 32) /* reaction_<name>_x */

static const char *const axis_name[3] = {"x", "y", "z"};

struct pdk_output {
  /* 1: a rank other than 0 of a run on several ranks (docs/scaling.md): it writes nothing, rank 0
   * writes the output (every rank holds the whole body) */
  int mute;
  pdk_ctx *ctx;
  pdk_particles *p; /* borrowed */
  int dim;
  pdk_index n;
  int compression; /* deflate level, 0 = off */
  int will_plot;   /* plot asked for and gnuplot found at open */
  int failed;      /* a write failed: the files are incomplete and close(.., 1) refuses */
  char *dir;
  char *name;
  char *h5_ref; /* "<name>.h5", XML-escaped: how the .xmf names the data file */
  char *final[OUT_NUM_FILES], *part[OUT_NUM_FILES];
  char *adopt_part, *adopt_final; /* pdk_output_adopt: a caller's file committed with the set */
  hid_t file;
  hid_t history; /* /history group */
  FILE *xmf, *csv;
  int num_steps; /* field outputs written */
  /* The fields of the last field output (as given, and their dataset names), its step and time:
   * what <name>_fields.csv holds. */
  int num_last;
  char (*last_field)[OUT_NAME_MAX], (*last_dname)[OUT_NAME_MAX];
  long last_step;
  double last_time;
  long rows;     /* history records written */
  int num_cols;
  char col_name[OUT_MAX_COLS][OUT_COL_MAX];
  const char *col_unit[OUT_MAX_COLS];
  hid_t col_dset[OUT_MAX_COLS];
  double col_absmax[OUT_MAX_COLS];
  int num_reaction;
  char reaction_name[OUT_MAX_REACTION][OUT_NAME_MAX];  /* sanitized, without "set:" */
  char reaction_field[OUT_MAX_REACTION][OUT_NAME_MAX]; /* "set:<name>" as given */
  int reaction_col[OUT_MAX_REACTION];                  /* first reaction column of set k */
  int disp_col[OUT_MAX_REACTION];                      /* first displacement column, or -1 */
  double reaction_n[OUT_MAX_REACTION][3]; /* unit direction of reaction_<set>_n, or zero */
  int reaction_n_col[OUT_MAX_REACTION];   /* its column, or -1 */
  int work_col; /* plastic_work; damage_work and breaking_work follow */
  /* walls: wall_<name>_force and wall_<name>_impulse per wall from wall_col, then contact_work;
   * the impulses and time of the previous row give the mean force since it */
  int num_walls, wall_col;
  double wall_prev_impulse[PDK_MAX_WALLS], wall_prev_time;
  int num_sets;
  char (*set_name)[OUT_NAME_MAX];  /* [num_sets] sanitized names of the "set:*" fields at open */
  char (*set_field)[OUT_NAME_MAX]; /* [num_sets] their field names, "set:<name>" */
  const char *unit_time, *unit_energy, *unit_force, *unit_length;
  const char *unit_stress, *unit_temperature; /* and these for the fields' unit attributes */
  double thickness; /* 2-D: the out-of-plane thickness the volumes include (0: not given) */
};

typedef enum out_layout { OUT_SCALAR, OUT_VECTOR, OUT_TENSOR, OUT_MATRIX } out_layout;

/* ---- src/io/output.c ------------------------------------------------------------------------------
 */

/* Dataset name of a field: every character outside [A-Za-z0-9_-] becomes '_'. */
void pdk_out_sanitize(const char *in, char *out, size_t cap);
/* malloc'd copy of s with the five XML special characters escaped. */
char *pdk_out_xml_escape(const char *s);
/* malloc'd copy of s for a single-quoted gnuplot string ('' stands for '). */
char *pdk_out_gnuplot_quote(const char *s);
/* Comma-separated names of the registered fields, for "no such field" messages. */
void pdk_out_field_list(const pdk_particles *p, char *buf, size_t cap);
/* Flushes the three growing files; an error here usually means a full disk. */
int pdk_out_flush_files(pdk_output *o);

/* ---- src/io/output_fields.c -----------------------------------------------------------------------
 */

/* How a field of num_comp components is stored: the dataset's columns and where component c goes.
 */
out_layout pdk_out_field_layout(int dim, int num_comp, int *cols, int col_of[9]);
/* Creates the dataset `name` in loc, [n] (cols = 1) or [n][cols], chunked by OUT_CHUNK_ROWS rows,
 * shuffled and deflated at `level` when level > 0 and this HDF5 has deflate. */
int pdk_out_create_field_dataset(pdk_output *o, hid_t loc, const char *name, pdk_type type,
                                 int cols, int level, hid_t *out);
/* The unit of a particle field pdk declares in the output's units, or NULL (see there). */
const char *pdk_out_field_unit(const pdk_output *o, const char *field, char *buf, size_t len);
/* Creates and writes the dataset `name` in loc from field `field` of p, deflated at `level`. */
int pdk_out_write_field(pdk_output *o, pdk_particles *p, hid_t loc, const char *name,
                        const char *field, int level, out_layout *layout_out, int *cols_out,
                        pdk_type *type_out);

/* Opens a grid (time, topology, geometry from `geometry_path`) and adds the static attributes
 * that are not among `fields`. The caller adds the fields and closes the grid. */
int pdk_out_xmf_grid_open(pdk_output *o, long step, double time, const char *geometry_path,
                          const char *const *fields, int num_fields);

/* 1 when `name` is among the fields of this output. */
int pdk_out_listed(const char *name, const char *const *fields, int num_fields);

/* ---- src/io/output_restart.c ----------------------------------------------------------------------
 */

/* The start of every .xmf, up to its grids. */
extern const char pdk_out_xmf_header[];
/* The CSV's header line (with its newline), malloc'd. */
char *pdk_out_csv_header(const pdk_output *o);
/* Copies the earlier output's records up to step `upto` into the new files. Runs at the end of
 * pdk_output_open, after the headers. */
int pdk_out_append_earlier(pdk_output *o, long upto, const char *scene);

/* ---- src/io/output_plot.c -------------------------------------------------------------------------
 */

/* Writes the history's gnuplot script (as .part; committed by the caller). */
int pdk_out_write_plot_script(pdk_output *o);
/* Runs gnuplot on script part[gp], which reads part[data] and writes part[png]. */
int pdk_out_run_gnuplot(pdk_output *o, int gp, int png, int data);

/* ---- src/io/output_snapshot.c ---------------------------------------------------------------------
 */


#define SNAP_MAX_PANELS 6

/* What write_snapshot_csv wrote, for the plot: CSV columns (1-based) of the plotted positions and
 * of each panel's value (|u| from two columns), and the positions' bounding box. */
typedef struct out_snapshot {
  int pos_col[2]; /* x, y columns; pos_add[c] > 0: plus that column (X + u) */
  int pos_add[2];
  int num_panels;
  char title[SNAP_MAX_PANELS][OUT_NAME_MAX + 8];
  char unit[SNAP_MAX_PANELS][64]; /* the panel's unit (field_unit), "" when unknown */
  int col[SNAP_MAX_PANELS]; /* value column; norm[k] > 0: the length of that many from col */
  int norm[SNAP_MAX_PANELS];
  /* Over the particles that have not failed (all when "failed" is not written): the positions'
   * bounding box, the view, and each panel's range of values, its colour scale, so that failed
   * particles flung far away do not shrink the body or the scales. */
  double lo[2], hi[2];
  double ref_lo[2], ref_hi[2]; /* reference positions of every particle written: the failed panel */
  double vlo[SNAP_MAX_PANELS], vhi[SNAP_MAX_PANELS];
  pdk_index num_shown;
  int failed_col; /* column of "failed" (0: not written); the other panels leave failed out */
  double slice_z; /* 3-D: the reference z of the layer written; NAN in 2-D */
  pdk_index num_rows; /* particles written */
} out_snapshot;

/* Writes <name>_fields.csv (as .part) from the last field output and fills *snap. */
int pdk_out_write_snapshot_csv(pdk_output *o, out_snapshot *snap);
/* Writes <name>_fields.gp (as .part), the plot of the snapshot. */
int pdk_out_write_snapshot_script(pdk_output *o, const out_snapshot *snap);

#endif
