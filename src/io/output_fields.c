/* Run output, field outputs: each field of an output as an HDF5 dataset under /steps/<k>
 * (scalars, vectors, tensors and matrices by the number of components, a unit attribute where pdk
 * knows the field's unit), and one XDMF grid per output that indexes them for ParaView
 * (src/io/output.c, src/io/output_impl.h).
 */
#include <errno.h>
#include <math.h>
#include <string.h>

#include "output_impl.h"
#include "pdk/ctx.h"
#include "pdk/output.h"
#include "pdk/particles.h"

/* ---- field layout -----------------------------------------------------------------------------
 */

/* How a field of num_comp components is stored: the dataset's columns and where component c goes.
 */
out_layout pdk_out_field_layout(int dim, int num_comp, int *cols, int col_of[9]) {
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
int pdk_out_create_field_dataset(pdk_output *o, hid_t loc, const char *name, pdk_type type,
                                 int cols, int level, hid_t *out) {
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
const char *pdk_out_field_unit(const pdk_output *o, const char *field, char *buf, size_t len) {
  static const char *const length[] = {"x", "X", "u", "ul_X"};
  static const char *const one[] = {"eps_p", "damage", "bond_damage", "failed", "stab_factor",
                                    "theta", "F",      "ul_F",        "ul_J",   "flag"};
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
int pdk_out_write_field(pdk_output *o, pdk_particles *p, hid_t loc, const char *name,
                        const char *field, int level, out_layout *layout_out, int *cols_out,
                        pdk_type *type_out) {
  int err = PDK_SUCCESS;
  hid_t d = -1;
  pdk_type type;
  int num_comp, cols, col_of[9];
  void *comp[9];
  PDK_CALL(pdk_particles_field_info(p, field, &type, &num_comp));
  out_layout layout = pdk_out_field_layout(o->dim, num_comp, &cols, col_of);
  for (int c = 0; c < num_comp; ++c)
    comp[c] = pdk_particles_field_data(p, field, c);
  PDK_CALL_GOTO(pdk_out_create_field_dataset(o, loc, name, type, cols, level, &d));
  PDK_CALL_GOTO(write_field_data(o, d, type, num_comp, cols, col_of, comp));
  {
    char buf[64];
    const char *unit = pdk_out_field_unit(o, field, buf, sizeof buf);
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
  char *escaped = pdk_out_xml_escape(name);
  PDK_CHECK(escaped, o->ctx, PDK_ERR_MEMORY, "out of memory");
  fprintf(o->xmf, "      <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Node\">\n", escaped,
          layout_name(layout));
  free(escaped);
  xmf_data_item(o, "        ", cols, type, path);
  fprintf(o->xmf, "      </Attribute>\n");
  return PDK_SUCCESS;
}

/* 1 when `name` is among the fields of this output (then its static attribute is left out: one
 * grid must not hold two attributes of the same name). */
int pdk_out_listed(const char *name, const char *const *fields, int num_fields) {
  for (int k = 0; k < num_fields; ++k)
    if (!strcmp(fields[k], name)) return 1;
  return 0;
}

int pdk_out_xmf_grid_open(pdk_output *o, long step, double time, const char *geometry_path,
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
  if (!pdk_out_listed("id", fields, num_fields))
    PDK_CALL(xmf_attribute(o, "id", OUT_SCALAR, 1, PDK_I64, "/static/id"));
  if (!pdk_out_listed("volume", fields, num_fields))
    PDK_CALL(xmf_attribute(o, "volume", OUT_SCALAR, 1, PDK_F64, "/static/volume"));
  for (int s = 0; s < o->num_sets; ++s) {
    if (pdk_out_listed(o->set_field[s], fields, num_fields)) continue;
    snprintf(path, sizeof path, "/static/sets/%s", o->set_name[s]);
    PDK_CALL(xmf_attribute(o, o->set_field[s], OUT_SCALAR, 1, PDK_U8, path));
  }
  return PDK_SUCCESS;
}

/* ---- writes -----------------------------------------------------------------------------------
 */

int pdk_output_write_fields(pdk_output *o, pdk_particles *p, long step, double time,
                            const char *const *fields, int num_fields) {
  if (!o)
    return p ? pdk_ctx_error_set(pdk_particles_ctx(p), PDK_ERR_ARG, __func__, "no output given")
             : PDK_ERR_ARG;
  if (o->mute) return PDK_SUCCESS;
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
      pdk_out_field_list(p, list, sizeof list);
      PDK_CHECK_GOTO(0, ctx, PDK_ERR_NOT_FOUND,
                     "cannot write field '%s': no such particle field; the fields are: %s",
                     fields[k] ? fields[k] : "(null)", list);
    }
    pdk_out_sanitize(fields[k], dname[k], OUT_NAME_MAX);
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
  PDK_CALL_GOTO(pdk_out_xmf_grid_open(o, step, time, path, fields, num_fields));
  for (int k = 0; k < num_fields; ++k) {
    out_layout layout;
    int cols;
    pdk_type type;
    PDK_CALL_GOTO(
        pdk_out_write_field(o, p, g, dname[k], fields[k], o->compression, &layout, &cols, &type));
    snprintf(path, sizeof path, OUT_STEP_GROUP "/%s", (long)k_out, dname[k]);
    PDK_CALL_GOTO(xmf_attribute(o, fields[k], layout, cols, type, path));
  }
  fprintf(o->xmf, "    </Grid>\n");
  PDK_CALL_GOTO(pdk_out_flush_files(o));
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
