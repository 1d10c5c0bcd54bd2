/* Private to libpdk: error macros, aligned allocation, the context's insides.
 *
 * Error convention: a fallible function returns int (0 = success). PDK_CHECK records a
 * message in the context and returns; PDK_CHECK_GOTO and PDK_CALL_GOTO set `err` and jump to the
 * function's single `cleanup:` label, for functions that own memory. Inside OpenMP regions record
 * failure in a private flag, reduce it, and check after the region.
 */
#ifndef PDK_IMPL_H
#define PDK_IMPL_H

#include <stdarg.h>
#include <stdlib.h>

#include "pdk/ctx.h"
#include "pdk/particles.h"

#define PDK_ERRMSG_MAX 2048

struct pdk_pmb_consts;  /* kernels/kernels.h */
struct pdk_lps_consts;
struct pdk_bond_arrays;
struct pdk_sell_arrays;
struct pdk_stencil_arrays;

/* Kernel-variant table: one function pointer per kernel kind, filled at context creation from the
 * CPU's features (or the user's forced choice). Later issues add kinds; callers never branch on
 * variants themselves. */
struct pdk_corr_consts; /* kernels/kernels.h */
struct pdk_corr_arrays;
struct pdk_galerkin_consts;
struct pdk_galerkin_arrays;

typedef struct pdk_kernel_table {
  const char *name; /* "ref" or "simd" */
  /* Family build, candidate scan (kernels/ref/family_scan.c and variants). */
  pdk_index (*family_scan2)(pdk_index n_cand, const double *restrict cx, const double *restrict cy,
                            double xi, double yi, double r2max, pdk_index self,
                            const pdk_index *restrict cand_id, pdk_index *restrict out);
  pdk_index (*family_scan3)(pdk_index n_cand, const double *restrict cx, const double *restrict cy,
                            const double *restrict cz, double xi, double yi, double zi,
                            double r2max, pdk_index self, const pdk_index *restrict cand_id,
                            pdk_index *restrict out);
  /* Correspondence, total Lagrangian (kernels/ref/corr.c and variants): shape, pass 1, pass 2;
   * corr_opt = 1 when they are optimized variants (they then need the B, G pass-2 arrays in
   * double storage: pdk_corr_pair_layout). */
  pdk_index (*corr_shape)(const struct pdk_corr_consts *k, const struct pdk_corr_arrays *a,
                          pdk_index i0, pdk_index i1);
  void (*corr_pass1)(const struct pdk_corr_consts *k, const struct pdk_corr_arrays *a,
                     pdk_index i0, pdk_index i1);
  void (*corr_pass2)(const struct pdk_corr_consts *k, const struct pdk_corr_arrays *a,
                     pdk_index i0, pdk_index i1);
  int corr_opt;
  /* PMB force and LPS dilation / force passes (kernels/ref/pmb.c, lps.c and variants; arrays and
   * contract in kernels/kernels.h). bond_rows = 1: the entries read the packed rows ref4/cur4,
   * which the drivers then fill; 0: they read the SoA arrays only. */
  int bond_rows;
  pdk_bond_index (*pmb_force)(const struct pdk_pmb_consts *k, const struct pdk_bond_arrays *a,
                       pdk_index i0, pdk_index i1);
  void (*lps_dilation)(const struct pdk_lps_consts *k, const struct pdk_bond_arrays *a,
                       pdk_index i0, pdk_index i1);
  pdk_bond_index (*lps_force)(const struct pdk_lps_consts *k, const struct pdk_bond_arrays *a,
                       pdk_index i0, pdk_index i1);
  /* PMB force and LPS passes over the sliced layout (model layout sell; kernels/ref/bond_sell.c and
   * variants), over slices of sell_width rows: the SIMD lanes (4 AVX2, 8 AVX-512; the reference
   * takes any width and uses 8). It reads the packed rows when bond_rows = 1. */
  int sell_width;
  pdk_bond_index (*pmb_force_sell)(const struct pdk_pmb_consts *k,
                                   const struct pdk_bond_arrays *a,
                                   const struct pdk_sell_arrays *s, int64_t s0, int64_t s1);
  void (*lps_dilation_sell)(const struct pdk_lps_consts *k, const struct pdk_bond_arrays *a,
                            const struct pdk_sell_arrays *s, int64_t s0, int64_t s1);
  pdk_bond_index (*lps_force_sell)(const struct pdk_lps_consts *k,
                                   const struct pdk_bond_arrays *a,
                                   const struct pdk_sell_arrays *s, int64_t s0, int64_t s1);
  /* PMB force pass in the stencil layout (kernels/opt/pmb_stencil.h), rows r0 .. r1-1. */
  pdk_bond_index (*pmb_stencil)(const struct pdk_pmb_consts *k,
                                const struct pdk_stencil_arrays *a, int64_t r0, int64_t r1);
  /* LPS dilation and force passes in the stencil layout (kernels/opt/lps_stencil.h). */
  void (*lps_stencil_dilation)(const struct pdk_lps_consts *k,
                               const struct pdk_stencil_arrays *a, int64_t r0, int64_t r1);
  pdk_bond_index (*lps_stencil_force)(const struct pdk_lps_consts *k,
                                      const struct pdk_stencil_arrays *a, int64_t r0, int64_t r1);
  /* Correspondence passes 1 and 2 in the stencil layout (kernels/opt/corr_stencil.h). */
  void (*corr_stencil_pass1)(const struct pdk_corr_consts *k, const struct pdk_corr_arrays *c,
                             const struct pdk_stencil_arrays *a, int64_t r0, int64_t r1);
  void (*corr_stencil_pass2)(const struct pdk_corr_consts *k, const struct pdk_corr_arrays *c,
                             const struct pdk_stencil_arrays *a, int64_t r0, int64_t r1);
  /* Peridynamic Galerkin (kernels/ref/galerkin.c; the reference in every family for now). */
  pdk_index (*galerkin_shape)(const struct pdk_galerkin_consts *k,
                              const struct pdk_galerkin_arrays *a, pdk_index k0, pdk_index k1);
  pdk_index (*galerkin_psi)(const struct pdk_galerkin_consts *k,
                            const struct pdk_galerkin_arrays *a, double *psi, pdk_index k0,
                            pdk_index k1);
  pdk_index (*galerkin_pass1)(const struct pdk_galerkin_consts *k,
                              const struct pdk_galerkin_arrays *a, int unit, pdk_index k0,
                              pdk_index k1);
  void (*galerkin_pass2)(const struct pdk_galerkin_consts *k, const struct pdk_galerkin_arrays *a,
                         int area, pdk_index i0, pdk_index i1);
} pdk_kernel_table;

struct pdk_ctx {
  int num_threads;
  int max_threads;   /* hardware threads the process may use */
  pdk_bind bind;
  int bind_errno;    /* errno of the last failed hwloc_set_cpubind (0: none failed) */
  unsigned isa;
  pdk_kernel_table kernels;
  void *topology;    /* hwloc_topology_t, owned */
  void *caller_cpuset; /* hwloc_bitmap_t: the creating thread's binding, restored on destroy */
  int num_bound;     /* OpenMP threads 0..num_bound-1 were bound to cores (restored on destroy) */
  int num_cores;
  int error_code;
  char error[PDK_ERRMSG_MAX];
};

/* Selects the kernel table by name ("ref", "simd") or, for NULL, the best for `isa`. */
int pdk_kernels_select(const char *name, unsigned isa, pdk_kernel_table *out);

/* Binds the calling OpenMP thread `tid` to a core per the policy (no-op for NONE). Binding is
 * best effort (a container may forbid it): a failure is recorded in bind_errno through the hwloc
 * wrapper convention and reported by pdk_ctx_print_info, never fatal. */
void pdk_ctx_bind_thread(pdk_ctx *ctx, int tid);

#define PDK_CHECK(cond, ctx, code, ...)                                                         \
  do {                                                                                          \
    if (!(cond)) return pdk_ctx_error_set((ctx), (code), __func__, __VA_ARGS__);                \
  } while (0)

/* A pointer argument of a public function that must not be NULL (a handle, an out pointer):
 * PDK_ERR_ARG, with a message in ctx when there is one (ctx may be NULL). */
#define PDK_CHECK_ARG(ptr, ctx)                                                                 \
  PDK_CHECK((ptr) != NULL, (ctx), PDK_ERR_ARG, "argument '%s' is NULL", #ptr)

#define PDK_CALL(expr)                                                                          \
  do {                                                                                          \
    int pdk_call_err_ = (expr);                                                                 \
    if (pdk_call_err_) return pdk_call_err_;                                                    \
  } while (0)

#define PDK_CHECK_GOTO(cond, ctx, code, ...)                                                    \
  do {                                                                                          \
    if (!(cond)) {                                                                              \
      err = pdk_ctx_error_set((ctx), (code), __func__, __VA_ARGS__);                            \
      goto cleanup;                                                                             \
    }                                                                                           \
  } while (0)

#define PDK_CALL_GOTO(expr)                                                                     \
  do {                                                                                          \
    err = (expr);                                                                               \
    if (err) goto cleanup;                                                                      \
  } while (0)

/* 64-byte aligned allocation of `count` elements of `size` bytes; NULL on overflow or failure.
 * Memory is zeroed. Free with pdk_free_aligned. */
void *pdk_alloc_aligned(size_t count, size_t size);
void pdk_free_aligned(void *ptr);

static inline pdk_index pdk_pad_count(pdk_index n) {
  return (pdk_index)(((int64_t)n + PDK_PAD - 1) / PDK_PAD * PDK_PAD);
}

#endif
