/* Context: creation options, thread count, kernel table choice, error recording.
 * labels: unit */
#include "core/pdk_impl.h"
#include "test_util.h"

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  T_ASSERT(pdk_ctx_num_threads(ctx) == 1, "explicit thread count kept");
  T_ASSERT(pdk_ctx_error_code(ctx) == 0 && pdk_ctx_error_message(ctx)[0] == '\0', "fresh context has no error");

  /* PDK_CHECK records code, message and the function name. */
  int err = pdk_ctx_error_set(ctx, PDK_ERR_ARG, "somewhere", "horizon must be > 0, got %g", -1.0);
  T_ASSERT(err == PDK_ERR_ARG, "error_set returns its code");
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "horizon must be > 0, got -1") != NULL, "message kept");
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "somewhere") != NULL, "function named");
  pdk_ctx_error_clear(ctx);
  T_ASSERT(pdk_ctx_error_message(ctx)[0] == '\0', "cleared");

  T_FAILS(ctx, pdk_ctx_set_num_threads(ctx, 0), PDK_ERR_ARG, "thread count 0");
  T_OK(ctx, pdk_ctx_set_num_threads(ctx, 2));
  T_ASSERT(pdk_ctx_num_threads(ctx) == 2, "set_num_threads");
  pdk_ctx_destroy(&ctx);
  T_ASSERT(ctx == NULL, "destroy sets NULL");
  pdk_ctx_destroy(&ctx); /* NULL accepted */

  /* Forced kernel family and a bad one. */
  pdk_ctx_opts o = pdk_ctx_opts_default();
  o.kernels = "ref";
  char why[512];
  T_ASSERT(pdk_ctx_create(&o, &ctx, why, sizeof why) == 0, "%s", why);
  T_ASSERT(!strcmp(pdk_ctx_kernels_name(ctx), "ref"), "forced ref, got %s", pdk_ctx_kernels_name(ctx));
  pdk_ctx_destroy(&ctx);
  o.kernels = "fastest";
  T_ASSERT(pdk_ctx_create(&o, &ctx, why, sizeof why) == PDK_ERR_ARG && ctx == NULL, "bad kernel name refused");
  T_ASSERT(strstr(why, "fastest") && strstr(why, "'ref' or 'simd'"), "message names value and choices: %s", why);

  /* Environment overrides: PDK_BIND and PDK_NUM_THREADS, with clear refusals. */
  setenv("PDK_BIND", "sometimes", 1);
  T_ASSERT(pdk_ctx_create(NULL, &ctx, why, sizeof why) == PDK_ERR_ARG, "bad PDK_BIND refused");
  T_ASSERT(strstr(why, "sometimes") && strstr(why, "'core' or 'none'"), "%s", why);
  setenv("PDK_BIND", "none", 1);
  setenv("PDK_NUM_THREADS", "2", 1);
  T_ASSERT(pdk_ctx_create(NULL, &ctx, why, sizeof why) == 0, "%s", why);
  T_ASSERT(pdk_ctx_bind_policy(ctx) == PDK_BIND_NONE, "PDK_BIND=none honoured");
  T_ASSERT(pdk_ctx_num_threads(ctx) == 2, "PDK_NUM_THREADS honoured");
  pdk_ctx_destroy(&ctx);
  setenv("PDK_NUM_THREADS", "two", 1);
  T_ASSERT(pdk_ctx_create(NULL, &ctx, why, sizeof why) == PDK_ERR_ARG && strstr(why, "two"), "%s", why);
  unsetenv("PDK_NUM_THREADS");
  unsetenv("PDK_BIND");

  /* Aligned allocation is aligned and zeroed; overflow gives NULL. */
  double *a = pdk_alloc_aligned(13, sizeof(double));
  T_ASSERT(a && ((uintptr_t)a % PDK_ALIGN) == 0, "64-byte aligned");
  for (int i = 0; i < 13; ++i) T_ASSERT(a[i] == 0.0, "zeroed");
  pdk_free_aligned(a);
  T_ASSERT(pdk_alloc_aligned(SIZE_MAX / 4, 8) == NULL, "overflow detected");
  return 0;
}
