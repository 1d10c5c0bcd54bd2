/* pdk context: threads, binding, CPU features, kernel-variant table, last error.
 *
 * Every stateful pdk object is created from a context and reports its errors into it. Functions
 * that can fail return an int status (PDK_SUCCESS == 0); the message of the last failure is kept
 * in the context (pdk_ctx_error_message) and names what was wrong, where and how to fix it.
 * There are no globals: two contexts are independent.
 *
 * NULL arguments: every public function takes NULL for a handle or pointer without crashing. One
 * that returns a status returns PDK_ERR_ARG, with a message naming the argument in the context
 * when one is at hand (the ctx argument or the context of another handle); destroy and close
 * functions do nothing; getters return 0, NULL, "" or NaN (pdk_model_float_stretch_ratio: -1).
 * Optional pointers (documented as such, e.g. out-counts and opts that default) stay optional.
 */
#ifndef PDK_CTX_H
#define PDK_CTX_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "pdk/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Index of a particle: 32-bit signed (bond_j is int32, so a store holds < 2^31 particles). */
typedef int32_t pdk_index;
/* Count or offset of bonds: 64-bit (bond_start). */
typedef int64_t pdk_bond_index;

typedef enum pdk_status {
  PDK_SUCCESS = 0,
  PDK_ERR_ARG = 1,         /* an argument or input value is out of range or inconsistent */
  PDK_ERR_MEMORY = 2,      /* allocation failed or a size would overflow */
  PDK_ERR_IO = 3,          /* file could not be read or written */
  PDK_ERR_EXTERNAL = 4,    /* a dependency (HDF5, hwloc, SuiteSparse, libcyaml) failed */
  PDK_ERR_NUMERIC = 5,     /* non-finite or singular numbers */
  PDK_ERR_UNSUPPORTED = 6, /* a valid request this build or this CPU cannot serve */
  PDK_ERR_NOT_FOUND = 7    /* a named field, set or variant does not exist */
} pdk_status;

/* Thread binding policy (hwloc). */
typedef enum pdk_bind {
  PDK_BIND_CORE = 0, /* one thread per physical core, bound to it (default) */
  PDK_BIND_NONE = 1  /* leave placement to the OS */
} pdk_bind;

/* CPU features detected at run time; bit flags. */
enum {
  PDK_ISA_AVX2 = 1u << 0,    /* AVX2 + FMA */
  PDK_ISA_AVX512 = 1u << 1   /* AVX-512 F, VL, DQ, BW */
};

typedef struct pdk_ctx_opts {
  int num_threads;     /* 0: from the environment, PDK_NUM_THREADS, else the first entry of
                          OMP_NUM_THREADS, else one per core (hwloc) capped at the OpenMP
                          maximum */
  pdk_bind bind;       /* env PDK_BIND=core|none overrides the default, not an explicit option */
  int bind_explicit;   /* 1: `bind` was set by the caller and wins over the environment */
  const char *kernels; /* force a kernel variant family by name ("ref", "simd", or "avx2",
                          "avx512": simd limited to that ISA); NULL: best for the CPU; env
                          PDK_KERNELS */
} pdk_ctx_opts;

typedef struct pdk_ctx pdk_ctx;

PDK_EXPORT pdk_ctx_opts pdk_ctx_opts_default(void);

/* Creates a context. On failure *out is NULL and, if err_buf is not NULL, the reason is written
 * to err_buf (there is no context yet to hold it). With PDK_BIND_CORE the OpenMP threads pdk uses
 * are bound to cores, the calling thread (OpenMP's thread 0) included; HDF5's automatic error
 * printing is off while any context exists (pdk reports HDF5 failures in its own messages).
 * pdk_ctx_destroy gives both back: the threads it bound return to the calling thread's binding
 * at creation, and the last context destroyed restores the HDF5 error handler it found. */
PDK_EXPORT int pdk_ctx_create(const pdk_ctx_opts *opts, pdk_ctx **out, char *err_buf,
                              size_t err_len);
PDK_EXPORT void pdk_ctx_destroy(pdk_ctx **ctx);

PDK_EXPORT int pdk_ctx_num_threads(const pdk_ctx *ctx);
/* Changes the thread count used by later calls (1 .. number of hardware threads). */
PDK_EXPORT int pdk_ctx_set_num_threads(pdk_ctx *ctx, int num_threads);
PDK_EXPORT pdk_bind pdk_ctx_bind_policy(const pdk_ctx *ctx);
/* PDK_ISA_* bits that this CPU has and pdk may use */
PDK_EXPORT unsigned pdk_ctx_isa(const pdk_ctx *ctx);
/* "ref", "simd", "avx2" or "avx512" */
PDK_EXPORT const char *pdk_ctx_kernels_name(const pdk_ctx *ctx);

/* Last error. The message is empty when nothing failed since the last clear. */
PDK_EXPORT const char *pdk_ctx_error_message(const pdk_ctx *ctx);
PDK_EXPORT int pdk_ctx_error_code(const pdk_ctx *ctx);
PDK_EXPORT void pdk_ctx_error_clear(pdk_ctx *ctx);

/* Records an error in the context and returns `code`. `where` is the function name. Used by
 * drivers through PDK_CHECK; public so applications built on pdk can report into the same place. */
PDK_EXPORT int pdk_ctx_error_set(pdk_ctx *ctx, int code, const char *where, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* Prints version, build flags, SIMD features, hwloc topology and thread binding. */
PDK_EXPORT int pdk_ctx_print_info(pdk_ctx *ctx, FILE *out);

/* Peak resident memory of this process in bytes (0 if unknown). */
PDK_EXPORT size_t pdk_peak_memory_bytes(void);
/* Monotonic wall clock in seconds. */
PDK_EXPORT double pdk_wtime(void);

PDK_EXPORT const char *pdk_status_name(int code);

#ifdef __cplusplus
}
#endif
#endif
