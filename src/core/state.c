/* A checkpoint part as an object sees it (src/core/state.h): named scalars (HDF5 attributes) and 1-D
 * arrays of one group. The checkpoint file itself (format, checksum, order of the parts) is
 * src/io/checkpoint.c's; the objects that save and load parts (the explicit solver, the model and
 * its kinds) call only these. */
#include <stdarg.h>
#include <stdio.h>

#include "state.h"
#include "state_impl.h"
#include "pdk/ctx.h"
#include "pdk/particles.h"

pdk_ctx *pdk_state_ctx(const pdk_state *s) { return s->ctx; }

int pdk_state_put_i64(pdk_state *s, const char *name, int64_t value) {
  return pdk_h5_attr_write_i64(s->ctx, s->g, name, value);
}

int pdk_state_put_f64(pdk_state *s, const char *name, double value) {
  return pdk_h5_attr_write_f64(s->ctx, s->g, name, value);
}

int pdk_state_put_array(pdk_state *s, const char *name, pdk_type type, size_t count,
                        const void *data) {
  int err = PDK_SUCCESS;
  pdk_ctx *ctx = s->ctx;
  hid_t space = -1, d = -1;
  herr_t st;
  const hsize_t dims[1] = {(hsize_t)count};
  PDK_H5_CALL_GOTO(ctx, space, H5Screate_simple(1, dims, NULL));
  PDK_H5_CALL_GOTO(
      ctx, d,
      H5Dcreate2(s->g, name, pdk_h5_file_type(type), space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  if (count)
    PDK_H5_CALL_GOTO(ctx, st,
                     H5Dwrite(d, pdk_h5_mem_type(type), H5S_ALL, H5S_ALL, H5P_DEFAULT, data));
cleanup:
  if (d >= 0) H5Dclose(d);
  if (space >= 0) H5Sclose(space);
  return err;
}

int pdk_state_has(const pdk_state *s, const char *name) {
  return pdk_h5_attr_exists(s->g, name) || H5Lexists(s->g, name, H5P_DEFAULT) > 0;
}

int pdk_state_get_i64(pdk_state *s, const char *name, int64_t *value) {
  return pdk_h5_attr_read_i64(s->ctx, s->g, name, value);
}

int pdk_state_get_f64(pdk_state *s, const char *name, double *value) {
  return pdk_h5_attr_read_f64(s->ctx, s->g, name, value);
}

int pdk_state_get_array(pdk_state *s, const char *name, pdk_type type, size_t count, void *data) {
  int err = PDK_SUCCESS;
  pdk_ctx *ctx = s->ctx;
  hid_t d = -1, space = -1;
  herr_t st;
  hsize_t dims[1] = {0};
  PDK_H5_CALL_GOTO(ctx, d, H5Dopen2(s->g, name, H5P_DEFAULT));
  PDK_H5_CALL_GOTO(ctx, space, H5Dget_space(d));
  PDK_CHECK_GOTO(H5Sget_simple_extent_ndims(space) == 1, ctx, PDK_ERR_IO, "'%s' is not 1-D", name);
  H5Sget_simple_extent_dims(space, dims, NULL);
  PDK_CHECK_GOTO(dims[0] == (hsize_t)count, ctx, PDK_ERR_IO, "'%s' has %llu entries, expected %llu",
                 name, (unsigned long long)dims[0], (unsigned long long)count);
  if (count)
    PDK_H5_CALL_GOTO(ctx, st,
                     H5Dread(d, pdk_h5_mem_type(type), H5S_ALL, H5S_ALL, H5P_DEFAULT, data));
cleanup:
  if (space >= 0) H5Sclose(space);
  if (d >= 0) H5Dclose(d);
  return err;
}

int pdk_state_mismatch_v(pdk_ctx *ctx, const char *where, const char *path, const char *fmt,
                         va_list ap) {
  char what[512];
  vsnprintf(what, sizeof what, fmt, ap);
  return pdk_ctx_error_set(ctx, PDK_ERR_ARG, where,
                           "checkpoint '%s' does not fit this simulation: %s; the scene changed "
                           "since the checkpoint was written (restart with the scene stored in "
                           "its 'scene' attribute, or start afresh)",
                           path, what);
}

int pdk_state_mismatch(pdk_state *s, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  const int err = pdk_state_mismatch_v(s->ctx, "pdk_checkpoint_restore", s->path, fmt, ap);
  va_end(ap);
  return err;
}

int pdk_state_missing(pdk_state *s, const char *name) {
  return pdk_ctx_error_set(s->ctx, PDK_ERR_IO, "pdk_checkpoint_restore",
                           "checkpoint '%s' lacks /%s/%s", s->path, s->group, name);
}
