/* Private: the collective operations the layers above use when a run has several ranks
 * (src/core/comm.c; the only file that calls MPI). Without MPI, or on one rank, each is a no-op
 * that succeeds. */
#ifndef PDK_CORE_COMM_H
#define PDK_CORE_COMM_H

#include <stddef.h>
#include <stdint.h>

#include "pdk/ctx.h"

/* Every rank r owns the rows [start[r], start[r + 1]) of buf (elem bytes a row); afterwards every
 * rank holds every rank's rows (in place). */
int pdk_comm_allgather_rows(pdk_ctx *ctx, void *buf, size_t elem, const int64_t *start);
/* *v becomes the sum over the ranks (integers: exact). */
int pdk_comm_sum_i64(pdk_ctx *ctx, int64_t *v);

#endif
