/* Translation of foreign libraries' failures into pdk errors; see ext.h for each convention. */
#include "ext.h"
#include "pdk/ctx.h"

#include <errno.h>
#include <pthread.h>
#include <string.h>

static pthread_mutex_t h5_quiet_lock = PTHREAD_MUTEX_INITIALIZER;
static int h5_quiet_count;      /* contexts alive */
static H5E_auto2_t h5_saved_func; /* the handler before the first context */
static void *h5_saved_data;

void pdk_h5_quiet_acquire(void) {
  pthread_mutex_lock(&h5_quiet_lock);
  if (h5_quiet_count++ == 0) {
    if (H5Eget_auto2(H5E_DEFAULT, &h5_saved_func, &h5_saved_data) < 0)
      h5_saved_func = NULL, h5_saved_data = NULL;
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  }
  pthread_mutex_unlock(&h5_quiet_lock);
}

void pdk_h5_quiet_release(void) {
  pthread_mutex_lock(&h5_quiet_lock);
  if (h5_quiet_count > 0 && --h5_quiet_count == 0)
    H5Eset_auto2(H5E_DEFAULT, h5_saved_func, h5_saved_data);
  pthread_mutex_unlock(&h5_quiet_lock);
}

int pdk_ext_hwloc_fail(pdk_ctx *ctx, const char *call, const char *where, int err_no) {
  return pdk_ctx_error_set(ctx, PDK_ERR_EXTERNAL, where, "hwloc call %s failed: %s", call,
                           err_no ? strerror(err_no) : "no reason given (errno 0)");
}

typedef struct h5_walk {
  char text[1024];
  size_t len;
} h5_walk;

static herr_t h5_walk_cb(unsigned n, const H5E_error2_t *e, void *data) {
  h5_walk *w = data;
  if (w->len + 8 >= sizeof w->text) return 0;
  int k = snprintf(w->text + w->len, sizeof w->text - w->len, "%s%s()%s%s", n ? "; " : "",
                   e->func_name ? e->func_name : "?", e->desc && e->desc[0] ? ": " : "",
                   e->desc ? e->desc : "");
  if (k > 0) w->len += (size_t)k < sizeof w->text - w->len ? (size_t)k : sizeof w->text - w->len - 1;
  return 0;
}

int pdk_ext_h5_fail(pdk_ctx *ctx, const char *call, const char *where) {
  h5_walk w = {{0}, 0};
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, h5_walk_cb, &w);
  H5Eclear2(H5E_DEFAULT);
  return pdk_ctx_error_set(ctx, PDK_ERR_EXTERNAL, where, "HDF5 call %s failed: %s", call,
                           w.len ? w.text : "no HDF5 error stack");
}

const char *pdk_cholmod_status_text(int status) {
  switch (status) {
  case CHOLMOD_OK: return "ok";
  case CHOLMOD_NOT_INSTALLED: return "method not installed";
  case CHOLMOD_OUT_OF_MEMORY: return "out of memory";
  case CHOLMOD_TOO_LARGE: return "integer overflow (problem too large)";
  case CHOLMOD_INVALID: return "invalid input";
  case CHOLMOD_GPU_PROBLEM: return "GPU problem";
  case CHOLMOD_NOT_POSDEF: return "matrix not positive definite";
  case CHOLMOD_DSMALL: return "diagonal entry tiny (ill-conditioned)";
  default: return "unknown status";
  }
}

int pdk_ext_cholmod_fail(pdk_ctx *ctx, const char *call, const char *where, int status) {
  return pdk_ctx_error_set(ctx, PDK_ERR_EXTERNAL, where, "CHOLMOD call %s failed: %s (status %d)",
                           call, pdk_cholmod_status_text(status), status);
}

const char *pdk_umfpack_status_text(int status) {
  switch (status) {
  case UMFPACK_OK: return "ok";
  case UMFPACK_WARNING_singular_matrix: return "matrix is singular";
  case UMFPACK_WARNING_determinant_underflow: return "determinant underflow";
  case UMFPACK_WARNING_determinant_overflow: return "determinant overflow";
  case UMFPACK_ERROR_out_of_memory: return "out of memory";
  case UMFPACK_ERROR_invalid_Numeric_object: return "invalid Numeric object";
  case UMFPACK_ERROR_invalid_Symbolic_object: return "invalid Symbolic object";
  case UMFPACK_ERROR_argument_missing: return "argument missing";
  case UMFPACK_ERROR_n_nonpositive: return "matrix dimension not positive";
  case UMFPACK_ERROR_invalid_matrix: return "invalid matrix (column pointers or row indices)";
  case UMFPACK_ERROR_different_pattern: return "pattern changed since the symbolic analysis";
  case UMFPACK_ERROR_invalid_system: return "invalid system";
  case UMFPACK_ERROR_invalid_permutation: return "invalid permutation";
  case UMFPACK_ERROR_internal_error: return "internal error";
  case UMFPACK_ERROR_file_IO: return "file I/O error";
  default: return "unknown status";
  }
}

int pdk_ext_umfpack_fail(pdk_ctx *ctx, const char *call, const char *where, int status) {
  return pdk_ctx_error_set(ctx, PDK_ERR_EXTERNAL, where, "UMFPACK call %s failed: %s (status %d)",
                           call, pdk_umfpack_status_text(status), status);
}

int pdk_ext_cyaml_fail(pdk_ctx *ctx, const char *call, const char *where, cyaml_err_t status) {
  return pdk_ctx_error_set(ctx, PDK_ERR_EXTERNAL, where, "libcyaml call %s failed: %s", call,
                           cyaml_strerror(status));
}
