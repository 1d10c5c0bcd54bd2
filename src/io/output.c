/* Run output: HDF5 fields and histories, an XDMF index for ParaView, CSV histories and a gnuplot
 * PNG; the layout and the crash-safety rule are in include/pdk/output.h. This file holds the
 * object (open, history records, close); field outputs, appending, the plot and the snapshot are
 * in the files src/io/output_impl.h lists.
 *
 * An output owns five files, each written as <final>.part and renamed by pdk_output_close:
 *   OUT_H5   <name>.h5             static data at open, one group per field output, histories
 *   OUT_XMF  <name>.xmf            header at open, one grid appended per field output, footer at
 *                                  close (so the .part is readable up to the last output)
 *   OUT_CSV  <name>_history.csv    header at open, one row per history record
 *   OUT_GP   <name>_history.gp     gnuplot script, written at close
 *   OUT_PNG  <name>_history.png    made by gnuplot at close, when it is on the PATH
 *   OUT_FCSV <name>_fields.csv     the last field output, one row per particle (3-D: one layer),
 *                                  written at close from the .h5 (so it is that output's data)
 *   OUT_FGP  <name>_fields.gp      gnuplot script drawing it, written at close
 *   OUT_FPNG <name>_fields.png     made by gnuplot at close, when it is on the PATH
 * Field outputs flush the HDF5 file, the XDMF and the CSV (H5Fflush, fflush). Close completes
 * every new file as .part (gnuplot reads and writes .part files), syncs them, removes the previous
 * run's files of this name (its .xmf first), then renames the new ones (the .xmf last): see
 * finish(). The name must be printable (no control character): it reaches the gnuplot scripts
 * as single-quoted strings, where only ' is special.
 *
 * Histories: one f64 dataset per column under /history, extended by one row per record (chunks
 * of OUT_HIST_CHUNK rows). Columns (o->col_name): step, time, kinetic, strain, external_work,
 * broken, then reaction_<set>_<c> for every reaction set and component, then disp_<set>_<c> for
 * every reaction set whose "set:<set>" field exists (mean of x - X over its members, in index
 * order), then plastic_work, damage_work, breaking_work, dt (the step size; 0 in static), failed
 * (particles whose Johnson-Cook damage reached D_c) and damage_max (the largest D), then
 * reaction_<set>_n for every reaction set given a direction (opts->reaction_normals).
 * col_absmax keeps each column's largest |value| so the plot can pick the component that carries
 * the load.
 */
#define _DEFAULT_SOURCE /* fork, execlp, pipe, access */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "output_impl.h"
#include "pdk/ctx.h"
#include "pdk/explicit.h"
#include "pdk/comm.h"
#include "pdk/output.h"
#include "pdk/particles.h"

pdk_output_opts pdk_output_opts_default(void) {
  pdk_output_opts o;
  memset(&o, 0, sizeof o);
  o.dir = ".";
  o.name = "pdk";
  o.plot = 1;
  o.compression = 0;
  return o;
}

/* ---- open -------------------------------------------------------------------------------------
 */

static int gnuplot_on_path(void) {
  const char *path = getenv("PATH");
  if (!path) return 0;
  const char *q = path;
  for (;;) {
    const char *end = strchr(q, ':');
    size_t len = end ? (size_t)(end - q) : strlen(q);
    char buf[4096];
    if (len + 10 < sizeof buf) {
      if (len == 0)
        strcpy(buf, "./gnuplot");
      else {
        memcpy(buf, q, len);
        strcpy(buf + len, "/gnuplot");
      }
      if (access(buf, X_OK) == 0) return 1;
    }
    if (!end) return 0;
    q = end + 1;
  }
}

static int set_units(pdk_output *o, const char *units) {
  if (!units) {
    o->unit_time = "time";
    o->unit_energy = "energy";
    o->unit_force = "force";
    o->unit_length = "length";
    o->unit_stress = "pressure";
    o->unit_temperature = "temperature";
  } else if (!strcmp(units, "SI")) {
    o->unit_time = "s";
    o->unit_energy = "J";
    o->unit_force = "N";
    o->unit_length = "m";
    o->unit_stress = "Pa";
    o->unit_temperature = "K";
  } else if (!strcmp(units, "mm-N-s-tonne")) {
    o->unit_time = "s";
    o->unit_energy = "mJ";
    o->unit_force = "N";
    o->unit_length = "mm";
    o->unit_stress = "MPa";
    o->unit_temperature = "K";
  } else {
    return pdk_ctx_error_set(o->ctx, PDK_ERR_ARG, __func__,
                             "unknown output units '%s'; use \"SI\", \"mm-N-s-tonne\" or none",
                             units);
  }
  return PDK_SUCCESS;
}

static void add_column(pdk_output *o, const char *name, const char *unit) {
  snprintf(o->col_name[o->num_cols], OUT_COL_MAX, "%s", name);
  o->col_unit[o->num_cols] = unit;
  o->num_cols++;
}

/* The history columns, in order (see the file comment). */
static int define_columns(pdk_output *o, const pdk_output_opts *opts) {
  pdk_ctx *ctx = o->ctx;
  char buf[OUT_COL_MAX];
  add_column(o, "step", "-");
  add_column(o, "time", o->unit_time);
  add_column(o, "kinetic", o->unit_energy);
  add_column(o, "strain", o->unit_energy);
  add_column(o, "external_work", o->unit_energy);
  add_column(o, "broken", "bonds");
  o->num_reaction = opts->num_reaction_sets;
  for (int k = 0; k < o->num_reaction; ++k) {
    const char *s = opts->reaction_sets[k];
    PDK_CHECK(s && s[0], ctx, PDK_ERR_ARG, "reaction set %d has no name", k);
    const char *bare = strncmp(s, "set:", 4) ? s : s + 4;
    PDK_CHECK(strlen(bare) + 5 < OUT_NAME_MAX, ctx, PDK_ERR_ARG,
              "reaction set name '%s' is too long", s);
    pdk_out_sanitize(bare, o->reaction_name[k], sizeof o->reaction_name[k]);
    snprintf(o->reaction_field[k], OUT_NAME_MAX, "set:%s", bare);
    for (int j = 0; j < k; ++j)
      PDK_CHECK(strcmp(o->reaction_name[j], o->reaction_name[k]), ctx, PDK_ERR_ARG,
                "reaction sets %d and %d both give the history column name '%s'", j, k,
                o->reaction_name[k]);
  }
  for (int k = 0; k < o->num_reaction; ++k) {
    o->reaction_col[k] = o->num_cols;
    for (int c = 0; c < o->dim; ++c) {
      snprintf(buf, sizeof buf, "reaction_%s_%s", o->reaction_name[k], axis_name[c]);
      add_column(o, buf, o->unit_force);
    }
  }
  for (int k = 0; k < o->num_reaction; ++k) {
    o->disp_col[k] = -1;
    const uint8_t *member = pdk_particles_field_data(o->p, o->reaction_field[k], 0);
    if (!member || !pdk_particles_field_exists(o->p, "x")) continue;
    pdk_index count = 0;
    for (pdk_index i = 0; i < o->n; ++i)
      count += member[i] != 0;
    if (!count) continue;
    o->disp_col[k] = o->num_cols;
    for (int c = 0; c < o->dim; ++c) {
      snprintf(buf, sizeof buf, "disp_%s_%s", o->reaction_name[k], axis_name[c]);
      add_column(o, buf, o->unit_length);
    }
  }
  /* Dissipated energy last, so the columns before keep their places. */
  o->work_col = o->num_cols;
  add_column(o, "plastic_work", o->unit_energy);
  add_column(o, "damage_work", o->unit_energy);
  add_column(o, "breaking_work", o->unit_energy);
  add_column(o, "dt", o->unit_time); /* the explicit step size (changes with dt_update) */
  add_column(o, "failed", "particles");
  add_column(o, "damage_max", "-");
  for (int k = 0; k < o->num_reaction; ++k) { /* along the direction of a roller on the set */
    o->reaction_n_col[k] = -1;
    const double *d = opts->reaction_normals ? opts->reaction_normals[k] : NULL;
    if (!d || (d[0] == 0 && d[1] == 0 && d[2] == 0)) continue;
    memcpy(o->reaction_n[k], d, sizeof o->reaction_n[k]);
    o->reaction_n_col[k] = o->num_cols;
    snprintf(buf, sizeof buf, "reaction_%s_n", o->reaction_name[k]);
    add_column(o, buf, o->unit_force);
  }
  /* Walls after everything else, so scenes without walls keep their columns. */
  PDK_CHECK(opts->num_walls >= 0 && opts->num_walls <= PDK_MAX_WALLS &&
                (opts->num_walls == 0 || opts->walls),
            ctx, PDK_ERR_ARG, "0 to %d walls can be recorded, got %d", PDK_MAX_WALLS,
            opts->num_walls);
  o->num_walls = opts->num_walls;
  o->wall_col = o->num_cols;
  for (int k = 0; k < o->num_walls; ++k) {
    char bare[OUT_NAME_MAX];
    PDK_CHECK(opts->walls[k] && opts->walls[k][0] && strlen(opts->walls[k]) + 16 < OUT_COL_MAX, ctx,
              PDK_ERR_ARG, "wall %d has no name or a name too long for a column", k);
    pdk_out_sanitize(opts->walls[k], bare, sizeof bare);
    snprintf(buf, sizeof buf, "wall_%s_force", bare);
    add_column(o, buf, o->unit_force);
    snprintf(buf, sizeof buf, "wall_%s_impulse", bare);
    add_column(o, buf, "N s");
  }
  if (o->num_walls) add_column(o, "contact_work", o->unit_energy);
  return PDK_SUCCESS;
}

/* /static/connectivity: int32 [n] = 0, 1, ..., n-1, the polyvertex cells of the XDMF grids.
 * Readers differ on a polyvertex topology without connectivity (ParaView's Xdmf3 reader makes no
 * cells of it); spelled out it costs a few bytes once deflated. */
static int write_connectivity(pdk_output *o, hid_t g) {
  pdk_ctx *ctx = o->ctx;
  int err = PDK_SUCCESS;
  hid_t d = -1;
  herr_t st;
  int32_t *cells = malloc((size_t)o->n * sizeof *cells);
  PDK_CHECK(cells, ctx, PDK_ERR_MEMORY, "out of memory for %d cells", (int)o->n);
  for (pdk_index i = 0; i < o->n; ++i)
    cells[i] = i;
  PDK_CALL_GOTO(
      pdk_out_create_field_dataset(o, g, "connectivity", PDK_I32, 1, OUT_STATIC_DEFLATE, &d));
  PDK_H5_CALL_GOTO(ctx, st, H5Dwrite(d, H5T_NATIVE_INT32, H5S_ALL, H5S_ALL, H5P_DEFAULT, cells));
cleanup:
  if (d >= 0) H5Dclose(d);
  free(cells);
  return err;
}

/* Root attributes and /static. */
static int write_static(pdk_output *o, const char *scene_text) {
  pdk_ctx *ctx = o->ctx;
  pdk_particles *p = o->p;
  int err = PDK_SUCCESS;
  hid_t g = -1, gs = -1;
  PDK_CALL_GOTO(pdk_h5_write_provenance(ctx, o->file, "pdk output"));
  PDK_CALL_GOTO(pdk_h5_attr_write_i64(ctx, o->file, "dimension", o->dim));
  PDK_CALL_GOTO(pdk_h5_attr_write_i64(ctx, o->file, "num_particles", o->n));
  if (scene_text) PDK_CALL_GOTO(pdk_h5_text_write(ctx, o->file, "scene", scene_text));
  PDK_H5_CALL_GOTO(ctx, g, H5Gcreate2(o->file, "static", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  PDK_CALL_GOTO(pdk_out_write_field(o, p, g, "id", "id", OUT_STATIC_DEFLATE, NULL, NULL, NULL));
  PDK_CALL_GOTO(pdk_out_write_field(o, p, g, "X", "X", OUT_STATIC_DEFLATE, NULL, NULL, NULL));
  PDK_CALL_GOTO(
      pdk_out_write_field(o, p, g, "volume", "volume", OUT_STATIC_DEFLATE, NULL, NULL, NULL));
  PDK_CALL_GOTO(write_connectivity(o, g));
  PDK_H5_CALL_GOTO(ctx, gs, H5Gcreate2(g, "sets", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  int num_fields = pdk_particles_num_fields(p);
  o->set_name = calloc((size_t)num_fields + 1, sizeof *o->set_name);
  o->set_field = calloc((size_t)num_fields + 1, sizeof *o->set_field);
  PDK_CHECK_GOTO(o->set_name && o->set_field, ctx, PDK_ERR_MEMORY, "out of memory");
  for (int k = 0; k < num_fields; ++k) {
    const char *f = pdk_particles_field_name(p, k);
    pdk_type type;
    int num_comp;
    if (strncmp(f, "set:", 4)) continue;
    PDK_CALL_GOTO(pdk_particles_field_info(p, f, &type, &num_comp));
    if (type != PDK_U8 || num_comp != 1) continue;
    char *name = o->set_name[o->num_sets];
    pdk_out_sanitize(f + 4, name, OUT_NAME_MAX);
    for (int j = 0; j < o->num_sets; ++j)
      PDK_CHECK_GOTO(strcmp(o->set_name[j], name), ctx, PDK_ERR_ARG,
                     "two sets give the dataset name '%s' (characters outside [A-Za-z0-9_-] become "
                     "'_'); rename one",
                     name);
    snprintf(o->set_field[o->num_sets], OUT_NAME_MAX, "%s", f);
    PDK_CALL_GOTO(pdk_out_write_field(o, p, gs, name, f, OUT_STATIC_DEFLATE, NULL, NULL, NULL));
    o->num_sets++;
  }
cleanup:
  if (gs >= 0) H5Gclose(gs);
  if (g >= 0) H5Gclose(g);
  return err;
}

static int create_history(pdk_output *o) {
  pdk_ctx *ctx = o->ctx;
  int err = PDK_SUCCESS;
  hid_t space = -1, dcpl = -1;
  herr_t st;
  hsize_t dims[1] = {0}, maxdims[1] = {H5S_UNLIMITED}, chunk[1] = {OUT_HIST_CHUNK};
  PDK_H5_CALL_GOTO(ctx, o->history,
                   H5Gcreate2(o->file, "history", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  PDK_H5_CALL_GOTO(ctx, space, H5Screate_simple(1, dims, maxdims));
  PDK_H5_CALL_GOTO(ctx, dcpl, H5Pcreate(H5P_DATASET_CREATE));
  PDK_H5_CALL_GOTO(ctx, st, H5Pset_chunk(dcpl, 1, chunk));
  for (int k = 0; k < o->num_cols; ++k) {
    PDK_H5_CALL_GOTO(ctx, o->col_dset[k],
                     H5Dcreate2(o->history, o->col_name[k], H5T_IEEE_F64LE, space, H5P_DEFAULT,
                                dcpl, H5P_DEFAULT));
    PDK_CALL_GOTO(pdk_h5_attr_write_string(ctx, o->col_dset[k], "unit", o->col_unit[k]));
  }
cleanup:
  if (dcpl >= 0) H5Pclose(dcpl);
  if (space >= 0) H5Sclose(space);
  return err;
}

/* Column col of the last history row (-1 when unreadable). */
static double last_row_value(const pdk_output *o, int col) {
  double v = -1.0;
  hid_t fspace = H5Dget_space(o->col_dset[col]), mspace = -1;
  const hsize_t start[1] = {(hsize_t)o->rows - 1}, one[1] = {1};
  if (fspace < 0 || H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, one, NULL) < 0 ||
      (mspace = H5Screate_simple(1, one, NULL)) < 0 ||
      H5Dread(o->col_dset[col], H5T_NATIVE_DOUBLE, mspace, fspace, H5P_DEFAULT, &v) < 0)
    v = -1.0;
  H5Eclear2(H5E_DEFAULT);
  if (mspace >= 0) H5Sclose(mspace);
  if (fspace >= 0) H5Sclose(fspace);
  return v;
}

long pdk_output_last_history_step(const pdk_output *o) {
  if (!o || o->rows <= 0) return -1;
  return (long)last_row_value(o, 0);
}

long pdk_output_last_field_step(const pdk_output *o) {
  return o && o->num_steps > 0 ? o->last_step : -1;
}

static void output_free(pdk_output *o);

int pdk_output_open(pdk_ctx *ctx, const pdk_output_opts *opts_in, pdk_particles *p,
                    pdk_output **out) {
  int err = PDK_SUCCESS;
  pdk_output *o = NULL;
  pdk_output_opts opts = opts_in ? *opts_in : pdk_output_opts_default();
  const char *dir = opts.dir && opts.dir[0] ? opts.dir : ".";
  PDK_CHECK_ARG(out, ctx);
  *out = NULL;
  PDK_CHECK_ARG(ctx, NULL);
  PDK_CHECK(p, ctx, PDK_ERR_ARG, "no particle store given");
  PDK_CHECK(opts.name && opts.name[0] && !strchr(opts.name, '/') && !strchr(opts.name, ':'), ctx,
            PDK_ERR_ARG,
            "output name '%s' must be a non-empty file stem without '/' or ':' (put "
            "directories in opts.dir)",
            opts.name ? opts.name : "(null)");
  for (const char *q = opts.name; *q; ++q)
    PDK_CHECK((unsigned char)*q >= 0x20 && *q != 0x7f, ctx, PDK_ERR_ARG,
              "output name has a control character (byte 0x%02x at position %d); a file stem "
              "must be printable text: choose another name",
              (unsigned)(unsigned char)*q, (int)(q - opts.name));
  PDK_CHECK(opts.compression >= 0 && opts.compression <= 9, ctx, PDK_ERR_ARG,
            "output compression must be a deflate level 0..9, got %d", opts.compression);
  PDK_CHECK(isfinite(opts.thickness) && opts.thickness >= 0, ctx, PDK_ERR_ARG,
            "output thickness must be >= 0 (0: not said), got %g", opts.thickness);
  PDK_CHECK(opts.num_reaction_sets >= 0 && opts.num_reaction_sets <= OUT_MAX_REACTION &&
                (opts.num_reaction_sets == 0 || opts.reaction_sets),
            ctx, PDK_ERR_ARG, "0 to %d reaction sets can be recorded, got %d", OUT_MAX_REACTION,
            opts.num_reaction_sets);
  o = calloc(1, sizeof *o);
  PDK_CHECK(o, ctx, PDK_ERR_MEMORY, "out of memory creating the output");
  o->ctx = ctx;
  o->p = p;
  if (pdk_comm_rank() != 0) { /* several ranks: rank 0 writes */
    o->mute = 1;
    *out = o;
    return PDK_SUCCESS;
  }
  o->dim = pdk_particles_dim(p);
  o->n = pdk_particles_count(p);
  o->compression = opts.compression;
  o->thickness = opts.thickness;
  o->file = o->history = -1;
  for (int k = 0; k < OUT_MAX_COLS; ++k)
    o->col_dset[k] = -1;
  PDK_CALL_GOTO(set_units(o, opts.units));
  o->dir = strdup(dir);
  o->name = strdup(opts.name);
  o->h5_ref = pdk_str_printf("%s.h5", opts.name);
  PDK_CHECK_GOTO(o->dir && o->name && o->h5_ref, ctx, PDK_ERR_MEMORY, "out of memory");
  {
    char *escaped = pdk_out_xml_escape(o->h5_ref);
    PDK_CHECK_GOTO(escaped, ctx, PDK_ERR_MEMORY, "out of memory");
    free(o->h5_ref);
    o->h5_ref = escaped;
  }
  static const char *const suffix[OUT_NUM_FILES] = {".h5",         ".xmf",         "_history.csv",
                                                    "_history.gp", "_history.png", "_fields.csv",
                                                    "_fields.gp",  "_fields.png"};
  for (int f = 0; f < OUT_NUM_FILES; ++f) {
    o->final[f] = pdk_str_printf("%s/%s%s", dir, opts.name, suffix[f]);
    o->part[f] = pdk_str_printf("%s/%s%s.part", dir, opts.name, suffix[f]);
    PDK_CHECK_GOTO(o->final[f] && o->part[f], ctx, PDK_ERR_MEMORY, "out of memory");
  }
  PDK_CALL_GOTO(define_columns(o, &opts));
  o->will_plot = opts.plot && gnuplot_on_path();
  PDK_CALL_GOTO(pdk_dir_create(ctx, dir));

  PDK_CALL_GOTO(pdk_h5_file_create(ctx, o->part[OUT_H5], &o->file));
  PDK_CALL_GOTO(write_static(o, opts.scene_text));
  PDK_CALL_GOTO(create_history(o));
  {
    hid_t g;
    PDK_H5_CALL_GOTO(ctx, g, H5Gcreate2(o->file, "steps", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    H5Gclose(g);
  }

  o->xmf = fopen(o->part[OUT_XMF], "w");
  PDK_CHECK_GOTO(o->xmf, ctx, PDK_ERR_IO, "cannot create '%s': %s", o->part[OUT_XMF],
                 strerror(errno));
  fputs(pdk_out_xmf_header, o->xmf);

  o->csv = fopen(o->part[OUT_CSV], "w");
  PDK_CHECK_GOTO(o->csv, ctx, PDK_ERR_IO, "cannot create '%s': %s", o->part[OUT_CSV],
                 strerror(errno));
  {
    char *hdr = pdk_out_csv_header(o);
    PDK_CHECK_GOTO(hdr, ctx, PDK_ERR_MEMORY, "out of memory");
    fputs(hdr, o->csv);
    free(hdr);
  }
  PDK_CALL_GOTO(pdk_out_flush_files(o));
  if (opts.append) PDK_CALL_GOTO(pdk_out_append_earlier(o, opts.append_step, opts.append_scene));
  if (o->rows > 0 && o->num_walls) { /* a continued history: the mean forces go on from its end */
    o->wall_prev_time = last_row_value(o, 1);
    for (int k = 0; k < o->num_walls; ++k)
      o->wall_prev_impulse[k] = last_row_value(o, o->wall_col + 2 * k + 1);
  }
  *out = o;
  return PDK_SUCCESS;
cleanup:
  output_free(o);
  return err;
}

/* ---- writes: history ---------------------------------------------------------------------------
 */

static void set_displacement(pdk_output *o, int k, double out[3]) {
  const uint8_t *member = pdk_particles_field_data(o->p, o->reaction_field[k], 0);
  double sum[3] = {0, 0, 0};
  pdk_index count = 0;
  for (int c = 0; c < 3; ++c)
    out[c] = 0.0;
  if (!member) return;
  for (int c = 0; c < o->dim; ++c) {
    const double *x = pdk_particles_field_data(o->p, "x", c), *X = pdk_particles_X(o->p, c);
    if (!x) return;
    count = 0;
    for (pdk_index i = 0; i < o->n; ++i)
      if (member[i]) {
        sum[c] += x[i] - X[i];
        count++;
      }
  }
  for (int c = 0; c < o->dim; ++c)
    out[c] = count ? sum[c] / (double)count : 0.0;
}

int pdk_output_write_history(pdk_output *o, const pdk_history *h) {
  PDK_CHECK_ARG(o, NULL);
  if (o->mute) return PDK_SUCCESS;
  pdk_ctx *ctx = o->ctx;
  PDK_CHECK_ARG(h, ctx);
  int err = PDK_SUCCESS;
  hid_t fspace = -1, mspace = -1;
  herr_t st;
  double row[OUT_MAX_COLS];
  PDK_CHECK(!o->failed, ctx, PDK_ERR_ARG,
            "an earlier write to '%s' failed; close the output with success = 0", o->part[OUT_H5]);
  PDK_CHECK(h, ctx, PDK_ERR_ARG, "no history record given");
  row[0] = (double)h->step;
  row[1] = h->time;
  row[2] = h->kinetic;
  row[3] = h->strain;
  row[4] = h->external_work;
  row[5] = (double)h->broken;
  for (int k = 0; k < o->num_reaction; ++k)
    for (int c = 0; c < o->dim; ++c)
      row[o->reaction_col[k] + c] = h->reaction[k][c];
  for (int k = 0; k < o->num_reaction; ++k) {
    if (o->disp_col[k] < 0) continue;
    double u[3];
    set_displacement(o, k, u);
    for (int c = 0; c < o->dim; ++c)
      row[o->disp_col[k] + c] = u[c];
  }
  row[o->work_col] = h->plastic_work;
  row[o->work_col + 1] = h->damage_work;
  row[o->work_col + 2] = h->breaking_work;
  row[o->work_col + 3] = h->dt;
  row[o->work_col + 4] = (double)h->failed;
  row[o->work_col + 5] = h->damage_max;
  for (int k = 0; k < o->num_reaction; ++k)
    if (o->reaction_n_col[k] >= 0) {
      double rn = 0.0;
      for (int c = 0; c < o->dim; ++c)
        rn += h->reaction[k][c] * o->reaction_n[k][c];
      row[o->reaction_n_col[k]] = rn;
    }
  for (int k = 0; k < o->num_walls; ++k) {
    const double dt = h->time - o->wall_prev_time;
    row[o->wall_col + 2 * k] =
        o->rows > 0 && dt > 0 ? (h->wall_impulse[k] - o->wall_prev_impulse[k]) / dt : 0.0;
    row[o->wall_col + 2 * k + 1] = h->wall_impulse[k];
  }
  if (o->num_walls) row[o->wall_col + 2 * o->num_walls] = h->contact_work;

  o->failed = 1; /* until the row is complete */
  hsize_t size[1] = {(hsize_t)o->rows + 1}, start[1] = {(hsize_t)o->rows}, one[1] = {1};
  PDK_H5_CALL_GOTO(ctx, mspace, H5Screate_simple(1, one, NULL));
  for (int k = 0; k < o->num_cols; ++k) {
    PDK_H5_CALL_GOTO(ctx, st, H5Dset_extent(o->col_dset[k], size));
    PDK_H5_CALL_GOTO(ctx, fspace, H5Dget_space(o->col_dset[k]));
    PDK_H5_CALL_GOTO(ctx, st, H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, one, NULL));
    PDK_H5_CALL_GOTO(
        ctx, st, H5Dwrite(o->col_dset[k], H5T_NATIVE_DOUBLE, mspace, fspace, H5P_DEFAULT, &row[k]));
    H5Sclose(fspace);
    fspace = -1;
    if (fabs(row[k]) > o->col_absmax[k]) o->col_absmax[k] = fabs(row[k]);
  }
  fprintf(o->csv, "%ld,%.17g,%.17g,%.17g,%.17g,%lld", h->step, row[1], row[2], row[3], row[4],
          (long long)h->broken);
  for (int k = 6; k < o->num_cols; ++k)
    fprintf(o->csv, ",%.17g", row[k]);
  fprintf(o->csv, "\n");
  PDK_CHECK_GOTO(!ferror(o->csv), ctx, PDK_ERR_IO, "cannot write '%s': %s", o->part[OUT_CSV],
                 strerror(errno));
  PDK_CALL_GOTO(pdk_h5_file_check(ctx, o->file, o->part[OUT_H5]));
  for (int k = 0; k < o->num_walls; ++k)
    o->wall_prev_impulse[k] = h->wall_impulse[k];
  o->wall_prev_time = h->time;
  o->rows++;
  o->failed = 0;
cleanup:
  if (fspace >= 0) H5Sclose(fspace);
  if (mspace >= 0) H5Sclose(mspace);
  if (err && pdk_h5_file_error(o->file)) /* the disk's error, not what HDF5 made of it */
    err = pdk_h5_file_check(ctx, o->file, o->part[OUT_H5]);
  return err;
}

int pdk_output_will_plot(const pdk_output *o) { return o ? o->will_plot : 0; }
int pdk_output_num_field_steps(const pdk_output *o) { return o ? o->num_steps : 0; }
long pdk_output_num_history_rows(const pdk_output *o) { return o ? o->rows : 0; }

/* ---- close ------------------------------------------------------------------------------------
 */

/* Closes every open handle (no error reporting: used on every path). */
static void close_handles(pdk_output *o) {
  if (o->xmf) fclose(o->xmf);
  if (o->csv) fclose(o->csv);
  o->xmf = o->csv = NULL;
  for (int k = 0; k < OUT_MAX_COLS; ++k)
    if (o->col_dset[k] >= 0) {
      H5Dclose(o->col_dset[k]);
      o->col_dset[k] = -1;
    }
  if (o->history >= 0) H5Gclose(o->history);
  if (o->file >= 0) pdk_h5_file_close(NULL, o->file, o->part[OUT_H5]);
  o->history = o->file = -1;
}

static void output_free(pdk_output *o) {
  if (!o) return;
  close_handles(o);
  for (int f = 0; f < OUT_NUM_FILES; ++f) {
    if (o->part[f]) pdk_file_remove(o->part[f]);
    free(o->part[f]);
    free(o->final[f]);
  }
  if (o->adopt_part) pdk_file_remove(o->adopt_part);
  free(o->adopt_part);
  free(o->adopt_final);
  free(o->set_name);
  free(o->set_field);
  free(o->last_field);
  free(o->last_dname);
  free(o->dir);
  free(o->name);
  free(o->h5_ref);
  free(o);
}

/* The closing phase. Every new file is completed under its temporary name first (the plots are
 * made from the temporary data files); then the previous run's files of this name are removed,
 * its .xmf first; then the new files get their final names, the .xmf last. A kill at any point
 * leaves files of one run only: until the first removal the previous run's set is whole (beside
 * the new .part files), after it only new files or none get final names, and a <name>.xmf is
 * there only when its whole set is. Returns the plot's error, if any, after everything else
 * succeeded (that PNG is then missing; no older PNG is left in its place). */
static int finish(pdk_output *o) {
  pdk_ctx *ctx = o->ctx;
  herr_t st;
  int made[OUT_NUM_FILES] = {0}; /* new files complete under their temporary names */
  if (o->num_steps == 0) { /* no field output: the reference configuration, so the .xmf opens */
    PDK_CALL(pdk_out_xmf_grid_open(o, 0, 0.0, "/static/X", NULL, 0));
    fprintf(o->xmf, "    </Grid>\n");
  }
  fprintf(o->xmf, "    </Grid>\n  </Domain>\n</Xdmf>\n");
  int bad = fflush(o->xmf) != 0 || ferror(o->xmf);
  bad |= fclose(o->xmf) != 0;
  o->xmf = NULL;
  PDK_CHECK(!bad, ctx, PDK_ERR_IO, "cannot write '%s': %s", o->part[OUT_XMF], strerror(errno));
  bad = fflush(o->csv) != 0 || ferror(o->csv);
  bad |= fclose(o->csv) != 0;
  o->csv = NULL;
  PDK_CHECK(!bad, ctx, PDK_ERR_IO, "cannot write '%s': %s", o->part[OUT_CSV], strerror(errno));
  for (int k = 0; k < o->num_cols; ++k) {
    st = H5Dclose(o->col_dset[k]);
    o->col_dset[k] = -1;
    PDK_CHECK(st >= 0, ctx, PDK_ERR_EXTERNAL, "H5Dclose of history column '%s' failed",
              o->col_name[k]);
  }
  st = H5Gclose(o->history);
  o->history = -1;
  PDK_CHECK(st >= 0, ctx, PDK_ERR_EXTERNAL, "H5Gclose of /history failed");
  /* everything written so far reached the disk before anything is read back from it */
  PDK_CALL(pdk_h5_file_flush(ctx, o->file, o->part[OUT_H5]));
  out_snapshot snap = {0};
  const int snapshot = o->num_steps > 0;
  if (snapshot) PDK_CALL(pdk_out_write_snapshot_csv(o, &snap));
  hid_t file = o->file;
  o->file = -1;
  PDK_CALL(pdk_h5_file_close(ctx, file, o->part[OUT_H5]));
  made[OUT_H5] = made[OUT_XMF] = made[OUT_CSV] = 1;
  made[OUT_FCSV] = snapshot;

  int plot_err = PDK_SUCCESS;
  if (o->will_plot && o->rows > 0) {
    PDK_CALL(pdk_out_write_plot_script(o));
    made[OUT_GP] = 1;
    plot_err = pdk_out_run_gnuplot(o, OUT_GP, OUT_PNG, OUT_CSV);
    made[OUT_PNG] = !plot_err;
  }
  if (snap.num_panels > 0 && o->will_plot && !plot_err) {
    PDK_CALL(pdk_out_write_snapshot_script(o, &snap));
    made[OUT_FGP] = 1;
    plot_err = pdk_out_run_gnuplot(o, OUT_FGP, OUT_FPNG, OUT_FCSV);
    made[OUT_FPNG] = !plot_err;
  }
  for (int f = 0; f < OUT_NUM_FILES; ++f)
    if (made[f]) PDK_CALL(pdk_file_sync(ctx, o->part[f]));
  if (o->adopt_part) PDK_CALL(pdk_file_sync(ctx, o->adopt_part));

  /* the previous run's files, the .xmf first: from here on its set is incomplete */
  PDK_CALL(pdk_file_discard(ctx, o->final[OUT_XMF]));
  for (int f = 0; f < OUT_NUM_FILES; ++f)
    if (f != OUT_XMF) PDK_CALL(pdk_file_discard(ctx, o->final[f]));
  if (o->adopt_final) PDK_CALL(pdk_file_discard(ctx, o->adopt_final));
  /* the new files, the .xmf last */
  for (int f = 0; f < OUT_NUM_FILES; ++f)
    if (f != OUT_XMF && made[f]) PDK_CALL(pdk_file_commit(ctx, o->part[f], o->final[f]));
  if (o->adopt_part) {
    PDK_CALL(pdk_file_commit(ctx, o->adopt_part, o->adopt_final));
    free(o->adopt_part);
    o->adopt_part = NULL;
  }
  PDK_CALL(pdk_file_commit(ctx, o->part[OUT_XMF], o->final[OUT_XMF]));
  return plot_err;
}

int pdk_output_adopt(pdk_output *o, const char *part, const char *final) {
  PDK_CHECK_ARG(o, NULL);
  pdk_ctx *ctx = o->ctx;
  PDK_CHECK(part && part[0] && final && final[0] && strcmp(part, final), ctx, PDK_ERR_ARG,
            "pdk_output_adopt needs a file's temporary name and another, final name");
  if (o->mute) return PDK_SUCCESS;
  PDK_CHECK(!o->adopt_part, ctx, PDK_ERR_ARG,
            "the output already adopted '%s': it takes one file of the caller's", o->adopt_part);
  PDK_CHECK(pdk_file_exists(part), ctx, PDK_ERR_IO, "cannot adopt '%s': it does not exist", part);
  o->adopt_part = strdup(part);
  o->adopt_final = strdup(final);
  if (!o->adopt_part || !o->adopt_final) {
    free(o->adopt_part);
    free(o->adopt_final);
    o->adopt_part = o->adopt_final = NULL;
    return pdk_ctx_error_set(ctx, PDK_ERR_MEMORY, __func__, "out of memory");
  }
  return PDK_SUCCESS;
}

int pdk_output_close(pdk_output **op, int success) {
  if (!op || !*op) return PDK_SUCCESS;
  pdk_output *o = *op;
  *op = NULL;
  if (o->mute) {
    free(o);
    return PDK_SUCCESS;
  }
  int err = PDK_SUCCESS;
  if (success && o->failed)
    err = pdk_ctx_error_set(o->ctx, PDK_ERR_ARG, __func__,
                            "an earlier write to '%s' failed, so the output is incomplete; its "
                            "files were removed",
                            o->part[OUT_H5]);
  else if (success)
    err = finish(o);
  output_free(o); /* removes whatever .part files remain */
  return err;
}
