/* Point clouds from CSV files (src/space/points.h). */
#define _POSIX_C_SOURCE 200809L /* getline, strndup */
#include "points.h"

#include "core/h5io.h"
#include "pdk/ctx.h"
#include "pdk/particles.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <string.h>

enum { COL_X = 0, COL_Y, COL_Z, COL_VOLUME, COL_AREA, COL_SET, COL_MATERIAL, COL_NUM_KINDS };

void pdk_points_free(pdk_points *pts) {
  if (!pts) return;
  for (int a = 0; a < 3; ++a)
    free(pts->X[a]);
  free(pts->volume);
  for (int k = 0; k < pts->num_sets; ++k) {
    free(pts->set_name[k]);
    free(pts->set[k]);
  }
  free(pts->material);
  free(pts->path);
  for (int k = 0; k < pts->num_mkeys; ++k)
    free(pts->mkey[k].name);
  free(pts->mkey);
  memset(pts, 0, sizeof *pts);
}

static int grow(pdk_points *p, pdk_index cap) {
  for (int a = 0; a < p->dim; ++a) {
    double *x = realloc(p->X[a], (size_t)cap * sizeof(double));
    if (!x) return 1;
    p->X[a] = x;
  }
  double *v = realloc(p->volume, (size_t)cap * sizeof(double));
  if (!v) return 1;
  p->volume = v;
  for (int k = 0; k < p->num_sets; ++k) {
    uint8_t *s = realloc(p->set[k], (size_t)cap);
    if (!s) return 1;
    p->set[k] = s;
  }
  if (p->mkey) {
    int32_t *m = realloc(p->material, (size_t)cap * sizeof(int32_t));
    if (!m) return 1;
    p->material = m;
  }
  return 0;
}

/* The key of a material cell (name, or index when name is NULL) first seen at line/row: its
 * number in p->mkey, added when new; -1 when there are too many distinct values or no memory. */
int pdk_points_mkey_find(pdk_points *p, const char *name, size_t len, long index, long line,
                         long row) {
  for (int k = 0; k < p->num_mkeys; ++k) {
    const pdk_points_mkey *m = &p->mkey[k];
    if (name ? m->name && strlen(m->name) == len && !strncmp(m->name, name, len)
             : !m->name && m->index == index)
      return k;
  }
  if (p->num_mkeys >= PDK_POINTS_MAX_MKEYS) return -1;
  pdk_points_mkey *m = &p->mkey[p->num_mkeys];
  m->name = NULL;
  if (name && !(m->name = strndup(name, len))) return -1;
  m->index = index;
  m->line = line;
  m->row = row;
  return p->num_mkeys++;
}

/* The next comma-separated cell of *q (blanks around it trimmed) into [*b, *e). */
static void next_cell(char **q, char **b, char **e) {
  char *s = *q;
  while (*s == ' ' || *s == '\t')
    ++s;
  char *t = s;
  while (*t && *t != ',' && *t != '\n' && *t != '\r')
    ++t;
  *q = *t == ',' ? t + 1 : t;
  while (t > s && (t[-1] == ' ' || t[-1] == '\t'))
    --t;
  *b = s;
  *e = t;
}

static int blank_or_comment(const char *line) {
  while (*line == ' ' || *line == '\t')
    ++line;
  return *line == '\0' || *line == '\n' || *line == '\r' || *line == '#';
}

int pdk_points_read_csv(pdk_ctx *ctx, const char *path, int dim, double thickness,
                        pdk_points *out) {
  int err = PDK_SUCCESS;
  memset(out, 0, sizeof *out);
  out->dim = dim;
  FILE *f = fopen(path, "r");
  PDK_CHECK(f, ctx, PDK_ERR_IO, "cannot open the point cloud '%s': %s", path, strerror(errno));
  char *line = NULL;
  size_t cap_line = 0;
  long lineno = 0;
  int kind[3 + 2 + PDK_POINTS_MAX_SETS], num_cols = 0, seen[COL_NUM_KINDS] = {0};
  pdk_index cap = 0;
  /* the header */
  for (;;) {
    ssize_t len = getline(&line, &cap_line, f);
    PDK_CHECK_GOTO(len >= 0, ctx, PDK_ERR_ARG,
                   "%s: the file has no header line; the first line names the columns: x, y%s, "
                   "volume%s, and set:<name> for each set",
                   path, dim == 3 ? ", z" : "", dim == 2 ? " (or area)" : "");
    ++lineno;
    if (!blank_or_comment(line)) break;
  }
  for (char *q = line; *q && *q != '\n' && *q != '\r';) {
    char *b, *e;
    next_cell(&q, &b, &e);
    const int w = (int)(e - b);
    PDK_CHECK_GOTO(num_cols < 3 + 3 + PDK_POINTS_MAX_SETS, ctx, PDK_ERR_ARG,
                   "%s:%ld: more than %d columns; a cloud holds at most %d sets", path, lineno,
                   3 + 3 + PDK_POINTS_MAX_SETS, PDK_POINTS_MAX_SETS);
    int k = -1;
    if (w == 1 && (*b == 'x' || *b == 'y' || (*b == 'z' && dim == 3)))
      k = *b == 'x' ? COL_X : *b == 'y' ? COL_Y : COL_Z;
    else if (w == 6 && !strncmp(b, "volume", 6))
      k = COL_VOLUME;
    else if (w == 4 && !strncmp(b, "area", 4) && dim == 2)
      k = COL_AREA;
    else if (w == 8 && !strncmp(b, "material", 8)) {
      k = COL_MATERIAL;
      if (!out->mkey) out->mkey = calloc(PDK_POINTS_MAX_MKEYS, sizeof *out->mkey);
      PDK_CHECK_GOTO(out->mkey, ctx, PDK_ERR_MEMORY, "out of memory");
    }
    else if (w > 4 && !strncmp(b, "set:", 4)) {
      k = COL_SET;
      for (const char *c = b + 4; c < e; ++c)
        PDK_CHECK_GOTO(isalnum((unsigned char)*c) || *c == '_' || *c == '-', ctx, PDK_ERR_ARG,
                       "%s:%ld: column '%.*s': a set name holds letters, digits, _ and - only",
                       path, lineno, w, b);
      for (int j = 0; j < out->num_sets; ++j)
        PDK_CHECK_GOTO(strlen(out->set_name[j]) != (size_t)(w - 4) ||
                           strncmp(out->set_name[j], b + 4, (size_t)(w - 4)),
                       ctx, PDK_ERR_ARG, "%s:%ld: column '%.*s' is named twice", path, lineno, w, b);
      out->set_name[out->num_sets] = strndup(b + 4, (size_t)(w - 4));
      PDK_CHECK_GOTO(out->set_name[out->num_sets], ctx, PDK_ERR_MEMORY, "out of memory");
      out->num_sets++;
    }
    PDK_CHECK_GOTO(k >= 0, ctx, PDK_ERR_ARG,
                   "%s:%ld: unknown column '%.*s'; the columns of a %d-D cloud are x, y%s, %s, "
                   "set:<name> and material",
                   path, lineno, w, b, dim, dim == 3 ? ", z" : "",
                   dim == 2 ? "volume or area" : "volume");
    PDK_CHECK_GOTO(k == COL_SET || !seen[k], ctx, PDK_ERR_ARG, "%s:%ld: column '%.*s' is named twice",
                   path, lineno, w, b);
    seen[k] = 1;
    kind[num_cols++] = k;
  }
  PDK_CHECK_GOTO(seen[COL_X] && seen[COL_Y] && (dim == 2 || seen[COL_Z]), ctx, PDK_ERR_ARG,
                 "%s:%ld: the header must name the columns x, y%s (the reference positions)", path,
                 lineno, dim == 3 ? ", z" : "");
  PDK_CHECK_GOTO(seen[COL_VOLUME] + seen[COL_AREA] == 1, ctx, PDK_ERR_ARG,
                 "%s:%ld: the header must name %s", path, lineno,
                 dim == 2 ? "one of volume (area x thickness) and area" : "the column volume");
  for (int a = 0; a < 3; ++a)
    out->lo[a] = INFINITY, out->hi[a] = -INFINITY;
  if (dim == 2) out->lo[2] = out->hi[2] = 0.0;

  /* the rows */
  const long header_line = lineno;
  for (;;) {
    ssize_t len = getline(&line, &cap_line, f);
    if (len < 0) break;
    ++lineno;
    if (blank_or_comment(line)) continue;
    if (out->n == cap) {
      cap = cap ? 2 * cap : 4096;
      PDK_CHECK_GOTO(cap <= INT32_MAX && !grow(out, cap), ctx, PDK_ERR_MEMORY,
                     "%s:%ld: out of memory for %ld particles", path, lineno, (long)cap);
    }
    const pdk_index i = out->n;
    char *q = line;
    int set = 0;
    for (int c = 0; c < num_cols; ++c) {
      char *b, *e;
      PDK_CHECK_GOTO(*q && *q != '\n' && *q != '\r', ctx, PDK_ERR_ARG,
                     "%s:%ld: %d values, the header (line %ld) names %d columns", path, lineno, c,
                     header_line, num_cols);
      next_cell(&q, &b, &e);
      if (kind[c] == COL_MATERIAL) {
        const int w = (int)(e - b);
        int digits = w > 0, name_ok = w > 0 && w <= 255;
        for (const char *t = b; t < e; ++t) {
          digits &= isdigit((unsigned char)*t) != 0;
          name_ok &= isalnum((unsigned char)*t) || *t == '_' || *t == '-' || *t == '.';
        }
        PDK_CHECK_GOTO(name_ok, ctx, PDK_ERR_ARG,
                       "%s:%ld: the material is '%.*s'; give a material's name (as in the "
                       "scene's materials list: letters, digits, _ - .) or its index (0 for "
                       "`material`, k for materials entry k - 1)",
                       path, lineno, w, b);
        const long index = digits && w <= 6 ? strtol(b, NULL, 10) : -1;
        PDK_CHECK_GOTO(!digits || index >= 0, ctx, PDK_ERR_ARG,
                       "%s:%ld: the material index %.*s is too large; a scene has at most 256 "
                       "materials",
                       path, lineno, w, b);
        const int key = pdk_points_mkey_find(out, digits ? NULL : b, (size_t)w, index, lineno, i);
        PDK_CHECK_GOTO(key >= 0, ctx, PDK_ERR_ARG,
                       "%s:%ld: more than %d different materials in the column material", path,
                       lineno, PDK_POINTS_MAX_MKEYS);
        out->material[i] = key;
        continue;
      }
      char *end = NULL;
      const char save = *e;
      *e = '\0';
      const double v = strtod(b, &end);
      const int ok = end == e && e > b;
      *e = save;
      PDK_CHECK_GOTO(ok && isfinite(v), ctx, PDK_ERR_ARG,
                     "%s:%ld: column %d is '%.*s', not a finite number", path, lineno, c + 1,
                     (int)(e - b), b);
      switch (kind[c]) {
      case COL_X:
      case COL_Y:
      case COL_Z: {
        const int a = kind[c] - COL_X;
        out->X[a][i] = v;
        out->lo[a] = fmin(out->lo[a], v);
        out->hi[a] = fmax(out->hi[a], v);
        break;
      }
      case COL_VOLUME:
      case COL_AREA:
        PDK_CHECK_GOTO(v > 0, ctx, PDK_ERR_ARG, "%s:%ld: the %s is %g; it must be > 0", path,
                       lineno, kind[c] == COL_AREA ? "area" : "volume", v);
        out->volume[i] = kind[c] == COL_AREA ? v * thickness : v;
        break;
      default:
        PDK_CHECK_GOTO(v == 0.0 || v == 1.0, ctx, PDK_ERR_ARG,
                       "%s:%ld: set:%s is %g; a set column holds 0 or 1", path, lineno,
                       out->set_name[set], v);
        out->set[set++][i] = (uint8_t)v;
      }
    }
    PDK_CHECK_GOTO(!*q || *q == '\n' || *q == '\r', ctx, PDK_ERR_ARG,
                   "%s:%ld: more values than the %d columns the header (line %ld) names", path,
                   lineno, num_cols, header_line);
    out->n++;
  }
  PDK_CHECK_GOTO(!ferror(f), ctx, PDK_ERR_IO, "cannot read '%s': %s", path, strerror(errno));
  PDK_CHECK_GOTO(out->n > 0, ctx, PDK_ERR_ARG, "%s: no particle after the header (line %ld)", path,
                 header_line);
cleanup:
  free(line);
  fclose(f);
  if (err) pdk_points_free(out);
  return err;
}

/* ---- HDF5 ------------------------------------------------------------------------------------ */

/* The dims of dataset `name` under g (rank <= 2), or -1 when it is not there. */
static int dset_dims(hid_t g, const char *name, hsize_t dims[2]) {
  if (H5Lexists(g, name, H5P_DEFAULT) <= 0) return -1;
  hid_t d = H5Dopen2(g, name, H5P_DEFAULT);
  if (d < 0) return -1;
  hid_t sp = H5Dget_space(d);
  int rank = sp >= 0 ? H5Sget_simple_extent_ndims(sp) : -1;
  dims[0] = dims[1] = 1;
  if (rank >= 1 && rank <= 2)
    H5Sget_simple_extent_dims(sp, dims, NULL);
  else
    rank = -2;
  if (sp >= 0) H5Sclose(sp);
  H5Dclose(d);
  return rank;
}

int pdk_points_read_h5(pdk_ctx *ctx, const char *path, int dim, pdk_points *out) {
  int err = PDK_SUCCESS;
  memset(out, 0, sizeof *out);
  out->dim = dim;
  hid_t f = -1, g = -1, gs = -1;
  double *xyz = NULL;
  f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  PDK_CHECK(f >= 0, ctx, PDK_ERR_IO, "cannot open the point cloud '%s' as an HDF5 file", path);
  /* X and volume at the root, or under /static (a pdk output file: its reference positions) */
  hsize_t dx[2], dv[2];
  const char *where = "/";
  g = H5Gopen2(f, "/", H5P_DEFAULT);
  if (dset_dims(g, "X", dx) < 0 && H5Lexists(f, "static", H5P_DEFAULT) > 0) {
    H5Gclose(g);
    g = H5Gopen2(f, "static", H5P_DEFAULT);
    where = "/static/";
  }
  const int rx = dset_dims(g, "X", dx), rv = dset_dims(g, "volume", dv);
  PDK_CHECK_GOTO(rx == 2 && (dx[1] == (hsize_t)dim || dx[1] == 3) && dx[0] >= 1, ctx, PDK_ERR_ARG,
                 "%s: needs a dataset X of shape [n][%d] (or [n][3]) with the reference positions, "
                 "at the root or under /static (a pdk output file)",
                 path, dim);
  PDK_CHECK_GOTO(rv == 1 && dv[0] == dx[0], ctx, PDK_ERR_ARG,
                 "%s: needs a dataset %svolume of shape [%llu] beside %sX (the particle volumes)",
                 path, where, (unsigned long long)dx[0], where);
  PDK_CHECK_GOTO(dx[0] <= INT32_MAX, ctx, PDK_ERR_ARG, "%s: %llu particles is more than pdk holds",
                 path, (unsigned long long)dx[0]);
  const pdk_index n = (pdk_index)dx[0];
  const int cols = (int)dx[1];
  out->n = n;
  xyz = malloc((size_t)n * (size_t)cols * sizeof(double));
  PDK_CHECK_GOTO(xyz && !grow(out, n), ctx, PDK_ERR_MEMORY, "out of memory for %ld particles",
                 (long)n);
  {
    const hsize_t start[2] = {0, 0}, count[2] = {dx[0], dx[1]};
    PDK_CALL_GOTO(pdk_h5_read_block(ctx, g, "X", H5T_NATIVE_DOUBLE, 2, start, count, xyz));
    PDK_CALL_GOTO(
        pdk_h5_read_block(ctx, g, "volume", H5T_NATIVE_DOUBLE, 1, start, count, out->volume));
  }
  for (int a = 0; a < 3; ++a)
    out->lo[a] = INFINITY, out->hi[a] = -INFINITY;
  if (dim == 2) out->lo[2] = out->hi[2] = 0.0;
  for (pdk_index i = 0; i < n; ++i) {
    for (int a = 0; a < dim; ++a) {
      const double v = xyz[(size_t)i * (size_t)cols + (size_t)a];
      PDK_CHECK_GOTO(isfinite(v), ctx, PDK_ERR_ARG, "%s: %sX[%ld][%d] is %g, not finite", path,
                     where, (long)i, a, v);
      out->X[a][i] = v;
      out->lo[a] = fmin(out->lo[a], v);
      out->hi[a] = fmax(out->hi[a], v);
    }
    PDK_CHECK_GOTO(out->volume[i] > 0 && isfinite(out->volume[i]), ctx, PDK_ERR_ARG,
                   "%s: %svolume[%ld] is %g; volumes must be > 0", path, where, (long)i,
                   out->volume[i]);
  }
  /* sets: every dataset of shape [n] in the group sets, 0 or 1 */
  if (H5Lexists(g, "sets", H5P_DEFAULT) > 0) {
    gs = H5Gopen2(g, "sets", H5P_DEFAULT);
    H5G_info_t info;
    PDK_CHECK_GOTO(gs >= 0 && H5Gget_info(gs, &info) >= 0, ctx, PDK_ERR_ARG,
                   "%s: cannot read the group %ssets", path, where);
    for (hsize_t k = 0; k < info.nlinks; ++k) {
      char name[PDK_FIELD_NAME_MAX];
      H5Lget_name_by_idx(gs, ".", H5_INDEX_NAME, H5_ITER_INC, k, name, sizeof name, H5P_DEFAULT);
      hsize_t ds[2];
      PDK_CHECK_GOTO(dset_dims(gs, name, ds) == 1 && ds[0] == dx[0], ctx, PDK_ERR_ARG,
                     "%s: %ssets/%s is not a dataset of %ld values (0 or 1 per particle)", path,
                     where, name, (long)n);
      PDK_CHECK_GOTO(out->num_sets < PDK_POINTS_MAX_SETS, ctx, PDK_ERR_ARG,
                     "%s: more than %d sets", path, PDK_POINTS_MAX_SETS);
      const int s = out->num_sets;
      out->set_name[s] = strdup(name);
      out->set[s] = malloc((size_t)n);
      out->num_sets++;
      PDK_CHECK_GOTO(out->set_name[s] && out->set[s], ctx, PDK_ERR_MEMORY, "out of memory");
      const hsize_t start[1] = {0}, count[1] = {dx[0]};
      PDK_CALL_GOTO(pdk_h5_read_block(ctx, gs, name, H5T_NATIVE_UINT8, 1, start, count, out->set[s]));
      for (pdk_index i = 0; i < n; ++i)
        PDK_CHECK_GOTO(out->set[s][i] <= 1, ctx, PDK_ERR_ARG,
                       "%s: %ssets/%s[%ld] is %d; a set holds 0 or 1", path, where, name, (long)i,
                       out->set[s][i]);
    }
  }
  /* material: an integer dataset [n], each particle's material index */
  if (H5Lexists(g, "material", H5P_DEFAULT) > 0) {
    hsize_t dm[2];
    int integer = 0;
    if (dset_dims(g, "material", dm) == 1 && dm[0] == dx[0]) {
      hid_t d = H5Dopen2(g, "material", H5P_DEFAULT), t = d >= 0 ? H5Dget_type(d) : -1;
      integer = t >= 0 && H5Tget_class(t) == H5T_INTEGER;
      if (t >= 0) H5Tclose(t);
      if (d >= 0) H5Dclose(d);
    }
    PDK_CHECK_GOTO(integer, ctx, PDK_ERR_ARG,
                   "%s: %smaterial is not an integer dataset of %ld values (each particle's "
                   "material index: 0 for `material`, k for materials entry k - 1)",
                   path, where, (long)n);
    out->mkey = calloc(PDK_POINTS_MAX_MKEYS, sizeof *out->mkey);
    out->material = malloc((size_t)n * sizeof(int32_t));
    PDK_CHECK_GOTO(out->mkey && out->material, ctx, PDK_ERR_MEMORY, "out of memory");
    const hsize_t start[1] = {0}, count[1] = {dx[0]};
    PDK_CALL_GOTO(
        pdk_h5_read_block(ctx, g, "material", H5T_NATIVE_INT32, 1, start, count, out->material));
    for (pdk_index i = 0; i < n; ++i) {
      PDK_CHECK_GOTO(out->material[i] >= 0, ctx, PDK_ERR_ARG,
                     "%s: %smaterial[%ld] is %d; a material index is >= 0 (0 for `material`, k "
                     "for materials entry k - 1)",
                     path, where, (long)i, (int)out->material[i]);
      const int key = pdk_points_mkey_find(out, NULL, 0, out->material[i], 0, i);
      PDK_CHECK_GOTO(key >= 0, ctx, PDK_ERR_ARG, "%s: more than %d different materials in %smaterial",
                     path, PDK_POINTS_MAX_MKEYS, where);
      out->material[i] = key;
    }
  }
cleanup:
  free(xyz);
  if (gs >= 0) H5Gclose(gs);
  if (g >= 0) H5Gclose(g);
  if (f >= 0) H5Fclose(f);
  if (err) pdk_points_free(out);
  return err;
}
