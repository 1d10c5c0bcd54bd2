/* A context leaves the host program as it found it, and takes its thread count from OpenMP's
 * variable too.
 *   - OMP_NUM_THREADS (without PDK_NUM_THREADS) sets the count: "1" gives 1 thread, "3,2" (a
 *     nested list) 3; PDK_NUM_THREADS wins over it; a value that is not a count is refused with
 *     a message naming the variable.
 *   - With PDK_BIND_CORE the calling thread is bound to one core while the context exists (on a
 *     machine with more than one core) and gets its own CPU set back from pdk_ctx_destroy; so do
 *     the OpenMP pool threads pdk bound (they started with the caller's set).
 *   - HDF5's automatic error printing is off while a context exists, and the handler the host had
 *     is back once the last context is destroyed.
 * Where the system forbids binding (some containers), the binding checks are skipped with a
 * note: nothing was pinned, so there is nothing to give back.
 * labels: unit */
#define _GNU_SOURCE
#include <hdf5.h>
#include <omp.h>
#include <sched.h>

#include "test_util.h"

static pdk_ctx *make(int bind_core) {
  pdk_ctx_opts o = pdk_ctx_opts_default();
  o.bind = bind_core ? PDK_BIND_CORE : PDK_BIND_NONE;
  o.bind_explicit = 1;
  pdk_ctx *ctx = NULL;
  char why[512];
  if (pdk_ctx_create(&o, &ctx, why, sizeof why)) T_FAIL("pdk_ctx_create: %s", why);
  return ctx;
}

static int threads_with(const char *omp, const char *pdk) {
  if (omp) setenv("OMP_NUM_THREADS", omp, 1); else unsetenv("OMP_NUM_THREADS");
  if (pdk) setenv("PDK_NUM_THREADS", pdk, 1); else unsetenv("PDK_NUM_THREADS");
  pdk_ctx *ctx = make(0);
  int n = pdk_ctx_num_threads(ctx);
  pdk_ctx_destroy(&ctx);
  return n;
}

static herr_t host_handler(hid_t stack, void *data) {
  (void)stack;
  (void)data;
  return 0;
}

int main(void) {
  /* thread count from the environment */
  T_ASSERT(threads_with("1", NULL) == 1, "OMP_NUM_THREADS=1 gives one thread");
  T_ASSERT(threads_with("3,2", NULL) == 3, "OMP_NUM_THREADS=3,2 gives 3 (its first level)");
  T_ASSERT(threads_with("1", "2") == 2, "PDK_NUM_THREADS wins over OMP_NUM_THREADS");
  {
    setenv("OMP_NUM_THREADS", "many", 1);
    unsetenv("PDK_NUM_THREADS");
    pdk_ctx *ctx = NULL;
    char why[512] = "";
    pdk_ctx_opts o = pdk_ctx_opts_default();
    T_ASSERT(pdk_ctx_create(&o, &ctx, why, sizeof why) == PDK_ERR_ARG && ctx == NULL,
             "OMP_NUM_THREADS=many is refused");
    T_ASSERT(strstr(why, "OMP_NUM_THREADS='many'"), "the message names the variable: %s", why);
    o.num_threads = 1; /* an explicit count does not read the environment */
    T_ASSERT(pdk_ctx_create(&o, &ctx, why, sizeof why) == 0, "explicit count: %s", why);
    pdk_ctx_destroy(&ctx);
    unsetenv("OMP_NUM_THREADS");
  }

  /* HDF5's error handler: a host's own, off under pdk, back afterwards */
  T_ASSERT(H5Eset_auto2(H5E_DEFAULT, host_handler, &host_handler) >= 0, "H5Eset_auto2");
  {
    pdk_ctx *a = make(0), *b = make(0);
    H5E_auto2_t f = NULL;
    void *d = NULL;
    T_ASSERT(H5Eget_auto2(H5E_DEFAULT, &f, &d) >= 0 && f == NULL, "printing off under pdk");
    pdk_ctx_destroy(&a);
    T_ASSERT(H5Eget_auto2(H5E_DEFAULT, &f, &d) >= 0 && f == NULL,
             "still off while a context exists");
    pdk_ctx_destroy(&b);
    T_ASSERT(H5Eget_auto2(H5E_DEFAULT, &f, &d) >= 0 && f == host_handler && d == &host_handler,
             "the host's handler is back after the last context");
  }

  /* binding: the caller's CPU set before, under and after a context */
  cpu_set_t before, now;
  T_ASSERT(sched_getaffinity(0, sizeof before, &before) == 0, "sched_getaffinity");
  const int cpus = CPU_COUNT(&before);
  pdk_ctx *ctx = make(1);
  const int nt = pdk_ctx_num_threads(ctx);
  T_ASSERT(sched_getaffinity(0, sizeof now, &now) == 0, "sched_getaffinity");
  if (CPU_EQUAL(&now, &before) && cpus > 1) {
    printf("pdk-test-note: binding is not allowed here (the thread kept %d CPUs); binding checks "
           "skipped\n",
           cpus);
    pdk_ctx_destroy(&ctx);
    return 0;
  }
  if (cpus > 1) T_ASSERT(CPU_COUNT(&now) < cpus, "bound to a core while the context exists");
  pdk_ctx_destroy(&ctx);
  T_ASSERT(sched_getaffinity(0, sizeof now, &now) == 0 && CPU_EQUAL(&now, &before),
           "the caller's CPU set is back after pdk_ctx_destroy (%d CPUs, had %d)", CPU_COUNT(&now),
           cpus);
  int pool_ok = 1;
#pragma omp parallel num_threads(nt) reduction(& : pool_ok)
  {
    cpu_set_t mine;
    pool_ok = sched_getaffinity(0, sizeof mine, &mine) == 0 && CPU_EQUAL(&mine, &before);
  }
  T_ASSERT(pool_ok, "the OpenMP threads pdk bound have the caller's CPU set back");
  return 0;
}
