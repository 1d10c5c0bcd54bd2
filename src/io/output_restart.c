/* Run output, appending (pdk_output_open with opts.append): the earlier run's records up to the
 * checkpoint copied into the new files (src/io/output.c, src/io/output_impl.h).
 */
#include <errno.h>
#include <math.h>
#include <string.h>

#include "output_impl.h"
#include "pdk/ctx.h"
#include "pdk/output.h"
#include "pdk/particles.h"

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

const char pdk_out_xmf_header[] =
    "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
    "<Xdmf Version=\"2.0\">\n  <Domain>\n"
    "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
static const char xmf_footer[] = "    </Grid>\n  </Domain>\n</Xdmf>\n"; /* as finish() writes it */
static const char xmf_grid_start[] = "    <Grid Name=\"step_";
static const char xmf_grid_end[] = "\n    </Grid>\n";

/* The CSV's header line (with its newline), malloc'd. */
char *pdk_out_csv_header(const pdk_output *o) {
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
int pdk_out_append_earlier(pdk_output *o, long upto, const char *scene) {
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
  hdr = pdk_out_csv_header(o);
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
  if (strncmp(xmf, pdk_out_xmf_header, strlen(pdk_out_xmf_header)))
    EARLIER_MISFIT(o, "'%s' does not start as a pdk XDMF index", o->final[OUT_XMF]);
  grid = malloc(((size_t)num_groups + 2) * sizeof *grid);
  PDK_CHECK_GOTO(grid, ctx, PDK_ERR_MEMORY, "out of memory");
  long num_grids = 0;
  q = xmf + strlen(pdk_out_xmf_header);
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
  PDK_CALL_GOTO(pdk_out_flush_files(o));
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
