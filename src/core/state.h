/* Private: an object's part of a checkpoint, as the object sees it.
 *
 * src/io/checkpoint.c owns the checkpoint file: its format, the checksum in the user block, the
 * particle fields, and the order of the parts. Each object with state beyond the particle fields
 * saves and loads its own part, next to its code, through a pdk_state: one group of the file,
 * holding named scalars (HDF5 attributes of the group) and arrays (1-D datasets in it):
 *   /solver  the explicit solver's scalars       src/solvers/explicit_state.c  pdk_explicit_state_*
 *   /model   the bond state and counters          src/models/model_state.c     pdk_model_state_*
 *            and the kind's own state after them  the kind's file       pdk_model_ops.state_*
 * The names and types of each part are listed in include/pdk/output.h (the checkpoint layout).
 *
 * Loading has two passes so that a checkpoint that does not fit changes nothing: the checks
 * (pdk_model_state_check, and the checkpoint's own) read and compare, and only then do the loads
 * (pdk_model_state_load, pdk_explicit_state_load) change the objects. A check that finds a
 * difference says so with pdk_state_mismatch.
 */
#ifndef PDK_STATE_H
#define PDK_STATE_H

#include <stddef.h>
#include <stdint.h>

#include "pdk_impl.h"
#include "pdk/ctx.h"
#include "pdk/particles.h"

typedef struct pdk_state pdk_state;

/* The context errors are reported into. */
pdk_ctx *pdk_state_ctx(const pdk_state *s);

/* Saving: a scalar, or an array of `count` entries of `type` (count 0 gives an empty array). */
int pdk_state_put_i64(pdk_state *s, const char *name, int64_t value);
int pdk_state_put_f64(pdk_state *s, const char *name, double value);
int pdk_state_put_array(pdk_state *s, const char *name, pdk_type type, size_t count,
                        const void *data);

/* Loading: 1 when the group holds a scalar or an array `name`, else 0. Reading one that is not
 * there, or an array of another length than `count`, is an error (PDK_ERR_IO). */
int pdk_state_has(const pdk_state *s, const char *name);
int pdk_state_get_i64(pdk_state *s, const char *name, int64_t *value);
int pdk_state_get_f64(pdk_state *s, const char *name, double *value);
int pdk_state_get_array(pdk_state *s, const char *name, pdk_type type, size_t count, void *data);

/* The errors of a check, naming the checkpoint file: PDK_ERR_ARG "checkpoint '<path>' does not
 * fit this simulation: <what>; the scene changed since ..." (printf format), and PDK_ERR_IO
 * "checkpoint '<path>' lacks /<group>/<name>". Both return the code. */
int pdk_state_mismatch(pdk_state *s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
int pdk_state_missing(pdk_state *s, const char *name);

#endif
