/* Run output: HDF5 fields and histories, an XDMF index for ParaView, CSV histories and a gnuplot
 * PNG; the layout and the crash-safety rule are in include/pdk/output.h.
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
 * (particles whose Johnson-Cook damage reached D_c) and damage_max (the largest D).
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

#include "h5io.h"
#include "pdk/output.h"

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
#define OUT_MAX_COLS (6 + 2 * OUT_MAX_REACTION * 3 + 6)
#define OUT_NAME_MAX (PDK_FIELD_NAME_MAX + 16)
#define OUT_COL_MAX (OUT_NAME_MAX + 32) /* reaction_<name>_x */

static const char *const axis_name[3] = {"x", "y", "z"};

struct pdk_output {
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
  int work_col; /* plastic_work; damage_work and breaking_work follow */
  int num_sets;
  char (*set_name)[OUT_NAME_MAX];  /* [num_sets] sanitized names of the "set:*" fields at open */
  char (*set_field)[OUT_NAME_MAX]; /* [num_sets] their field names, "set:<name>" */
  const char *unit_time, *unit_energy, *unit_force, *unit_length;
  const char *unit_stress, *unit_temperature; /* and these for the fields' unit attributes */
  double thickness; /* 2-D: the out-of-plane thickness the volumes include (0: not given) */
};

pdk_output_opts pdk_output_opts_default(void) {
  pdk_output_opts o;
  memset(&o, 0, sizeof o);
  o.dir = ".";
  o.name = "pdk";
  o.plot = 1;
  o.compression = 0;
  return o;
}

/* ---- names ------------------------------------------------------------------------------------
 */

/* Dataset name of a field: every character outside [A-Za-z0-9_-] becomes '_'. */
static void sanitize(const char *in, char *out, size_t cap) {
  size_t k = 0;
  for (; in[k] && k + 1 < cap; ++k) {
    char c = in[k];
    int ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
             c == '_' || c == '-';
    out[k] = ok ? c : '_';
  }
  out[k] = '\0';
}

/* malloc'd copy of s with the five XML special characters escaped. */
static char *xml_escape(const char *s) {
  size_t len = 0;
  for (const char *q = s; *q; ++q)
    len += *q == '&' ? 5 : (*q == '<' || *q == '>') ? 4 : (*q == '"' || *q == '\'') ? 6 : 1;
  char *out = malloc(len + 1), *w = out;
  if (!out) return NULL;
  for (const char *q = s; *q; ++q) {
    switch (*q) {
    case '&':
      memcpy(w, "&amp;", 5);
      w += 5;
      break;
    case '<':
      memcpy(w, "&lt;", 4);
      w += 4;
      break;
    case '>':
      memcpy(w, "&gt;", 4);
      w += 4;
      break;
    case '"':
      memcpy(w, "&quot;", 6);
      w += 6;
      break;
    case '\'':
      memcpy(w, "&apos;", 6);
      w += 6;
      break;
    default: *w++ = *q;
    }
  }
  *w = '\0';
  return out;
}

/* malloc'd copy of s for a single-quoted gnuplot string ('' stands for '). */
static char *gnuplot_quote(const char *s) {
  size_t len = strlen(s);
  for (const char *q = s; *q; ++q)
    len += *q == '\'';
  char *out = malloc(len + 1), *w = out;
  if (!out) return NULL;
  for (const char *q = s; *q; ++q) {
    if (*q == '\'') *w++ = '\'';
    *w++ = *q;
  }
  *w = '\0';
  return out;
}

/* Comma-separated names of the registered fields, for "no such field" messages. */
static void field_list(const pdk_particles *p, char *buf, size_t cap) {
  size_t len = 0;
  buf[0] = '\0';
  for (int k = 0; k < pdk_particles_num_fields(p) && len + 1 < cap; ++k) {
    int w = snprintf(buf + len, cap - len, "%s%s", k ? ", " : "", pdk_particles_field_name(p, k));
    if (w < 0) break;
    len += (size_t)w < cap - len ? (size_t)w : cap - len - 1;
  }
}

/* ---- field layout -----------------------------------------------------------------------------
 */

typedef enum out_layout { OUT_SCALAR, OUT_VECTOR, OUT_TENSOR, OUT_MATRIX } out_layout;

/* How a field of num_comp components is stored: the dataset's columns and where component c goes.
 */
static out_layout field_layout(int dim, int num_comp, int *cols, int col_of[9]) {
  if (num_comp == 1) {
    *cols = 1;
    col_of[0] = 0;
    return OUT_SCALAR;
  }
  if (num_comp == dim) {
    *cols = 3;
    for (int c = 0; c < dim; ++c)
      col_of[c] = c;
    return OUT_VECTOR;
  }
  if (num_comp == dim * dim) { /* component [a][c] at a*dim + c goes to 3a + c */
    *cols = 9;
    for (int a = 0; a < dim; ++a)
      for (int c = 0; c < dim; ++c)
        col_of[a * dim + c] = 3 * a + c;
    return OUT_TENSOR;
  }
  *cols = num_comp;
  for (int c = 0; c < num_comp; ++c)
    col_of[c] = c;
  return OUT_MATRIX;
}

static const char *layout_name(out_layout l) {
  static const char *const names[] = {"Scalar", "Vector", "Tensor", "Matrix"};
  return names[l];
}

/* XDMF NumberType and Precision of a pdk type. */
static const char *xdmf_number_type(pdk_type t, int *precision) {
  *precision = (int)pdk_type_size(t);
  switch (t) {
  case PDK_F64:
  case PDK_F32: return "Float";
  case PDK_I64:
  case PDK_I32: return "Int";
  case PDK_U8: return "UChar";
  }
  return "Float";
}

/* ---- HDF5 datasets ----------------------------------------------------------------------------
 */

/* Creates the dataset `name` in loc, [n] (cols = 1) or [n][cols], chunked by OUT_CHUNK_ROWS rows,
 * shuffled and deflated at `level` when level > 0 and this HDF5 has deflate. */
static int create_field_dataset(pdk_output *o, hid_t loc, const char *name, pdk_type type, int cols,
                                int level, hid_t *out) {
  pdk_ctx *ctx = o->ctx;
  int err = PDK_SUCCESS;
  hid_t space = -1, dcpl = -1;
  herr_t st;
  hsize_t dims[2] = {(hsize_t)o->n, (hsize_t)cols};
  hsize_t chunk[2] = {(hsize_t)(o->n < OUT_CHUNK_ROWS ? o->n : OUT_CHUNK_ROWS), (hsize_t)cols};
  int rank = cols > 1 ? 2 : 1;
  *out = -1;
  PDK_H5_CALL_GOTO(ctx, space, H5Screate_simple(rank, dims, NULL));
  PDK_H5_CALL_GOTO(ctx, dcpl, H5Pcreate(H5P_DATASET_CREATE));
  PDK_H5_CALL_GOTO(ctx, st, H5Pset_chunk(dcpl, rank, chunk));
  PDK_H5_CALL_GOTO(ctx, st, H5Pset_fill_time(dcpl, H5D_FILL_TIME_NEVER));
  if (level > 0 && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
    PDK_H5_CALL_GOTO(ctx, st, H5Pset_shuffle(dcpl));
    PDK_H5_CALL_GOTO(ctx, st, H5Pset_deflate(dcpl, (unsigned)level));
  }
  PDK_H5_CALL_GOTO(
      ctx, *out,
      H5Dcreate2(loc, name, pdk_h5_file_type(type), space, H5P_DEFAULT, dcpl, H5P_DEFAULT));
cleanup:
  if (dcpl >= 0) H5Pclose(dcpl);
  if (space >= 0) H5Sclose(space);
  return err;
}

/* Copies `rows` elements of `elem` bytes from src into column `col` of a row-major buffer of
 * `cols` columns. */
static void scatter_column(void *restrict dst, int cols, int col, const void *restrict src,
                           pdk_index rows, size_t elem) {
  switch (elem) {
  case 8: {
    uint64_t *d = dst;
    const uint64_t *s = src;
    for (pdk_index i = 0; i < rows; ++i)
      d[(size_t)i * cols + col] = s[i];
    break;
  }
  case 4: {
    uint32_t *d = dst;
    const uint32_t *s = src;
    for (pdk_index i = 0; i < rows; ++i)
      d[(size_t)i * cols + col] = s[i];
    break;
  }
  default: {
    unsigned char *d = dst;
    const unsigned char *s = src;
    for (pdk_index i = 0; i < rows; ++i)
      memcpy(d + ((size_t)i * cols + col) * elem, s + (size_t)i * elem, elem);
  }
  }
}

/* Writes a field (comp[c] = its component arrays) into dataset d: directly when it has one
 * column, else interleaved chunk by chunk (zeros in the padding columns). */
static int write_field_data(pdk_output *o, hid_t d, pdk_type type, int num_comp, int cols,
                            const int *col_of, void *const *comp) {
  pdk_ctx *ctx = o->ctx;
  int err = PDK_SUCCESS;
  hid_t fspace = -1, mspace = -1;
  herr_t st;
  unsigned char *buf = NULL;
  const size_t elem = pdk_type_size(type);
  const hid_t mtype = pdk_h5_mem_type(type);
  if (cols == 1) {
    PDK_H5_CALL_GOTO(ctx, st, H5Dwrite(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, comp[0]));
    goto cleanup;
  }
  const pdk_index block = o->n < OUT_CHUNK_ROWS ? o->n : OUT_CHUNK_ROWS;
  buf = malloc((size_t)block * (size_t)cols * elem);
  PDK_CHECK_GOTO(buf, ctx, PDK_ERR_MEMORY, "out of memory for an output buffer of %d rows",
                 (int)block);
  PDK_H5_CALL_GOTO(ctx, fspace, H5Dget_space(d));
  for (pdk_index r0 = 0; r0 < o->n; r0 += block) {
    pdk_index rows = o->n - r0 < block ? o->n - r0 : block;
    memset(buf, 0, (size_t)rows * (size_t)cols * elem);
    for (int c = 0; c < num_comp; ++c)
      scatter_column(buf, cols, col_of[c], (const unsigned char *)comp[c] + (size_t)r0 * elem, rows,
                     elem);
    hsize_t start[2] = {(hsize_t)r0, 0}, count[2] = {(hsize_t)rows, (hsize_t)cols};
    PDK_H5_CALL_GOTO(ctx, st,
                     H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, count, NULL));
    PDK_H5_CALL_GOTO(ctx, mspace, H5Screate_simple(2, count, NULL));
    PDK_H5_CALL_GOTO(ctx, st, H5Dwrite(d, mtype, mspace, fspace, H5P_DEFAULT, buf));
    H5Sclose(mspace);
    mspace = -1;
  }
cleanup:
  free(buf);
  if (mspace >= 0) H5Sclose(mspace);
  if (fspace >= 0) H5Sclose(fspace);
  return err;
}

static int name_in(const char *name, const char *const *list, int n) {
  for (int k = 0; k < n; ++k)
    if (!strcmp(name, list[k])) return 1;
  return 0;
}

/* The unit of a particle field pdk declares, in the output's units (output.units: "m", "s", "N",
 * "J", "Pa" with SI; "mm", "s", "N", "mJ", "MPa" with mm-N-s-tonne; the names of the quantities,
 * "length", "time", ..., without), or NULL for a field pdk does not know (a caller's own) or that
 * has none (ids, indices, set flags). "1": dimensionless. */
static const char *field_unit(const pdk_output *o, const char *field, char *buf, size_t len) {
  static const char *const length[] = {"x", "X", "u", "ul_X"};
  static const char *const one[] = {"eps_p", "damage", "failed", "stab_factor", "theta",
                                    "F",     "ul_F",   "ul_J",   "flag"};
  static const char *const stress[] = {"von_mises", "sigma_m", "sigma_m_avg"};
  static const char *const energy_density[] = {"w_plastic", "w_damage", "w_broken", "w_stab",
                                               "w_silling"};
  static const char *const volume[] = {"volume", "ul_volume"};
#define OUT_IN(list) (name_in(field, list, (int)(sizeof list / sizeof list[0])))
  if (OUT_IN(length)) return o->unit_length;
  if (OUT_IN(one)) return "1";
  if (OUT_IN(stress)) return o->unit_stress;
  if (!strcmp(field, "temp_rise")) return o->unit_temperature;
  if (OUT_IN(volume))
    snprintf(buf, len, "%s^3", o->unit_length);
  else if (!strcmp(field, "v"))
    snprintf(buf, len, "%s/%s", o->unit_length, o->unit_time);
  else if (!strcmp(field, "f")) /* force density */
    snprintf(buf, len, "%s/%s^3", o->unit_force, o->unit_length);
  else if (OUT_IN(energy_density))
    snprintf(buf, len, "%s/%s^3", o->unit_energy, o->unit_length);
  else if (!strcmp(field, "eps_p_rate"))
    snprintf(buf, len, "1/%s", o->unit_time);
  else
    return NULL;
#undef OUT_IN
  return buf;
}

/* Creates and writes the dataset `name` in loc from field `field` of p, deflated at `level`. */
static int write_field(pdk_output *o, pdk_particles *p, hid_t loc, const char *name,
                       const char *field, int level, out_layout *layout_out, int *cols_out,
                       pdk_type *type_out) {
  int err = PDK_SUCCESS;
  hid_t d = -1;
  pdk_type type;
  int num_comp, cols, col_of[9];
  void *comp[9];
  PDK_CALL(pdk_particles_field_info(p, field, &type, &num_comp));
  out_layout layout = field_layout(o->dim, num_comp, &cols, col_of);
  for (int c = 0; c < num_comp; ++c)
    comp[c] = pdk_particles_field_data(p, field, c);
  PDK_CALL_GOTO(create_field_dataset(o, loc, name, type, cols, level, &d));
  PDK_CALL_GOTO(write_field_data(o, d, type, num_comp, cols, col_of, comp));
  {
    char buf[64];
    const char *unit = field_unit(o, field, buf, sizeof buf);
    if (unit) PDK_CALL_GOTO(pdk_h5_attr_write_string(o->ctx, d, "unit", unit));
  }
  if (layout_out) *layout_out = layout;
  if (cols_out) *cols_out = cols;
  if (type_out) *type_out = type;
cleanup:
  if (d >= 0) H5Dclose(d);
  return err;
}

/* ---- XDMF -------------------------------------------------------------------------------------
 */

static void xmf_data_item(pdk_output *o, const char *indent, int cols, pdk_type type,
                          const char *path) {
  int precision;
  const char *number_type = xdmf_number_type(type, &precision);
  if (cols == 1)
    fprintf(o->xmf,
            "%s<DataItem Dimensions=\"%d\" NumberType=\"%s\" Precision=\"%d\" "
            "Format=\"HDF\">%s:%s</DataItem>\n",
            indent, (int)o->n, number_type, precision, o->h5_ref, path);
  else
    fprintf(o->xmf,
            "%s<DataItem Dimensions=\"%d %d\" NumberType=\"%s\" Precision=\"%d\" "
            "Format=\"HDF\">%s:%s</DataItem>\n",
            indent, (int)o->n, cols, number_type, precision, o->h5_ref, path);
}

/* A node attribute named after the field (XML-escaped). */
static int xmf_attribute(pdk_output *o, const char *name, out_layout layout, int cols,
                         pdk_type type, const char *path) {
  char *escaped = xml_escape(name);
  PDK_CHECK(escaped, o->ctx, PDK_ERR_MEMORY, "out of memory");
  fprintf(o->xmf, "      <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Node\">\n", escaped,
          layout_name(layout));
  free(escaped);
  xmf_data_item(o, "        ", cols, type, path);
  fprintf(o->xmf, "      </Attribute>\n");
  return PDK_SUCCESS;
}

/* Opens a grid (time, topology, geometry from `geometry_path`) and adds the static attributes
 * that are not among `fields`. The caller adds the fields and closes the grid. */
static int xmf_grid_open(pdk_output *o, long step, double time, const char *geometry_path,
                         const char *const *fields, int num_fields);

/* 1 when `name` is among the fields of this output (then its static attribute is left out: one
 * grid must not hold two attributes of the same name). */
static int listed(const char *name, const char *const *fields, int num_fields) {
  for (int k = 0; k < num_fields; ++k)
    if (!strcmp(fields[k], name)) return 1;
  return 0;
}

static int xmf_grid_open(pdk_output *o, long step, double time, const char *geometry_path,
                         const char *const *fields, int num_fields) {
  char path[2 * OUT_NAME_MAX + 32];
  fprintf(o->xmf, "    <Grid Name=\"step_%ld\" GridType=\"Uniform\">\n", step);
  fprintf(o->xmf, "      <Time Value=\"%.17g\"/>\n", time);
  fprintf(o->xmf,
          "      <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%d\" "
          "NodesPerElement=\"1\">\n",
          (int)o->n);
  xmf_data_item(o, "        ", 1, PDK_I32, "/static/connectivity");
  fprintf(o->xmf, "      </Topology>\n");
  fprintf(o->xmf, "      <Geometry GeometryType=\"XYZ\">\n");
  xmf_data_item(o, "        ", 3, PDK_F64, geometry_path);
  fprintf(o->xmf, "      </Geometry>\n");
  if (!listed("id", fields, num_fields))
    PDK_CALL(xmf_attribute(o, "id", OUT_SCALAR, 1, PDK_I64, "/static/id"));
  if (!listed("volume", fields, num_fields))
    PDK_CALL(xmf_attribute(o, "volume", OUT_SCALAR, 1, PDK_F64, "/static/volume"));
  for (int s = 0; s < o->num_sets; ++s) {
    if (listed(o->set_field[s], fields, num_fields)) continue;
    snprintf(path, sizeof path, "/static/sets/%s", o->set_name[s]);
    PDK_CALL(xmf_attribute(o, o->set_field[s], OUT_SCALAR, 1, PDK_U8, path));
  }
  return PDK_SUCCESS;
}

/* Flushes the three growing files; an error here usually means a full disk. */
static int flush_files(pdk_output *o) {
  pdk_ctx *ctx = o->ctx;
  PDK_CHECK(fflush(o->xmf) == 0 && !ferror(o->xmf), ctx, PDK_ERR_IO, "cannot write '%s': %s",
            o->part[OUT_XMF], strerror(errno));
  PDK_CHECK(fflush(o->csv) == 0 && !ferror(o->csv), ctx, PDK_ERR_IO, "cannot write '%s': %s",
            o->part[OUT_CSV], strerror(errno));
  return pdk_h5_file_flush(ctx, o->file, o->part[OUT_H5]);
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
    sanitize(bare, o->reaction_name[k], sizeof o->reaction_name[k]);
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
  PDK_CALL_GOTO(create_field_dataset(o, g, "connectivity", PDK_I32, 1, OUT_STATIC_DEFLATE, &d));
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
  PDK_CALL_GOTO(write_field(o, p, g, "id", "id", OUT_STATIC_DEFLATE, NULL, NULL, NULL));
  PDK_CALL_GOTO(write_field(o, p, g, "X", "X", OUT_STATIC_DEFLATE, NULL, NULL, NULL));
  PDK_CALL_GOTO(write_field(o, p, g, "volume", "volume", OUT_STATIC_DEFLATE, NULL, NULL, NULL));
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
    sanitize(f + 4, name, OUT_NAME_MAX);
    for (int j = 0; j < o->num_sets; ++j)
      PDK_CHECK_GOTO(strcmp(o->set_name[j], name), ctx, PDK_ERR_ARG,
                     "two sets give the dataset name '%s' (characters outside [A-Za-z0-9_-] become "
                     "'_'); rename one",
                     name);
    snprintf(o->set_field[o->num_sets], OUT_NAME_MAX, "%s", f);
    PDK_CALL_GOTO(write_field(o, p, gs, name, f, OUT_STATIC_DEFLATE, NULL, NULL, NULL));
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

/* ---- restart: continuing the output of an earlier run -----------------------------------------
 *
 * pdk_output_open with opts.append: when <name>.h5, .xmf and _history.csv of an earlier run are in
 * dir, the new .part files start as a copy of their records up to opts.append_step (history rows
 * with step <= it, field outputs /steps/<k> whose step attribute is <= it, and their XDMF grids),
 * and the run appends to that; records after it (written after the checkpoint by the run that was
 * interrupted) are dropped, so a restarted run's files equal those of a run that never stopped:
 * the CSV and the XDMF byte for byte, the HDF5 dataset for dataset (the kept field outputs are
 * copied with H5Ocopy, the history rows value for value). The earlier files must be of this
 * output: the same particles (every /static dataset), the same history columns, the checkpoint's
 * scene (opts.append_scene), and agree with one another (the CSV's rows are the .h5's, the .xmf's
 * grids its field outputs); anything else is an error that names what differs and changes none of
 * the earlier files.
 */

static const char xmf_header[] =
    "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
    "<Xdmf Version=\"2.0\">\n  <Domain>\n"
    "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
static const char xmf_footer[] = "    </Grid>\n  </Domain>\n</Xdmf>\n"; /* as finish() writes it */
static const char xmf_grid_start[] = "    <Grid Name=\"step_";
static const char xmf_grid_end[] = "\n    </Grid>\n";

/* The CSV's header line (with its newline), malloc'd. */
static char *csv_header(const pdk_output *o) {
  size_t len = 2, pos = 0;
  for (int k = 0; k < o->num_cols; ++k)
    len += strlen(o->col_name[k]) + strlen(o->col_unit[k]) + 4;
  char *h = malloc(len);
  if (!h) return NULL;
  for (int k = 0; k < o->num_cols; ++k)
    pos += (size_t)snprintf(h + pos, len - pos, "%s%s [%s]", k ? "," : "", o->col_name[k],
                            o->col_unit[k]);
  snprintf(h + pos, len - pos, "\n");
  return h;
}

/* A whole file into a malloc'd, NUL-terminated buffer. */
static int read_text_file(pdk_output *o, const char *path, char **text, size_t *len) {
  pdk_ctx *ctx = o->ctx;
  int err = PDK_SUCCESS;
  char *buf = NULL;
  FILE *f = fopen(path, "rb");
  *text = NULL;
  PDK_CHECK(f, ctx, PDK_ERR_IO, "cannot read '%s': %s", path, strerror(errno));
  long size = -1;
  if (fseek(f, 0, SEEK_END) == 0) size = ftell(f);
  PDK_CHECK_GOTO(size >= 0 && fseek(f, 0, SEEK_SET) == 0, ctx, PDK_ERR_IO, "cannot read '%s': %s",
                 path, strerror(errno));
  buf = malloc((size_t)size + 1);
  PDK_CHECK_GOTO(buf, ctx, PDK_ERR_MEMORY, "out of memory reading '%s' (%ld bytes)", path, size);
  PDK_CHECK_GOTO(fread(buf, 1, (size_t)size, f) == (size_t)size, ctx, PDK_ERR_IO,
                 "cannot read '%s': %s", path, ferror(f) ? strerror(errno) : "it got shorter");
  buf[size] = '\0';
  *text = buf;
  *len = (size_t)size;
  buf = NULL;
cleanup:
  free(buf);
  fclose(f);
  return err;
}

/* 1 when dataset `path` exists in both files with the same type, shape and bytes. */
static int same_dataset(hid_t fa, hid_t fb, const char *path) {
  hid_t d[2] = {-1, -1}, t[2] = {-1, -1}, s[2] = {-1, -1};
  unsigned char *buf[2] = {NULL, NULL};
  int same = 0;
  const hid_t f[2] = {fa, fb};
  for (int k = 0; k < 2; ++k)
    if ((d[k] = H5Dopen2(f[k], path, H5P_DEFAULT)) < 0 || (t[k] = H5Dget_type(d[k])) < 0 ||
        (s[k] = H5Dget_space(d[k])) < 0)
      goto done;
  if (H5Tequal(t[0], t[1]) <= 0 || H5Sextent_equal(s[0], s[1]) <= 0) goto done;
  const hssize_t np = H5Sget_simple_extent_npoints(s[0]);
  const size_t bytes = (size_t)(np > 0 ? np : 0) * H5Tget_size(t[0]);
  for (int k = 0; k < 2; ++k)
    if (!(buf[k] = malloc(bytes + 1)) ||
        (bytes && H5Dread(d[k], t[k], H5S_ALL, H5S_ALL, H5P_DEFAULT, buf[k]) < 0))
      goto done;
  same = !memcmp(buf[0], buf[1], bytes);
done:
  H5Eclear2(H5E_DEFAULT);
  for (int k = 0; k < 2; ++k) {
    free(buf[k]);
    if (s[k] >= 0) H5Sclose(s[k]);
    if (t[k] >= 0) H5Tclose(t[k]);
    if (d[k] >= 0) H5Dclose(d[k]);
  }
  return same;
}

/* Number of links in group `path` of file f, or -1 when it is not a readable group. */
static long group_size(hid_t f, const char *path) {
  H5G_info_t info;
  hid_t g = H5Gopen2(f, path, H5P_DEFAULT);
  long n = g >= 0 && H5Gget_info(g, &info) >= 0 ? (long)info.nlinks : -1;
  if (g >= 0) H5Gclose(g);
  H5Eclear2(H5E_DEFAULT);
  return n;
}

/* The XML text between a quote and the next '"' (or '<'), with the five entities undone. */
static void xml_unescape_to(const char *q, const char *end, char *out, size_t cap) {
  static const char *const ent[5] = {"&amp;", "&lt;", "&gt;", "&quot;", "&apos;"};
  static const char chr[5] = {'&', '<', '>', '"', '\''};
  size_t k = 0;
  while (q < end && k + 1 < cap) {
    int e = -1;
    for (int j = 0; j < 5 && e < 0; ++j)
      if (!strncmp(q, ent[j], strlen(ent[j]))) e = j;
    out[k++] = e >= 0 ? chr[e] : *q;
    q += e >= 0 ? strlen(ent[e]) : 1;
  }
  out[k] = '\0';
}

/* The fields of the XDMF grid [g, g_end) of field output k, in their order there (the order they
 * were written in): what <name>_fields.csv draws if the run writes no field output of its own. */
static int last_fields_from_grid(pdk_output *o, const char *g, const char *g_end, int k) {
  char prefix[64];
  snprintf(prefix, sizeof prefix, ":" OUT_STEP_GROUP "/", (long)k);
  int n = 0;
  for (const char *q = g; (q = strstr(q, "<Attribute Name=\"")) && q < g_end; ++q)
    ++n;
  char(*lf)[OUT_NAME_MAX] = calloc((size_t)n + 1, sizeof *lf);
  char(*ld)[OUT_NAME_MAX] = calloc((size_t)n + 1, sizeof *ld);
  if (!lf || !ld) {
    free(lf);
    free(ld);
    return pdk_ctx_error_set(o->ctx, PDK_ERR_MEMORY, __func__, "out of memory");
  }
  int m = 0;
  for (const char *q = g; (q = strstr(q, "<Attribute Name=\"")) && q < g_end;) {
    q += strlen("<Attribute Name=\"");
    const char *name_end = strchr(q, '"');
    const char *item_end = name_end ? strstr(name_end, "</DataItem>") : NULL;
    if (!item_end || item_end > g_end) break;
    const char *path = strstr(name_end, prefix);
    if (path && path < item_end) {
      char field[OUT_NAME_MAX];
      xml_unescape_to(q, name_end, field, sizeof field);
      path += strlen(prefix);
      if (pdk_particles_field_exists(o->p, field) && (size_t)(item_end - path) < OUT_NAME_MAX) {
        snprintf(lf[m], OUT_NAME_MAX, "%s", field);
        memcpy(ld[m], path, (size_t)(item_end - path));
        ld[m][item_end - path] = '\0';
        ++m;
      }
    }
    q = item_end;
  }
  free(o->last_field);
  free(o->last_dname);
  o->last_field = lf;
  o->last_dname = ld;
  o->num_last = m;
  return PDK_SUCCESS;
}

#define EARLIER_MISFIT(o, ...)                                                                     \
  do {                                                                                             \
    char why_[1024];                                                                               \
    snprintf(why_, sizeof why_, __VA_ARGS__);                                                      \
    err = pdk_ctx_error_set((o)->ctx, PDK_ERR_ARG, __func__,                                       \
                            "the output already in '%s' cannot be continued: %s; write the "       \
                            "restart's output to another folder, or move %s.h5, %s.xmf and "       \
                            "%s_history.csv out of '%s'",                                          \
                            (o)->dir, why_, (o)->name, (o)->name, (o)->name, (o)->dir);            \
    goto cleanup;                                                                                  \
  } while (0)

/* Copies the earlier output's records up to step `upto` into the new files (see above). Runs at
 * the end of pdk_output_open, after the headers. */
static int append_earlier(pdk_output *o, long upto, const char *scene) {
  pdk_ctx *ctx = o->ctx;
  int err = PDK_SUCCESS;
  hid_t old = -1, d = -1, fspace = -1, mspace = -1, g = -1;
  herr_t st;
  char *csv = NULL, *xmf = NULL, *hdr = NULL, *kind = NULL, *old_scene = NULL;
  double *steps = NULL, *col = NULL;
  const char **grid = NULL; /* [num_grids + 1]: where each XDMF step grid starts, then the end */
  long *gstep = NULL;
  double *gtime = NULL;
  size_t csv_len = 0, xmf_len = 0;
  char path[2 * OUT_NAME_MAX + 32];
  const int have[3] = {pdk_file_exists(o->final[OUT_H5]), pdk_file_exists(o->final[OUT_XMF]),
                       pdk_file_exists(o->final[OUT_CSV])};
  if (!have[0] && !have[1] && !have[2]) return PDK_SUCCESS; /* nothing to continue: afresh */
  static const int kinds[3] = {OUT_H5, OUT_XMF, OUT_CSV};
  for (int k = 0; k < 3; ++k)
    if (!have[k])
      EARLIER_MISFIT(o, "'%s' is missing (the .h5, the .xmf and the history CSV go together)",
                     o->final[kinds[k]]);

  /* 1. check everything, write nothing: the .h5 */
  old = H5Fopen(o->final[OUT_H5], H5F_ACC_RDONLY, H5P_DEFAULT);
  if (old < 0) {
    H5Eclear2(H5E_DEFAULT);
    EARLIER_MISFIT(o, "HDF5 cannot open '%s'", o->final[OUT_H5]);
  }
  int64_t v = -1;
  if (!pdk_h5_attr_exists(old, "kind") || pdk_h5_attr_read_string(ctx, old, "kind", &kind) ||
      strcmp(kind, "pdk output"))
    EARLIER_MISFIT(o, "'%s' is not a pdk output file", o->final[OUT_H5]);
  if (pdk_h5_attr_read_i64(ctx, old, "dimension", &v) || v != o->dim ||
      pdk_h5_attr_read_i64(ctx, old, "num_particles", &v) || v != o->n)
    EARLIER_MISFIT(o, "'%s' is of another body (dimension or particle count)", o->final[OUT_H5]);
  if (scene) {
    if (pdk_h5_text_read(ctx, old, "scene", &old_scene) || !old_scene || strcmp(old_scene, scene))
      EARLIER_MISFIT(o,
                     "'%s' was written by a run of another scene than the checkpoint's (compare "
                     "their 'scene' attributes: h5dump -a scene)",
                     o->final[OUT_H5]);
  }
  static const char *const statics[4] = {"/static/id", "/static/X", "/static/volume",
                                         "/static/connectivity"};
  for (int k = 0; k < 4; ++k)
    if (!same_dataset(old, o->file, statics[k]))
      EARLIER_MISFIT(o, "'%s' has another %s (other particles, or in another order)",
                     o->final[OUT_H5], statics[k]);
  if (group_size(old, "/static/sets") != o->num_sets)
    EARLIER_MISFIT(o, "'%s' has other sets", o->final[OUT_H5]);
  for (int s = 0; s < o->num_sets; ++s) {
    snprintf(path, sizeof path, "/static/sets/%s", o->set_name[s]);
    if (!same_dataset(old, o->file, path))
      EARLIER_MISFIT(o, "'%s' has another set '%s'", o->final[OUT_H5], o->set_name[s]);
  }
  /* the history columns: the same names, one length */
  if (group_size(old, "/history") != o->num_cols)
    EARLIER_MISFIT(o, "'%s' has %ld history columns, this run %d", o->final[OUT_H5],
                   group_size(old, "/history"), o->num_cols);
  hsize_t rows = 0;
  for (int k = 0; k < o->num_cols; ++k) {
    hsize_t dims[1] = {0};
    snprintf(path, sizeof path, "/history/%s", o->col_name[k]);
    d = H5Dopen2(old, path, H5P_DEFAULT);
    if (d < 0 || (fspace = H5Dget_space(d)) < 0 || H5Sget_simple_extent_ndims(fspace) != 1) {
      H5Eclear2(H5E_DEFAULT);
      EARLIER_MISFIT(o, "'%s' has no history column '%s'", o->final[OUT_H5], o->col_name[k]);
    }
    H5Sget_simple_extent_dims(fspace, dims, NULL);
    H5Sclose(fspace);
    fspace = -1;
    H5Dclose(d);
    d = -1;
    if (k > 0 && dims[0] != rows)
      EARLIER_MISFIT(o, "the history columns of '%s' differ in length", o->final[OUT_H5]);
    rows = dims[0];
  }
  steps = malloc(((size_t)rows + 1) * sizeof *steps);
  col = malloc(((size_t)rows + 1) * sizeof *col);
  PDK_CHECK_GOTO(steps && col, ctx, PDK_ERR_MEMORY, "out of memory reading %llu history rows",
                 (unsigned long long)rows);
  if (rows) {
    const hsize_t start[1] = {0}, count[1] = {rows};
    PDK_CALL_GOTO(
        pdk_h5_read_block(ctx, old, "/history/step", H5T_NATIVE_DOUBLE, 1, start, count, steps));
  }
  hsize_t keep = 0; /* rows at or before the checkpoint */
  while (keep < rows && steps[keep] <= (double)upto)
    ++keep;
  for (hsize_t r = 1; r < rows; ++r)
    if (!(steps[r] > steps[r - 1]))
      EARLIER_MISFIT(o, "the history steps of '%s' do not increase (row %llu)", o->final[OUT_H5],
                     (unsigned long long)r);
  if (rows > 0 && keep == 0)
    EARLIER_MISFIT(o, "its history starts at step %.0f, after the checkpoint's step %ld", steps[0],
                   upto);
  /* the field outputs: /steps/000000 .. /steps/<n-1> (six digits), steps increasing */
  const long num_groups = group_size(old, "/steps");
  if (num_groups < 0) EARLIER_MISFIT(o, "'%s' has no /steps group", o->final[OUT_H5]);
  gstep = malloc(((size_t)num_groups + 1) * sizeof *gstep);
  gtime = malloc(((size_t)num_groups + 1) * sizeof *gtime);
  PDK_CHECK_GOTO(gstep && gtime, ctx, PDK_ERR_MEMORY, "out of memory");
  long keep_groups = 0;
  for (long k = 0; k < num_groups; ++k) {
    snprintf(path, sizeof path, OUT_STEP_GROUP, k);
    g = H5Gopen2(old, path, H5P_DEFAULT);
    if (g < 0 || pdk_h5_attr_read_i64(ctx, g, "step", &v) ||
        pdk_h5_attr_read_f64(ctx, g, "time", &gtime[k])) {
      H5Eclear2(H5E_DEFAULT);
      EARLIER_MISFIT(o, "'%s' lacks the field output %s or its step and time", o->final[OUT_H5],
                     path);
    }
    H5Gclose(g);
    g = -1;
    gstep[k] = (long)v;
    if (k > 0 && gstep[k] <= gstep[k - 1])
      EARLIER_MISFIT(o, "the field outputs of '%s' are not in step order (%s)", o->final[OUT_H5],
                     path);
    if (gstep[k] <= upto) keep_groups = k + 1;
  }

  /* the CSV: this run's header, then one row per .h5 history row, with its step */
  PDK_CALL_GOTO(read_text_file(o, o->final[OUT_CSV], &csv, &csv_len));
  hdr = csv_header(o);
  PDK_CHECK_GOTO(hdr, ctx, PDK_ERR_MEMORY, "out of memory");
  const size_t hdr_len = strlen(hdr);
  if (csv_len < hdr_len || memcmp(csv, hdr, hdr_len))
    EARLIER_MISFIT(o, "the header of '%s' names other columns than this run's", o->final[OUT_CSV]);
  const char *q = csv + hdr_len, *csv_end = csv + csv_len, *csv_keep = q;
  hsize_t line = 0;
  while (q < csv_end) {
    const char *nl = memchr(q, '\n', (size_t)(csv_end - q));
    if (!nl) EARLIER_MISFIT(o, "the last line of '%s' is incomplete", o->final[OUT_CSV]);
    char *e = NULL;
    const long step = strtol(q, &e, 10);
    if (line >= rows || e == q || *e != ',' || (double)step != steps[line])
      EARLIER_MISFIT(o, "row %llu of '%s' is not row %llu of '%s'", (unsigned long long)line + 1,
                     o->final[OUT_CSV], (unsigned long long)line + 1, o->final[OUT_H5]);
    q = nl + 1;
    if (++line == keep) csv_keep = q;
  }
  if (line != rows)
    EARLIER_MISFIT(o, "'%s' has %llu rows, '%s' %llu", o->final[OUT_CSV], (unsigned long long)line,
                   o->final[OUT_H5], (unsigned long long)rows);

  /* the XDMF: the header, one grid per field output (or the one grid of the reference
   * configuration when there was none), the footer */
  PDK_CALL_GOTO(read_text_file(o, o->final[OUT_XMF], &xmf, &xmf_len));
  if (strncmp(xmf, xmf_header, strlen(xmf_header)))
    EARLIER_MISFIT(o, "'%s' does not start as a pdk XDMF index", o->final[OUT_XMF]);
  grid = malloc(((size_t)num_groups + 2) * sizeof *grid);
  PDK_CHECK_GOTO(grid, ctx, PDK_ERR_MEMORY, "out of memory");
  long num_grids = 0;
  q = xmf + strlen(xmf_header);
  while (!strncmp(q, xmf_grid_start, strlen(xmf_grid_start))) {
    const char *end = strstr(q, xmf_grid_end);
    if (!end || num_grids > num_groups)
      EARLIER_MISFIT(o, "'%s' has more grids than '%s' has field outputs, or an unfinished one",
                     o->final[OUT_XMF], o->final[OUT_H5]);
    grid[num_grids++] = q;
    q = end + strlen(xmf_grid_end);
  }
  grid[num_grids] = q;
  if (strcmp(q, xmf_footer) || (num_grids != num_groups && !(num_groups == 0 && num_grids == 1)))
    EARLIER_MISFIT(o, "'%s' does not list the %ld field outputs of '%s'", o->final[OUT_XMF],
                   num_groups, o->final[OUT_H5]);
  for (long k = 0; k < keep_groups; ++k) {
    char name[64];
    snprintf(name, sizeof name, "%s%ld\"", xmf_grid_start, gstep[k]);
    if (strncmp(grid[k], name, strlen(name)))
      EARLIER_MISFIT(o, "grid %ld of '%s' is not the field output at step %ld", k + 1,
                     o->final[OUT_XMF], gstep[k]);
  }

  /* 2. copy what is kept */
  o->failed = 1; /* until the copy is complete */
  for (int k = 0; k < o->num_cols && keep > 0; ++k) {
    const hsize_t start[1] = {0}, count[1] = {keep};
    snprintf(path, sizeof path, "/history/%s", o->col_name[k]);
    PDK_CALL_GOTO(pdk_h5_read_block(ctx, old, path, H5T_NATIVE_DOUBLE, 1, start, count, col));
    PDK_H5_CALL_GOTO(ctx, st, H5Dset_extent(o->col_dset[k], count));
    PDK_H5_CALL_GOTO(
        ctx, st, H5Dwrite(o->col_dset[k], H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, col));
    for (hsize_t r = 0; r < keep; ++r)
      if (fabs(col[r]) > o->col_absmax[k]) o->col_absmax[k] = fabs(col[r]);
  }
  o->rows = (long)keep;
  PDK_CHECK_GOTO(fwrite(csv + hdr_len, 1, (size_t)(csv_keep - (csv + hdr_len)), o->csv) ==
                     (size_t)(csv_keep - (csv + hdr_len)),
                 ctx, PDK_ERR_IO, "cannot write '%s': %s", o->part[OUT_CSV], strerror(errno));
  for (long k = 0; k < keep_groups; ++k) {
    snprintf(path, sizeof path, OUT_STEP_GROUP, k);
    PDK_H5_CALL_GOTO(ctx, st, H5Ocopy(old, path, o->file, path, H5P_DEFAULT, H5P_DEFAULT));
  }
  if (keep_groups > 0) {
    const size_t bytes = (size_t)(grid[keep_groups] - grid[0]);
    PDK_CHECK_GOTO(fwrite(grid[0], 1, bytes, o->xmf) == bytes, ctx, PDK_ERR_IO,
                   "cannot write '%s': %s", o->part[OUT_XMF], strerror(errno));
    PDK_CALL_GOTO(
        last_fields_from_grid(o, grid[keep_groups - 1], grid[keep_groups], (int)keep_groups - 1));
    o->last_step = gstep[keep_groups - 1];
    o->last_time = gtime[keep_groups - 1];
  }
  o->num_steps = (int)keep_groups;
  PDK_CALL_GOTO(flush_files(o));
  o->failed = 0;
cleanup:
  if (g >= 0) H5Gclose(g);
  if (mspace >= 0) H5Sclose(mspace);
  if (fspace >= 0) H5Sclose(fspace);
  if (d >= 0) H5Dclose(d);
  if (old >= 0) H5Fclose(old);
  free(csv);
  free(xmf);
  free(hdr);
  free(kind);
  free(old_scene);
  free(steps);
  free(col);
  free(grid);
  free(gstep);
  free(gtime);
  return err;
}

long pdk_output_last_history_step(const pdk_output *o) {
  if (!o || o->rows <= 0) return -1;
  double v = -1.0;
  hid_t fspace = H5Dget_space(o->col_dset[0]), mspace = -1;
  const hsize_t start[1] = {(hsize_t)o->rows - 1}, one[1] = {1};
  if (fspace < 0 || H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, one, NULL) < 0 ||
      (mspace = H5Screate_simple(1, one, NULL)) < 0 ||
      H5Dread(o->col_dset[0], H5T_NATIVE_DOUBLE, mspace, fspace, H5P_DEFAULT, &v) < 0)
    v = -1.0;
  H5Eclear2(H5E_DEFAULT);
  if (mspace >= 0) H5Sclose(mspace);
  if (fspace >= 0) H5Sclose(fspace);
  return (long)v;
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
    char *escaped = xml_escape(o->h5_ref);
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
  fputs(xmf_header, o->xmf);

  o->csv = fopen(o->part[OUT_CSV], "w");
  PDK_CHECK_GOTO(o->csv, ctx, PDK_ERR_IO, "cannot create '%s': %s", o->part[OUT_CSV],
                 strerror(errno));
  {
    char *hdr = csv_header(o);
    PDK_CHECK_GOTO(hdr, ctx, PDK_ERR_MEMORY, "out of memory");
    fputs(hdr, o->csv);
    free(hdr);
  }
  PDK_CALL_GOTO(flush_files(o));
  if (opts.append) PDK_CALL_GOTO(append_earlier(o, opts.append_step, opts.append_scene));
  *out = o;
  return PDK_SUCCESS;
cleanup:
  output_free(o);
  return err;
}

/* ---- writes -----------------------------------------------------------------------------------
 */

int pdk_output_write_fields(pdk_output *o, pdk_particles *p, long step, double time,
                            const char *const *fields, int num_fields) {
  if (!o)
    return p ? pdk_ctx_error_set(pdk_particles_ctx(p), PDK_ERR_ARG, __func__, "no output given")
             : PDK_ERR_ARG;
  pdk_ctx *ctx = o->ctx;
  int err = PDK_SUCCESS;
  hid_t g = -1;
  char(*dname)[OUT_NAME_MAX] = NULL;
  char list[1024], path[2 * OUT_NAME_MAX + 32];
  PDK_CHECK(!o->failed, ctx, PDK_ERR_ARG,
            "an earlier write to '%s' failed; close the output with success = 0", o->part[OUT_H5]);
  PDK_CHECK(p && pdk_particles_count(p) == o->n && pdk_particles_dim(p) == o->dim, ctx, PDK_ERR_ARG,
            "the particle store has %d particles in %d-D, the output was opened for %d in %d-D",
            p ? (int)pdk_particles_count(p) : 0, p ? pdk_particles_dim(p) : 0, (int)o->n, o->dim);
  PDK_CHECK(num_fields >= 0 && (num_fields == 0 || fields), ctx, PDK_ERR_ARG,
            "bad field list (%d names)", num_fields);
  PDK_CHECK(isfinite(time), ctx, PDK_ERR_ARG, "output time must be finite, got %g", time);
  dname = calloc((size_t)num_fields + 1, sizeof *dname);
  PDK_CHECK(dname, ctx, PDK_ERR_MEMORY, "out of memory");
  int geometry = -1; /* index of "x" in fields, when it can serve as the geometry */
  for (int k = 0; k < num_fields; ++k) {
    if (!fields[k] || !pdk_particles_field_exists(p, fields[k])) {
      field_list(p, list, sizeof list);
      PDK_CHECK_GOTO(0, ctx, PDK_ERR_NOT_FOUND,
                     "cannot write field '%s': no such particle field; the fields are: %s",
                     fields[k] ? fields[k] : "(null)", list);
    }
    sanitize(fields[k], dname[k], OUT_NAME_MAX);
    for (int j = 0; j < k; ++j)
      PDK_CHECK_GOTO(strcmp(dname[j], dname[k]), ctx, PDK_ERR_ARG,
                     "fields '%s' and '%s' are listed twice or map to the same dataset name '%s'",
                     fields[j], fields[k], dname[k]);
    pdk_type type;
    int num_comp;
    PDK_CALL_GOTO(pdk_particles_field_info(p, fields[k], &type, &num_comp));
    if (!strcmp(fields[k], "x") && type == PDK_F64 && num_comp == o->dim) geometry = k;
  }

  const int k_out = o->num_steps;
  snprintf(path, sizeof path, OUT_STEP_GROUP, (long)k_out);
  o->failed = 1; /* until this output is complete */
  PDK_H5_CALL_GOTO(ctx, g, H5Gcreate2(o->file, path, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  PDK_CALL_GOTO(pdk_h5_attr_write_i64(ctx, g, "step", step));
  PDK_CALL_GOTO(pdk_h5_attr_write_f64(ctx, g, "time", time));

  if (geometry >= 0)
    snprintf(path, sizeof path, OUT_STEP_GROUP "/%s", (long)k_out, dname[geometry]);
  else
    snprintf(path, sizeof path, "/static/X");
  PDK_CALL_GOTO(xmf_grid_open(o, step, time, path, fields, num_fields));
  for (int k = 0; k < num_fields; ++k) {
    out_layout layout;
    int cols;
    pdk_type type;
    PDK_CALL_GOTO(write_field(o, p, g, dname[k], fields[k], o->compression, &layout, &cols, &type));
    snprintf(path, sizeof path, OUT_STEP_GROUP "/%s", (long)k_out, dname[k]);
    PDK_CALL_GOTO(xmf_attribute(o, fields[k], layout, cols, type, path));
  }
  fprintf(o->xmf, "    </Grid>\n");
  PDK_CALL_GOTO(flush_files(o));
  {
    char(*lf)[OUT_NAME_MAX] = realloc(o->last_field, ((size_t)num_fields + 1) * sizeof *lf);
    if (lf) o->last_field = lf;
    char(*ld)[OUT_NAME_MAX] = realloc(o->last_dname, ((size_t)num_fields + 1) * sizeof *ld);
    if (ld) o->last_dname = ld;
    PDK_CHECK_GOTO(lf && ld, ctx, PDK_ERR_MEMORY, "out of memory");
    for (int k = 0; k < num_fields; ++k) {
      snprintf(o->last_field[k], OUT_NAME_MAX, "%s", fields[k]);
      memcpy(o->last_dname[k], dname[k], OUT_NAME_MAX);
    }
    o->num_last = num_fields;
    o->last_step = step;
    o->last_time = time;
  }
  o->num_steps++;
  o->failed = 0;
cleanup:
  if (g >= 0) H5Gclose(g);
  free(dname);
  if (err && pdk_h5_file_error(o->file)) /* the disk's error, not what HDF5 made of it */
    err = pdk_h5_file_check(ctx, o->file, o->part[OUT_H5]);
  return err;
}

/* Mean displacement x - X of the members of set k, per component, in index order. */
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

/* ---- plot -------------------------------------------------------------------------------------
 */

/* Component of reaction set k with the largest |value| over the run. */
static int main_component(const pdk_output *o, int k) {
  int best = 0;
  for (int c = 1; c < o->dim; ++c)
    if (o->col_absmax[o->reaction_col[k] + c] > o->col_absmax[o->reaction_col[k] + best]) best = c;
  return best;
}

/* 1 when set k has a displacement column and moved along its main reaction component. */
static int moved(const pdk_output *o, int k) {
  return o->disp_col[k] >= 0 && o->col_absmax[o->disp_col[k] + main_component(o, k)] > 0;
}

/* Writes the gnuplot script (as .part; committed by the caller). CSV columns are 1-based. */
static int write_plot_script(pdk_output *o) {
  pdk_ctx *ctx = o->ctx;
  int err = PDK_SUCCESS;
  char *stem = gnuplot_quote(o->name);
  FILE *f = NULL;
  PDK_CHECK_GOTO(stem, ctx, PDK_ERR_MEMORY, "out of memory");
  f = fopen(o->part[OUT_GP], "w");
  PDK_CHECK_GOTO(f, ctx, PDK_ERR_IO, "cannot create '%s': %s", o->part[OUT_GP], strerror(errno));
  int num_disp =
      0; /* sets that moved: plotting a fixed set against its zero displacement says nothing */
  for (int k = 0; k < o->num_reaction; ++k)
    num_disp += moved(o, k);
  /* a failure panel when any particle took Johnson-Cook damage */
  const int fail_col = o->work_col + 4, dmax_col = o->work_col + 5;
  const int damage_panel = o->col_absmax[dmax_col] > 0;
  int panels = 1 + (o->num_reaction > 0) + (num_disp > 0) + damage_panel;
  fprintf(f, "# pdk history plot; rerun with: gnuplot %s%s_history.gp (in this directory)\n",
          o->name[0] == '-' ? "./" : "", o->name);
  fprintf(f, "if (!exists(\"outfile\")) outfile = '%s_history.png'\n", stem);
  fprintf(f,
          "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
          "  set terminal pngcairo size %d,%d noenhanced\n} else {\n"
          "  set terminal png size %d,%d noenhanced\n}\n",
          500 * panels, 580, 500 * panels, 580); /* 580: room for the legends below */
  fprintf(f, "set output outfile\nset datafile separator ','\nset grid\n"
             "set key below\n" /* legends under the panels, clear of the curves */
             "set format x '%%g'\nset format y '%%g'\nset xtics rotate by 30 right\n");
  /* Time in the unit that fits the run (seconds: ms below 1 s, us below 1 ms): the column
   * $2 times tscale. */
  double tscale = 1.0;
  const char *tunit = o->unit_time;
  if (!strcmp(o->unit_time, "s") && o->col_absmax[1] > 0) {
    if (o->col_absmax[1] < 1e-3)
      tscale = 1e6, tunit = "us";
    else if (o->col_absmax[1] < 1.0)
      tscale = 1e3, tunit = "ms";
  }
  fprintf(f, "tscale = %g\n", tscale);
  /* 2-D: forces are those on the body's thickness (volumes are area x thickness) */
  char rlabel[128];
  if (o->dim == 2 && o->thickness > 0)
    snprintf(rlabel, sizeof rlabel, "reaction [%s] on the thickness %g %s", o->unit_force,
             o->thickness, o->unit_length);
  else if (o->dim == 2)
    snprintf(rlabel, sizeof rlabel, "reaction [%s] on the thickness of the body", o->unit_force);
  else
    snprintf(rlabel, sizeof rlabel, "reaction [%s]", o->unit_force);
  fprintf(f, "if (!exists(\"data\")) data = '%s_history.csv'\n", stem);
  fprintf(f, "set multiplot layout 1,%d title '%s'\n", panels, stem);
  if (o->num_reaction > 0) {
    fprintf(f, "set xlabel 'time [%s]'\nset ylabel '%s'\nplot ", tunit, rlabel);
    for (int k = 0; k < o->num_reaction; ++k) {
      int c = main_component(o, k);
      fprintf(f, "%sdata skip 1 using ($2*tscale):%d with lines title '%s %s'",
              k ? ", \\\n     " : "",
              o->reaction_col[k] + c + 1, o->reaction_name[k], axis_name[c]);
    }
    fprintf(f, "\n");
  }
  if (num_disp > 0) {
    fprintf(f, "set xlabel 'mean displacement of the set [%s]'\nset ylabel '%s'\nplot ",
            o->unit_length, rlabel);
    int first = 1;
    for (int k = 0; k < o->num_reaction; ++k) {
      if (!moved(o, k)) continue;
      int c = main_component(o, k);
      fprintf(f, "%sdata skip 1 using %d:%d with lines title '%s %s'", first ? "" : ", \\\n     ",
              o->disp_col[k] + c + 1, o->reaction_col[k] + c + 1, o->reaction_name[k],
              axis_name[c]);
      first = 0;
    }
    fprintf(f, "\n");
  }
  fprintf(f, "set xlabel 'time [%s]'\nset ylabel 'energy [%s]'\n", tunit, o->unit_energy);
  fprintf(f, "plot data skip 1 using ($2*tscale):3 with lines title 'kinetic', \\\n"
             "     data skip 1 using ($2*tscale):4 with lines title 'strain', \\\n");
  /* Dissipation curves only when the run dissipated: plastic, damage, bond breaking. */
  const char *work_title[3] = {"plastic work", "damage", "bond breaking"};
  int any_work = 0;
  for (int k = 0; k < 3; ++k) {
    if (!(o->col_absmax[o->work_col + k] > 0)) continue;
    fprintf(f, "     data skip 1 using ($2*tscale):%d with lines title '%s', \\\n",
            o->work_col + k + 1,
            work_title[k]);
    any_work = 1;
  }
  if (any_work)
    fprintf(f,
            "     data skip 1 using ($2*tscale):($3+$4+$%d+$%d+$%d) with lines title 'kinetic + "
            "strain + "
            "dissipated', \\\n",
            o->work_col + 1, o->work_col + 2, o->work_col + 3);
  else
    fprintf(f, "     data skip 1 using ($2*tscale):($3+$4) with lines title 'kinetic + strain', "
               "\\\n");
  fprintf(f, "     data skip 1 using ($2*tscale):5 with lines dashtype 2 title 'external work'\n");
  if (damage_panel)
    fprintf(f,
            "set xlabel 'time [%s]'\nset ylabel 'failed particles'\nset y2label 'largest damage'\n"
            "set y2tics\nset ytics nomirror\nset yrange [0:*]\nset y2range [0:*]\n"
            "plot data skip 1 using ($2*tscale):%d with lines title 'failed particles', \\\n"
            "     data skip 1 using ($2*tscale):%d axes x1y2 with lines title 'largest damage'\n",
            tunit, fail_col + 1, dmax_col + 1);
  fprintf(f, "unset multiplot\nset output\n");
  PDK_CHECK_GOTO(fflush(f) == 0 && !ferror(f), ctx, PDK_ERR_IO, "cannot write '%s': %s",
                 o->part[OUT_GP], strerror(errno));
cleanup:
  if (f) fclose(f);
  free(stem);
  return err;
}

/* File name of o->part[f] or o->final[f] without the directory. */
static const char *base_name(const pdk_output *o, const char *path) {
  return path + strlen(o->dir) + 1;
}

/* Runs gnuplot in o->dir on the script o->part[gp], reading the data o->part[data] and writing
 * the PNG o->part[png]: the new files keep their temporary names until every one is complete.
 * No shell is involved: gnuplot gets an argument vector, the script as "./<file>" (a name
 * starting with '-' is not an option) and the two file names as single-quoted gnuplot strings
 * ('' for ', the only character special there; the output name has no control character). When
 * gnuplot fails its stderr goes into the error message and no PNG is left. */
static int run_gnuplot(pdk_output *o, int gp, int png, int data) {
  pdk_ctx *ctx = o->ctx;
  int err = PDK_SUCCESS;
  int pipefd[2] = {-1, -1};
  char msg[1024] = "";
  size_t msg_len = 0;
  char *script = pdk_str_printf("./%s", base_name(o, o->part[gp]));
  char *q_png = gnuplot_quote(base_name(o, o->part[png]));
  char *q_data = gnuplot_quote(base_name(o, o->part[data]));
  char *expr = q_png && q_data ? pdk_str_printf("outfile='%s'; data='%s'", q_png, q_data) : NULL;
  PDK_CHECK_GOTO(script && expr, ctx, PDK_ERR_MEMORY, "out of memory");
  PDK_CHECK_GOTO(pipe(pipefd) == 0, ctx, PDK_ERR_EXTERNAL, "pipe() for gnuplot failed: %s",
                 strerror(errno));
  fflush(NULL);
  pid_t pid = fork();
  PDK_CHECK_GOTO(pid >= 0, ctx, PDK_ERR_EXTERNAL, "fork() for gnuplot failed: %s", strerror(errno));
  if (pid == 0) { /* child: only async-signal-safe calls until exec */
    int devnull = open("/dev/null", O_RDWR);
    if (devnull >= 0) {
      dup2(devnull, 0);
      dup2(devnull, 1);
    }
    dup2(pipefd[1], 2);
    close(pipefd[0]);
    if (chdir(o->dir) != 0) _exit(126);
    execlp("gnuplot", "gnuplot", "-e", expr, script, (char *)NULL);
    _exit(127);
  }
  close(pipefd[1]);
  pipefd[1] = -1;
  for (;;) {
    char buf[512];
    ssize_t got = read(pipefd[0], buf, sizeof buf);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    size_t take = (size_t)got < sizeof msg - 1 - msg_len ? (size_t)got : sizeof msg - 1 - msg_len;
    memcpy(msg + msg_len, buf, take);
    msg_len += take;
  }
  msg[msg_len] = '\0';
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  for (size_t k = 0; k < msg_len; ++k)
    if (msg[k] == '\n') msg[k] = ' ';
  PDK_CHECK_GOTO(WIFEXITED(status) && WEXITSTATUS(status) == 0 && pdk_file_exists(o->part[png]),
                 ctx, PDK_ERR_EXTERNAL,
                 "gnuplot failed on '%s' (%s %d)%s%s; the data files are complete, only the plot "
                 "is missing: rerun 'gnuplot %s%s' in '%s'",
                 o->final[gp], WIFEXITED(status) ? "exit status" : "signal",
                 WIFEXITED(status) ? WEXITSTATUS(status) : WTERMSIG(status), msg_len ? ": " : "",
                 msg, o->name[0] == '-' ? "./" : "", base_name(o, o->final[gp]), o->dir);
cleanup:
  if (err) pdk_file_remove(o->part[png]);
  if (pipefd[0] >= 0) close(pipefd[0]);
  if (pipefd[1] >= 0) close(pipefd[1]);
  free(script);
  free(q_png);
  free(q_data);
  free(expr);
  return err;
}

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

/* ---- field snapshot -----------------------------------------------------------------------------
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

/* Reads rows [r0, r0 + rows) of dataset `path` ([n] or [n][cols]) as doubles into buf. */
static int read_rows(pdk_output *o, const char *path, int cols, hsize_t r0, hsize_t rows,
                     double *buf) {
  const hsize_t start[2] = {r0, 0}, count[2] = {rows, (hsize_t)cols};
  return pdk_h5_read_block(o->ctx, o->file, path, H5T_NATIVE_DOUBLE, cols > 1 ? 2 : 1, start, count,
                           buf);
}

/* <name>_fields.csv: id, X, Y (, Z) and every component of every field of the last field output,
 * read back from the .h5 (still open), one row per particle in store order, 10 significant
 * digits. A vector gives <f>_x, <f>_y (, <f>_z), a tensor <f>_xx, <f>_xy, ... (its dim x dim
 * components), other fields <f>_0, ... In 3-D only one layer is written: the particles whose
 * reference z lies within half their own size (cube root of the volume) of z_s, the reference z of
 * the particle nearest the middle of the body's z extent; on a lattice, the layer nearest the
 * mid-plane. Fills *snap with what the plot draws: the current in-plane positions (x when
 * written, else X + u when u is, else X) and up to SNAP_MAX_PANELS scalar fields and |u|, in the
 * listed order. */
static int write_snapshot_csv(pdk_output *o, out_snapshot *snap) {
  pdk_ctx *ctx = o->ctx;
  int err = PDK_SUCCESS;
  const int nf = o->num_last;
  FILE *f = NULL;
  double **buf = calloc((size_t)nf + 3, sizeof *buf); /* fields, then id, X, volume */
  int *cols = calloc((size_t)nf + 1, sizeof *cols), *ncomp = calloc((size_t)nf + 1, sizeof *ncomp);
  int(*col_of)[9] = calloc((size_t)nf + 1, sizeof *col_of);
  out_layout *layout = calloc((size_t)nf + 1, sizeof *layout);
  char path[2 * OUT_NAME_MAX + 32];
  double *row = NULL;
  static const char *const tsuf[9] = {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"};
  const int dim = o->dim, c_fields = 2 + dim; /* first field column (1-based) */
  PDK_CHECK_GOTO(buf && cols && ncomp && col_of && layout, ctx, PDK_ERR_MEMORY, "out of memory");
  const pdk_index block = o->n < OUT_CHUNK_ROWS ? o->n : OUT_CHUNK_ROWS;
  for (int k = 0; k < nf + 3; ++k) {
    buf[k] = malloc((size_t)block * 9 * sizeof(double));
    PDK_CHECK_GOTO(buf[k], ctx, PDK_ERR_MEMORY, "out of memory for the field snapshot");
  }
  f = fopen(o->part[OUT_FCSV], "w");
  PDK_CHECK_GOTO(f, ctx, PDK_ERR_IO, "cannot create '%s': %s", o->part[OUT_FCSV], strerror(errno));

  memset(snap, 0, sizeof *snap);
  snap->slice_z = NAN;
  if (dim == 3) { /* the layer: z_s nearest the middle of the reference z extent */
    double zlo = INFINITY, zhi = -INFINITY, best = INFINITY;
    for (int pass = 0; pass < 2; ++pass)
      for (pdk_index r0 = 0; r0 < o->n; r0 += block) {
        const pdk_index rows = o->n - r0 < block ? o->n - r0 : block;
        PDK_CALL_GOTO(read_rows(o, "/static/X", 3, (hsize_t)r0, (hsize_t)rows, buf[nf + 1]));
        for (pdk_index i = 0; i < rows; ++i) {
          const double z = buf[nf + 1][3 * i + 2];
          if (pass == 0) {
            zlo = fmin(zlo, z);
            zhi = fmax(zhi, z);
          } else if (fabs(z - 0.5 * (zlo + zhi)) < best) {
            best = fabs(z - 0.5 * (zlo + zhi));
            snap->slice_z = z;
          }
        }
      }
  }

  /* header; column numbers (1-based) for the plot */
  fprintf(f, "id,X [%s],Y [%s]", o->unit_length, o->unit_length);
  if (dim == 3) fprintf(f, ",Z [%s]", o->unit_length);
  int col = c_fields, x_col = 0, u_col = 0, failed_col = 0;
  for (int k = 0; k < nf; ++k) {
    pdk_type type;
    PDK_CALL_GOTO(pdk_particles_field_info(o->p, o->last_field[k], &type, &ncomp[k]));
    layout[k] = field_layout(dim, ncomp[k], &cols[k], col_of[k]);
    const char *dn = o->last_dname[k];
    if (layout[k] == OUT_VECTOR && !strcmp(o->last_field[k], "x")) x_col = col;
    if (layout[k] == OUT_VECTOR && !strcmp(o->last_field[k], "u")) u_col = col;
    if (layout[k] == OUT_SCALAR && !strcmp(o->last_field[k], "failed")) failed_col = col;
    if ((layout[k] == OUT_SCALAR || (layout[k] == OUT_VECTOR && !strcmp(o->last_field[k], "u"))) &&
        snap->num_panels < SNAP_MAX_PANELS) {
      const int q = snap->num_panels++;
      snap->col[q] = col;
      snap->norm[q] = layout[k] == OUT_VECTOR ? dim : 0;
      snprintf(snap->title[q], sizeof snap->title[q], snap->norm[q] ? "|%s|" : "%s", dn);
      char ubuf[64];
      const char *unit = field_unit(o, o->last_field[k], ubuf, sizeof ubuf);
      snprintf(snap->unit[q], sizeof snap->unit[q], "%s", unit ? unit : "");
    }
    for (int c = 0; c < ncomp[k]; ++c, ++col) {
      if (layout[k] == OUT_SCALAR)
        fprintf(f, ",%s", dn);
      else if (layout[k] == OUT_VECTOR)
        fprintf(f, ",%s_%s", dn, axis_name[c]);
      else if (layout[k] == OUT_TENSOR)
        fprintf(f, ",%s_%s", dn, tsuf[col_of[k][c]]);
      else
        fprintf(f, ",%s_%d", dn, c);
    }
  }
  fprintf(f, "\n");
  const int num_cols = col - 1;
  snap->failed_col = failed_col;
  row = malloc((size_t)(num_cols + 1) * sizeof *row); /* row[c]: CSV column c (1-based) */
  PDK_CHECK_GOTO(row, ctx, PDK_ERR_MEMORY, "out of memory");
  for (int c = 0; c < 2; ++c) {
    snap->pos_col[c] = x_col ? x_col + c : 2 + c;
    snap->pos_add[c] = !x_col && u_col ? u_col + c : 0;
    snap->lo[c] = snap->ref_lo[c] = INFINITY;
    snap->hi[c] = snap->ref_hi[c] = -INFINITY;
  }
  for (int q = 0; q < snap->num_panels; ++q) {
    snap->vlo[q] = INFINITY;
    snap->vhi[q] = -INFINITY;
  }

  for (pdk_index r0 = 0; r0 < o->n; r0 += block) {
    const pdk_index rows = o->n - r0 < block ? o->n - r0 : block;
    PDK_CALL_GOTO(read_rows(o, "/static/id", 1, (hsize_t)r0, (hsize_t)rows, buf[nf]));
    PDK_CALL_GOTO(read_rows(o, "/static/X", 3, (hsize_t)r0, (hsize_t)rows, buf[nf + 1]));
    if (dim == 3)
      PDK_CALL_GOTO(read_rows(o, "/static/volume", 1, (hsize_t)r0, (hsize_t)rows, buf[nf + 2]));
    for (int k = 0; k < nf; ++k) {
      snprintf(path, sizeof path, OUT_STEP_GROUP "/%s", (long)o->num_steps - 1, o->last_dname[k]);
      PDK_CALL_GOTO(read_rows(o, path, cols[k], (hsize_t)r0, (hsize_t)rows, buf[k]));
    }
    for (pdk_index i = 0; i < rows; ++i) {
      if (dim == 3 && !(fabs(buf[nf + 1][3 * i + 2] - snap->slice_z) <= 0.5 * cbrt(buf[nf + 2][i])))
        continue;
      snap->num_rows++;
      row[1] = buf[nf][i];
      for (int c = 0; c < dim; ++c)
        row[2 + c] = buf[nf + 1][3 * i + c];
      for (int k = 0, c0 = c_fields; k < nf; c0 += ncomp[k], ++k)
        for (int c = 0; c < ncomp[k]; ++c)
          row[c0 + c] = buf[k][(size_t)i * cols[k] + col_of[k][c]];
      fprintf(f, "%.0f", row[1]);
      for (int c = 2; c <= num_cols; ++c)
        fprintf(f, ",%.10g", row[c]);
      fprintf(f, "\n");
      for (int c = 0; c < 2; ++c) {
        snap->ref_lo[c] = fmin(snap->ref_lo[c], row[2 + c]);
        snap->ref_hi[c] = fmax(snap->ref_hi[c], row[2 + c]);
      }
      if (failed_col && row[failed_col] != 0.0) continue;
      snap->num_shown++;
      for (int c = 0; c < 2; ++c) {
        const double x = row[snap->pos_col[c]] + (snap->pos_add[c] ? row[snap->pos_add[c]] : 0.0);
        snap->lo[c] = fmin(snap->lo[c], x);
        snap->hi[c] = fmax(snap->hi[c], x);
      }
      for (int q = 0; q < snap->num_panels; ++q) {
        const int c = snap->col[q];
        double v = row[c];
        if (snap->norm[q]) {
          v = 0.0;
          for (int a = 0; a < snap->norm[q]; ++a)
            v += row[c + a] * row[c + a];
          v = sqrt(v);
        }
        snap->vlo[q] = fmin(snap->vlo[q], v);
        snap->vhi[q] = fmax(snap->vhi[q], v);
      }
    }
  }
  PDK_CHECK_GOTO(fflush(f) == 0 && !ferror(f), ctx, PDK_ERR_IO, "cannot write '%s': %s",
                 o->part[OUT_FCSV], strerror(errno));
cleanup:
  if (f && fclose(f) != 0 && !err)
    err = pdk_ctx_error_set(ctx, PDK_ERR_IO, __func__, "cannot write '%s': %s", o->part[OUT_FCSV],
                            strerror(errno));
  if (buf)
    for (int k = 0; k < nf + 3; ++k)
      free(buf[k]);
  free(buf);
  free(cols);
  free(ncomp);
  free(col_of);
  free(layout);
  free(row);
  return err;
}

/* <name>_fields.gp: one panel per plotted field, the particles as dots coloured by the value, in
 * the positions of the snapshot, equal axes. */
static int write_snapshot_script(pdk_output *o, const out_snapshot *snap) {
  pdk_ctx *ctx = o->ctx;
  int err = PDK_SUCCESS;
  char *stem = gnuplot_quote(o->name), *title = NULL;
  FILE *f = NULL;
  PDK_CHECK_GOTO(stem, ctx, PDK_ERR_MEMORY, "out of memory");
  f = fopen(o->part[OUT_FGP], "w");
  PDK_CHECK_GOTO(f, ctx, PDK_ERR_IO, "cannot create '%s': %s", o->part[OUT_FGP], strerror(errno));
  /* Panel size from the body's aspect; the dot size from the mean spacing in pixels. */
  /* (every particle failed: no box, the view and the scales are gnuplot's automatic ones) */
  const int have_box = snap->num_shown > 0;
  double bw = have_box ? snap->hi[0] - snap->lo[0] : 1.0,
         bh = have_box ? snap->hi[1] - snap->lo[1] : 1.0;
  if (!(bw > 0)) bw = bh > 0 ? bh : 1.0;
  if (!(bh > 0)) bh = bw;
  /* Side by side, or stacked when the body is wide (a bar): pixels per panel */
  const int wide = bw > 1.5 * bh, np = snap->num_panels;
  const int pw = wide ? 900 : 440;
  int ph = (int)((wide ? 0.7 : 0.78) * pw * bh / bw) + 110;
  ph = ph < (wide ? 260 : 300) ? (wide ? 260 : 300) : ph > 1000 ? 1000 : ph;
  char slice[96] = "";
  if (!isnan(snap->slice_z))
    snprintf(slice, sizeof slice, ", layer Z = %.6g [%s]", snap->slice_z, o->unit_length);
  title = pdk_str_printf("%s, step %ld, t = %.6g [%s]%s%s", stem, o->last_step, o->last_time,
                         o->unit_time, slice,
                         snap->pos_col[0] != 2 || snap->pos_add[0] ? ", current positions" : "");
  PDK_CHECK_GOTO(title, ctx, PDK_ERR_MEMORY, "out of memory");
  int width = wide ? pw : pw * np; /* at least the title's width, about 8 pixels a character */
  if (width < 8 * (int)strlen(title) + 60) width = 8 * (int)strlen(title) + 60;
  const int height = wide ? ph * np : ph;
  const double scale = fmin((wide ? 0.7 : 0.62) * pw / bw, (ph - 110.0) / bh); /* px per length */
  const double h = sqrt(bw * bh / (double)(snap->num_rows > 0 ? snap->num_rows : 1));
  double ps = 1.6 * scale * h / 6.0; /* pt 7 at pointsize 1 is about 6 pixels across */
  ps = ps < 0.05 ? 0.05 : ps > 3.0 ? 3.0 : ps;
  fprintf(f,
          "# pdk field plot of the last field output (step %ld, t = %.6g); rerun with: gnuplot "
          "%s%s_fields.gp (in this directory)\n",
          o->last_step, o->last_time, o->name[0] == '-' ? "./" : "", o->name);
  fprintf(f, "if (!exists(\"outfile\")) outfile = '%s_fields.png'\n", stem);
  fprintf(f,
          "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
          "  set terminal pngcairo size %d,%d noenhanced\n} else {\n"
          "  set terminal png size %d,%d noenhanced\n}\n",
          width, height, width, height);
  fprintf(f,
          "set output outfile\nset datafile separator ','\nunset key\nset size ratio -1\n"
          "set format x '%%g'\nset format y '%%g'\nset format cb '%%g'\n"
          "set xtics rotate by 30 right\nset xlabel '[%s]'\n",
          o->unit_length);
  fprintf(f, "set palette defined (0 '#440154', 1 '#3b528b', 2 '#21918c', 3 '#5ec962', "
             "4 '#fde725')\n");
  fprintf(f, "if (!exists(\"data\")) data = '%s_fields.csv'\ntitle = '%s'\n", stem, title);
  char view[256] = "set autoscale xy\n";
  if (have_box) {
    const double m = 0.03 * fmax(bw, bh);
    snprintf(view, sizeof view, "set xrange [%.10g:%.10g]\nset yrange [%.10g:%.10g]\n",
             snap->lo[0] - m, snap->lo[0] + bw + m, snap->lo[1] - m, snap->lo[1] + bh + m);
    fputs(view, f);
  }
  fprintf(f, "set multiplot layout %d,%d title title\n", wide ? np : 1, wide ? 1 : np);
  char xs[64], ys[64], xs_unfailed[96];
  for (int c = 0; c < 2; ++c) {
    char *dst = c ? ys : xs;
    if (snap->pos_add[c])
      snprintf(dst, 64, "($%d+$%d)", snap->pos_col[c], snap->pos_add[c]);
    else
      snprintf(dst, 64, "($%d)", snap->pos_col[c]);
  }
  /* a failed particle's x undefined: gnuplot skips the point (a NaN colour would be drawn) */
  snprintf(xs_unfailed, sizeof xs_unfailed, "($%d != 0 ? NaN : %s)", snap->failed_col, xs);
  for (int q = 0; q < snap->num_panels; ++q) {
    char *pt = gnuplot_quote(snap->title[q]);
    PDK_CHECK_GOTO(pt, ctx, PDK_ERR_MEMORY, "out of memory");
    const int fc = snap->failed_col;
    if (fc && snap->col[q] == fc) {
      /* where the body broke: every particle at its reference position, the failed ones (1)
       * drawn over the others (0), in the view of the reference positions */
      fprintf(f, "set title '%s, reference positions'\n", pt);
      free(pt);
      const double rw = snap->ref_hi[0] - snap->ref_lo[0], rh = snap->ref_hi[1] - snap->ref_lo[1];
      if (snap->num_rows > 0) {
        const double m = 0.03 * fmax(rw, rh) + (rw > 0 || rh > 0 ? 0.0 : 1.0);
        fprintf(f, "set xrange [%.10g:%.10g]\nset yrange [%.10g:%.10g]\n", snap->ref_lo[0] - m,
                snap->ref_hi[0] + m, snap->ref_lo[1] - m, snap->ref_hi[1] + m);
      }
      fprintf(f,
              "set cbrange [0:1]\nplot data skip 1 using ($%d != 0 ? NaN : $2):($3):(0) with "
              "points pt 7 ps %.3g lc palette, data skip 1 using ($%d == 0 ? NaN : $2):($3):(1) "
              "with points pt 7 ps %.3g lc palette\n%s",
              fc, ps, fc, ps, view);
      continue;
    }
    /* the panel's title carries the colour scale's unit ("1": dimensionless, none) */
    if (snap->unit[q][0] && strcmp(snap->unit[q], "1")) {
      char *u = gnuplot_quote(snap->unit[q]);
      PDK_CHECK_GOTO(u, ctx, PDK_ERR_MEMORY, "out of memory");
      fprintf(f, "set title '%s [%s]'\n", pt, u);
      free(u);
    } else {
      fprintf(f, "set title '%s'\n", pt);
    }
    free(pt);
    if (have_box && snap->vhi[q] > snap->vlo[q])
      fprintf(f, "set cbrange [%.10g:%.10g]\n", snap->vlo[q], snap->vhi[q]);
    else
      fprintf(f, "set autoscale cb\n");
    char v[96];
    if (snap->norm[q] == 3)
      snprintf(v, sizeof v, "(sqrt($%d**2+$%d**2+$%d**2))", snap->col[q], snap->col[q] + 1,
               snap->col[q] + 2);
    else if (snap->norm[q])
      snprintf(v, sizeof v, "(sqrt($%d**2+$%d**2))", snap->col[q], snap->col[q] + 1);
    else
      snprintf(v, sizeof v, "($%d)", snap->col[q]);
    /* (the failed panel took the branch above: every other panel leaves failed particles out) */
    fprintf(f, "plot data skip 1 using %s:%s:%s with points pt 7 ps %.3g lc palette\n",
            fc ? xs_unfailed : xs, ys, v, ps);
  }
  fprintf(f, "unset multiplot\nset output\n");
  PDK_CHECK_GOTO(fflush(f) == 0 && !ferror(f), ctx, PDK_ERR_IO, "cannot write '%s': %s",
                 o->part[OUT_FGP], strerror(errno));
cleanup:
  if (f) fclose(f);
  free(stem);
  free(title);
  return err;
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
    PDK_CALL(xmf_grid_open(o, 0, 0.0, "/static/X", NULL, 0));
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
  if (snapshot) PDK_CALL(write_snapshot_csv(o, &snap));
  hid_t file = o->file;
  o->file = -1;
  PDK_CALL(pdk_h5_file_close(ctx, file, o->part[OUT_H5]));
  made[OUT_H5] = made[OUT_XMF] = made[OUT_CSV] = 1;
  made[OUT_FCSV] = snapshot;

  int plot_err = PDK_SUCCESS;
  if (o->will_plot && o->rows > 0) {
    PDK_CALL(write_plot_script(o));
    made[OUT_GP] = 1;
    plot_err = run_gnuplot(o, OUT_GP, OUT_PNG, OUT_CSV);
    made[OUT_PNG] = !plot_err;
  }
  if (snap.num_panels > 0 && o->will_plot && !plot_err) {
    PDK_CALL(write_snapshot_script(o, &snap));
    made[OUT_FGP] = 1;
    plot_err = run_gnuplot(o, OUT_FGP, OUT_FPNG, OUT_FCSV);
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
