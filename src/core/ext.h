/* Wrappers for calls into foreign libraries (hwloc, HDF5, SuiteSparse, libcyaml).
 *
 * Each macro evaluates one foreign call, translates that library's failure convention into a pdk
 * error whose message names the foreign function (the text of the call) and the library's own
 * reason, and returns (or, for the _GOTO forms, sets `err` and jumps to `cleanup`).
 *   hwloc:    return value < 0, reason from errno
 *   HDF5:     return value < 0 (herr_t, hid_t), reason from the HDF5 error stack
 *   CHOLMOD:  return value 0/NULL or common->status < CHOLMOD_OK (warnings > 0 are not failures)
 *   UMFPACK:  status != UMFPACK_OK (warnings such as singular matrix are failures for pdk)
 *   libcyaml: cyaml_err_t != CYAML_OK, reason from cyaml_strerror
 */
#ifndef PDK_EXT_H
#define PDK_EXT_H

#include <cholmod.h>
#include <cyaml/cyaml.h>
#include <hdf5.h>
#include <umfpack.h>

#include "pdk_impl.h"
#include "pdk/ctx.h"

/* HDF5's automatic error-stack printing is off while any context exists (pdk reports HDF5
 * failures itself, with the file's name): the first pdk_h5_quiet_acquire saves the process's
 * handler and turns printing off, the last pdk_h5_quiet_release puts the saved handler back, so
 * a host program that uses HDF5 gets its own setting back when it destroys its contexts. */
void pdk_h5_quiet_acquire(void);
void pdk_h5_quiet_release(void);

int pdk_ext_hwloc_fail(pdk_ctx *ctx, const char *call, const char *where, int err_no);
int pdk_ext_h5_fail(pdk_ctx *ctx, const char *call, const char *where);
int pdk_ext_cholmod_fail(pdk_ctx *ctx, const char *call, const char *where, int status);
int pdk_ext_umfpack_fail(pdk_ctx *ctx, const char *call, const char *where, int status);
int pdk_ext_cyaml_fail(pdk_ctx *ctx, const char *call, const char *where, cyaml_err_t status);
const char *pdk_umfpack_status_text(int status);
const char *pdk_cholmod_status_text(int status);

/* hwloc: `expr` returns int, < 0 on failure. */
#define PDK_HWLOC_CALL(ctx, expr)                                                               \
  do {                                                                                          \
    errno = 0;                                                                                  \
    if ((expr) < 0) return pdk_ext_hwloc_fail((ctx), #expr, __func__, errno);                   \
  } while (0)

/* HDF5: `expr` returns herr_t or hid_t, < 0 on failure. `out` (may be NULL) receives the value. */
#define PDK_H5_CALL(ctx, expr)                                                                  \
  do {                                                                                          \
    if ((int64_t)(expr) < 0) return pdk_ext_h5_fail((ctx), #expr, __func__);                    \
  } while (0)
#define PDK_H5_CALL_GOTO(ctx, var, expr)                                                        \
  do {                                                                                          \
    (var) = (expr);                                                                             \
    if ((int64_t)(var) < 0) {                                                                   \
      err = pdk_ext_h5_fail((ctx), #expr, __func__);                                            \
      goto cleanup;                                                                             \
    }                                                                                           \
  } while (0)

/* CHOLMOD: `expr` returns int (TRUE on success) or a pointer (NULL on failure); `cc` is the
 * cholmod_common. A positive status is a warning (for example not positive definite, which
 * the caller inspects itself through L->minor) and not reported as a failure here. */
#define PDK_CHOLMOD_CALL_GOTO(ctx, cc, expr)                                                    \
  do {                                                                                          \
    int pdk_ok_ = ((expr) != 0);                                                                \
    if (!pdk_ok_ || (cc)->status < CHOLMOD_OK) {                                                \
      err = pdk_ext_cholmod_fail((ctx), #expr, __func__, (cc)->status);                         \
      goto cleanup;                                                                             \
    }                                                                                           \
  } while (0)

/* UMFPACK: `expr` returns an int status. */
#define PDK_UMFPACK_CALL_GOTO(ctx, expr)                                                        \
  do {                                                                                          \
    int pdk_st_ = (int)(expr);                                                                  \
    if (pdk_st_ != UMFPACK_OK) {                                                                \
      err = pdk_ext_umfpack_fail((ctx), #expr, __func__, pdk_st_);                              \
      goto cleanup;                                                                             \
    }                                                                                           \
  } while (0)

/* libcyaml: `expr` returns cyaml_err_t. */
#define PDK_CYAML_CALL_GOTO(ctx, expr)                                                          \
  do {                                                                                          \
    cyaml_err_t pdk_ce_ = (expr);                                                               \
    if (pdk_ce_ != CYAML_OK) {                                                                  \
      err = pdk_ext_cyaml_fail((ctx), #expr, __func__, pdk_ce_);                                \
      goto cleanup;                                                                             \
    }                                                                                           \
  } while (0)

#endif
