/* Context: thread count, hwloc topology and binding, CPU features, kernel table, last error. */
#include <ctype.h>
#include <errno.h>
#include <hwloc.h>
#include <omp.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include "ext.h"
#include "pdk/ctx.h"
#include "pdk/version.h"
#include "pdk/comm.h"

pdk_ctx_opts pdk_ctx_opts_default(void) {
  pdk_ctx_opts o;
  memset(&o, 0, sizeof o);
  o.num_threads = 0;
  o.bind = PDK_BIND_CORE;
  o.bind_explicit = 0;
  o.kernels = NULL;
  return o;
}

static unsigned detect_isa(void) {
  unsigned isa = 0;
#if defined(__x86_64__) && defined(__GNUC__)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) isa |= PDK_ISA_AVX2;
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
      __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw"))
    isa |= PDK_ISA_AVX512;
#endif
  return isa;
}

static int parse_positive_int(const char *s, int *out) {
  char *end = NULL;
  errno = 0;
  long v = strtol(s, &end, 10);
  if (errno || end == s || *end != '\0' || v < 1 || v > 4096) return -1;
  *out = (int)v;
  return 0;
}

static int fail_early(char *buf, size_t len, const char *fmt, const char *arg) {
  if (buf && len) snprintf(buf, len, fmt, arg);
  return PDK_ERR_ARG;
}

/* Binds OpenMP threads 0..num_threads-1 to cores per the policy; remembers how many were. */
static void bind_threads(pdk_ctx *ctx) {
  if (ctx->bind != PDK_BIND_CORE) return;
  if (ctx->num_threads > ctx->num_bound) ctx->num_bound = ctx->num_threads;
#pragma omp parallel default(none) shared(ctx) num_threads(ctx->num_threads)
  pdk_ctx_bind_thread(ctx, omp_get_thread_num());
}

int pdk_ctx_create(const pdk_ctx_opts *opts_in, pdk_ctx **out, char *err_buf, size_t err_len) {
  pdk_ctx_opts opts = opts_in ? *opts_in : pdk_ctx_opts_default();
  if (!out) return fail_early(err_buf, err_len, "%s", "pdk_ctx_create: argument 'out' is NULL");
  *out = NULL;
  if (err_buf && err_len) err_buf[0] = '\0';

  const char *env_bind = getenv("PDK_BIND");
  if (env_bind && !opts.bind_explicit) {
    if (!strcmp(env_bind, "core")) opts.bind = PDK_BIND_CORE;
    else if (!strcmp(env_bind, "none")) opts.bind = PDK_BIND_NONE;
    else return fail_early(err_buf, err_len, "PDK_BIND='%s' is not a binding policy; use 'core' or 'none'", env_bind);
  }
  /* several MPI ranks on one host would pin their threads to the same cores (thread t to core t
   * of each rank's view): the placement is left to mpiexec's binding unless asked for */
  if (!env_bind && !opts.bind_explicit && pdk_comm_size() > 1) opts.bind = PDK_BIND_NONE;
  const char *env_threads = getenv("PDK_NUM_THREADS");
  if (env_threads && opts.num_threads == 0) {
    if (parse_positive_int(env_threads, &opts.num_threads))
      return fail_early(err_buf, err_len, "PDK_NUM_THREADS='%s' is not a thread count; use an integer from 1 to 4096", env_threads);
  }
  /* OpenMP's own variable, after pdk's: its first entry (a list gives nested levels) */
  const char *env_omp = getenv("OMP_NUM_THREADS");
  if (env_omp && env_omp[0] && opts.num_threads == 0) {
    char first[32] = {0};
    const size_t len = strcspn(env_omp, ",");
    if (len < sizeof first) memcpy(first, env_omp, len);
    if (len >= sizeof first || parse_positive_int(first, &opts.num_threads))
      return fail_early(err_buf, err_len, "OMP_NUM_THREADS='%s' is not a thread count; use an integer from 1 to 4096 (or unset it)", env_omp);
  }
  if (opts.num_threads < 0)
    return fail_early(err_buf, err_len, "%s", "num_threads must be >= 0 (0 picks one thread per core)");
  const char *env_kernels = getenv("PDK_KERNELS");
  if (env_kernels && !opts.kernels) opts.kernels = env_kernels;

  pdk_ctx *ctx = calloc(1, sizeof *ctx);
  if (!ctx) return fail_early(err_buf, err_len, "%s", "out of memory creating the context");
  ctx->isa = detect_isa();
  ctx->bind = opts.bind;

  hwloc_topology_t topo;
  if (hwloc_topology_init(&topo) < 0 || hwloc_topology_load(topo) < 0) {
    free(ctx);
    return fail_early(err_buf, err_len, "hwloc could not read the machine topology: %s", strerror(errno));
  }
  ctx->topology = topo;
  int depth = hwloc_get_type_depth(topo, HWLOC_OBJ_CORE);
  ctx->num_cores = depth < 0 ? 0 : (int)hwloc_get_nbobjs_by_depth(topo, (unsigned)depth);
  if (ctx->num_cores < 1) ctx->num_cores = 1;
  ctx->max_threads = omp_get_num_procs();
  if (ctx->max_threads < 1) ctx->max_threads = 1;

  int nt = opts.num_threads ? opts.num_threads : ctx->num_cores;
  if (nt > ctx->max_threads && !opts.num_threads) nt = ctx->max_threads;
  if (nt > 4096) nt = 4096;
  ctx->num_threads = nt;

  if (pdk_kernels_select(opts.kernels, ctx->isa, &ctx->kernels)) {
    hwloc_topology_destroy(topo);
    free(ctx);
    return fail_early(err_buf, err_len,
                      "PDK_KERNELS/kernels='%s' is not a kernel family this CPU runs; use 'ref' "
                      "or 'simd' (best for the CPU), or 'avx2', 'avx512' where the CPU has them",
                      opts.kernels);
  }
  pdk_h5_quiet_acquire();

  if (ctx->bind == PDK_BIND_CORE) {
    /* the caller's thread is OpenMP thread 0 and gets pinned: keep its binding to give back */
    hwloc_bitmap_t set = hwloc_bitmap_alloc();
    if (set && hwloc_get_cpubind(topo, set, HWLOC_CPUBIND_THREAD) == 0)
      ctx->caller_cpuset = set;
    else
      hwloc_bitmap_free(set);
    bind_threads(ctx);
  }
  *out = ctx;
  return PDK_SUCCESS;
}

void pdk_ctx_destroy(pdk_ctx **ctx) {
  if (!ctx || !*ctx) return;
  pdk_ctx *c = *ctx;
  hwloc_topology_t topo = c->topology;
  if (c->caller_cpuset) {
    /* the threads pdk pinned (the caller's and the OpenMP pool's) get the caller's binding back,
     * the one they started with */
    hwloc_const_bitmap_t set = c->caller_cpuset;
    if (c->num_bound > 0) {
#pragma omp parallel default(none) shared(topo, set) num_threads(c->num_bound)
      hwloc_set_cpubind(topo, set, HWLOC_CPUBIND_THREAD);
    }
    hwloc_bitmap_free(c->caller_cpuset);
  }
  if (topo) hwloc_topology_destroy(topo);
  pdk_h5_quiet_release();
  free(c);
  *ctx = NULL;
}

void pdk_ctx_bind_thread(pdk_ctx *ctx, int tid) {
  if (ctx->bind != PDK_BIND_CORE) return;
  hwloc_topology_t topo = ctx->topology;
  hwloc_obj_t core = hwloc_get_obj_by_type(topo, HWLOC_OBJ_CORE, (unsigned)(tid % ctx->num_cores));
  if (!core) return;
  errno = 0;
  if (hwloc_set_cpubind(topo, core->cpuset, HWLOC_CPUBIND_THREAD) < 0) {
    __atomic_store_n(&ctx->bind_errno, errno ? errno : EINVAL, __ATOMIC_RELAXED);
  }
}

int pdk_ctx_num_threads(const pdk_ctx *ctx) { return ctx ? ctx->num_threads : 0; }

int pdk_ctx_set_num_threads(pdk_ctx *ctx, int num_threads) {
  PDK_CHECK_ARG(ctx, NULL);
  PDK_CHECK(num_threads >= 1 && num_threads <= 4096, ctx, PDK_ERR_ARG,
            "thread count %d is out of range; use 1 to 4096", num_threads);
  ctx->num_threads = num_threads;
  bind_threads(ctx);
  return PDK_SUCCESS;
}

pdk_bind pdk_ctx_bind_policy(const pdk_ctx *ctx) { return ctx ? ctx->bind : PDK_BIND_NONE; }
unsigned pdk_ctx_isa(const pdk_ctx *ctx) { return ctx ? ctx->isa : 0u; }
const char *pdk_ctx_kernels_name(const pdk_ctx *ctx) { return ctx ? ctx->kernels.name : ""; }

size_t pdk_peak_memory_bytes(void) {
  struct rusage ru;
  if (getrusage(RUSAGE_SELF, &ru)) return 0;
  return (size_t)ru.ru_maxrss * 1024u; /* Linux reports KiB */
}

double pdk_wtime(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void print_bytes(FILE *out, uint64_t b) {
  if (b >= (1ull << 30)) fprintf(out, "%.1f GiB", (double)b / (1ull << 30));
  else if (b >= (1ull << 20)) fprintf(out, "%.1f MiB", (double)b / (1ull << 20));
  else fprintf(out, "%.0f KiB", (double)b / 1024.0);
}

static void print_caches(FILE *out, hwloc_topology_t topo) {
  static const hwloc_obj_type_t types[] = {HWLOC_OBJ_L1CACHE, HWLOC_OBJ_L2CACHE, HWLOC_OBJ_L3CACHE};
  static const char *names[] = {"L1d", "L2", "L3"};
  for (int k = 0; k < 3; ++k) {
    int count = hwloc_get_nbobjs_by_type(topo, types[k]);
    if (count <= 0) continue;
    hwloc_obj_t c = hwloc_get_obj_by_type(topo, types[k], 0);
    fprintf(out, "  %-4s %d x ", names[k], count);
    print_bytes(out, c->attr->cache.size);
    fprintf(out, " (line %u B)\n", c->attr->cache.linesize);
  }
}

int pdk_ctx_print_info(pdk_ctx *ctx, FILE *out) {
  PDK_CHECK_ARG(ctx, NULL);
  PDK_CHECK_ARG(out, ctx);
  hwloc_topology_t topo = ctx->topology;
  unsigned maj, min, rel;
  fprintf(out, "pdk %s\n", PDK_VERSION_STRING);
  fprintf(out, "build: %s, %s\n", PDK_BUILD_TYPE, PDK_COMPILER);
  fprintf(out, "flags: %s\n", PDK_BUILD_FLAGS[0] ? PDK_BUILD_FLAGS : "(none)");
  PDK_H5_CALL(ctx, H5get_libversion(&maj, &min, &rel));
  unsigned hw = hwloc_get_api_version();
  fprintf(out, "dependencies: OpenMP %d, hwloc %u.%u.%u, HDF5 %u.%u.%u, CHOLMOD %d.%d.%d, UMFPACK %d.%d.%d, libcyaml %s\n",
          _OPENMP, hw >> 16, (hw >> 8) & 0xff, hw & 0xff, maj, min, rel, CHOLMOD_MAIN_VERSION,
          CHOLMOD_SUB_VERSION, CHOLMOD_SUBSUB_VERSION, UMFPACK_MAIN_VERSION, UMFPACK_SUB_VERSION,
          UMFPACK_SUBSUB_VERSION, cyaml_version_str);

  fprintf(out, "SIMD (run time): avx2+fma %s, avx512 %s; compiled for %s\n",
          ctx->isa & PDK_ISA_AVX2 ? "yes" : "no", ctx->isa & PDK_ISA_AVX512 ? "yes" : "no",
#if defined(__AVX512F__)
          "AVX-512"
#elif defined(__AVX2__)
          "AVX2"
#else
          "baseline x86-64 (variants chosen at run time)"
#endif
  );
  fprintf(out, "kernels: %s\n", ctx->kernels.name);

  int npkg = hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_PACKAGE);
  int npu = hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_PU);
  int nnuma = hwloc_get_nbobjs_by_type(topo, HWLOC_OBJ_NUMANODE);
  hwloc_obj_t root = hwloc_get_root_obj(topo);
  const char *model = hwloc_obj_get_info_by_name(root, "CPUModel");
  if (!model) {
    hwloc_obj_t pkg = hwloc_get_obj_by_type(topo, HWLOC_OBJ_PACKAGE, 0);
    model = pkg ? hwloc_obj_get_info_by_name(pkg, "CPUModel") : NULL;
  }
  fprintf(out, "topology (hwloc): %d package(s), %d core(s), %d hardware thread(s), %d NUMA node(s)%s%s\n",
          npkg, ctx->num_cores, npu, nnuma, model ? ", " : "", model ? model : "");
  for (int k = 0; k < nnuma; ++k) {
    hwloc_obj_t node = hwloc_get_obj_by_type(topo, HWLOC_OBJ_NUMANODE, (unsigned)k);
    fprintf(out, "  NUMA %d: ", k);
    print_bytes(out, node->attr->numanode.local_memory);
    fprintf(out, "\n");
  }
  print_caches(out, topo);

  int nt = ctx->num_threads;
  if (ctx->bind == PDK_BIND_CORE && nt > ctx->num_bound) ctx->num_bound = nt;
  fprintf(out, "threads: %d (binding policy: %s; set with --threads, PDK_NUM_THREADS, OMP_NUM_THREADS, PDK_BIND=core|none)\n",
          nt, ctx->bind == PDK_BIND_CORE ? "one per core" : "none");
  char where[256][128];
  int shown = nt < 256 ? nt : 256;
#pragma omp parallel default(none) shared(ctx, topo, where, shown) num_threads(nt)
  {
    int tid = omp_get_thread_num();
    pdk_ctx_bind_thread(ctx, tid);
    if (tid < shown) {
      hwloc_bitmap_t set = hwloc_bitmap_alloc();
      if (set && hwloc_get_cpubind(topo, set, HWLOC_CPUBIND_THREAD) == 0) {
        char list[64];
        hwloc_bitmap_list_snprintf(list, sizeof list, set);
        int cpu = hwloc_get_last_cpu_location(topo, set, HWLOC_CPUBIND_THREAD) == 0
                      ? hwloc_bitmap_first(set) : -1;
        snprintf(where[tid], sizeof where[tid], "PUs {%s}, running on PU %d", list, cpu);
      } else {
        snprintf(where[tid], sizeof where[tid], "binding unknown");
      }
      hwloc_bitmap_free(set);
    }
  }
  for (int t = 0; t < shown; ++t) fprintf(out, "  thread %d: %s\n", t, where[t]);
  if (ctx->bind_errno) {
    /* reported through the hwloc wrapper's wording, but not an error: threads run unbound */
    pdk_ext_hwloc_fail(ctx, "hwloc_set_cpubind(core)", __func__, ctx->bind_errno);
    fprintf(out, "  note: %s; threads run where the OS puts them (PDK_BIND=none silences this)\n",
            pdk_ctx_error_message(ctx));
    pdk_ctx_error_clear(ctx);
  }
  return PDK_SUCCESS;
}
