/* Ranks through MPI (include/pdk/comm.h, core/comm.h): the only file of pdk that calls MPI. A
 * build without MPI (PDK_HAVE_MPI 0) compiles the same functions for one rank. */
#include "comm.h"

#include <limits.h>
#include <stdlib.h>

#include "pdk_impl.h"
#include "pdk/comm.h"
#include "pdk/ctx.h"
#include "pdk/version.h"

#if PDK_HAVE_MPI
#include <mpi.h>

static int started_here;

static int mpi_on(void) {
  int on = 0, done = 0;
  MPI_Initialized(&on);
  if (on) MPI_Finalized(&done);
  return on && !done;
}

/* Whether a launcher (mpiexec of Open MPI, MPICH's Hydra, a PMIx launcher) started this process:
 * a process started otherwise runs on one rank without starting MPI (no singleton start-up, which
 * costs time and can fail where MPI's transports cannot open). */
static int launched(void) {
  const char *const vars[] = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "PMI_RANK"};
  for (size_t k = 0; k < sizeof vars / sizeof vars[0]; ++k)
    if (getenv(vars[k])) return 1;
  return 0;
}

int pdk_comm_init(int *argc, char ***argv) {
  if (mpi_on() || !launched()) return PDK_SUCCESS;
  int provided = 0;
  if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    return PDK_ERR_EXTERNAL;
  started_here = 1;
  return PDK_SUCCESS;
}

void pdk_comm_finalize(void) {
  if (started_here && mpi_on()) MPI_Finalize();
  started_here = 0;
}

void pdk_comm_abort(int code) {
  if (mpi_on() && pdk_comm_size() > 1) MPI_Abort(MPI_COMM_WORLD, code);
  exit(code);
}

int pdk_comm_rank(void) {
  int r = 0;
  if (mpi_on()) MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

int pdk_comm_size(void) {
  int s = 1;
  if (mpi_on()) MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

int pdk_comm_built_with_mpi(void) { return 1; }

int pdk_comm_allgather_rows(pdk_ctx *ctx, void *buf, size_t elem, const int64_t *start) {
  const int size = pdk_comm_size();
  if (size == 1) return PDK_SUCCESS;
  int *counts = malloc(2 * (size_t)size * sizeof *counts);
  PDK_CHECK(counts, ctx, PDK_ERR_MEMORY, "out of memory for the exchange between %d ranks", size);
  int *displs = counts + size;
  for (int r = 0; r < size; ++r) {
    const int64_t c = (start[r + 1] - start[r]) * (int64_t)elem, d = start[r] * (int64_t)elem;
    if (c > INT_MAX || d > INT_MAX) {
      free(counts);
      return pdk_ctx_error_set(ctx, PDK_ERR_UNSUPPORTED, __func__,
                               "an exchange between ranks of more than %d bytes (%lld up to rank "
                               "%d) is not supported yet; run on one rank",
                               INT_MAX, (long long)(d + c), r);
    }
    counts[r] = (int)c;
    displs[r] = (int)d;
  }
  const int rc = MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, buf, counts, displs, MPI_BYTE,
                                MPI_COMM_WORLD);
  free(counts);
  PDK_CHECK(rc == MPI_SUCCESS, ctx, PDK_ERR_EXTERNAL, "MPI_Allgatherv failed (error %d)", rc);
  return PDK_SUCCESS;
}

int pdk_comm_sum_i64(pdk_ctx *ctx, int64_t *v) {
  if (pdk_comm_size() == 1) return PDK_SUCCESS;
  const int rc = MPI_Allreduce(MPI_IN_PLACE, v, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
  PDK_CHECK(rc == MPI_SUCCESS, ctx, PDK_ERR_EXTERNAL, "MPI_Allreduce failed (error %d)", rc);
  return PDK_SUCCESS;
}

#else /* one rank */

int pdk_comm_init(int *argc, char ***argv) {
  (void)argc;
  (void)argv;
  return PDK_SUCCESS;
}
void pdk_comm_finalize(void) {}
void pdk_comm_abort(int code) { exit(code); }
int pdk_comm_rank(void) { return 0; }
int pdk_comm_size(void) { return 1; }
int pdk_comm_built_with_mpi(void) { return 0; }
int pdk_comm_allgather_rows(pdk_ctx *ctx, void *buf, size_t elem, const int64_t *start) {
  (void)ctx;
  (void)buf;
  (void)elem;
  (void)start;
  return PDK_SUCCESS;
}
int pdk_comm_sum_i64(pdk_ctx *ctx, int64_t *v) {
  (void)ctx;
  (void)v;
  return PDK_SUCCESS;
}

#endif
