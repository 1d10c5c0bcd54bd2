/* Particle store: built-in fields, alignment and padding, field registry, memory report.
 * labels: unit */
#include "test_util.h"

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  pdk_particles *p = NULL;
  for (int dim = 2; dim <= 3; ++dim) {
    for (pdk_index n = 1; n <= 17; ++n) {
      T_OK(ctx, pdk_particles_create(ctx, dim, n, &p));
      T_ASSERT(pdk_particles_count(p) == n && pdk_particles_dim(p) == dim, "n %d dim %d", (int)n, dim);
      pdk_index np = pdk_particles_count_padded(p);
      T_ASSERT(np % PDK_PAD == 0 && np >= n && np - n < PDK_PAD, "padding of %d is %d", (int)n, (int)np);
      /* Built-in fields exist; a 2-D store has no third coordinate. */
      T_ASSERT(pdk_particles_field_exists(p, "id") && pdk_particles_field_exists(p, "X") &&
               pdk_particles_field_exists(p, "volume"), "built-ins");
      T_ASSERT((pdk_particles_X(p, 2) != NULL) == (dim == 3), "z exists only in 3-D");
      int64_t *id = pdk_particles_id(p);
      for (pdk_index i = 0; i < n; ++i) T_ASSERT(id[i] == i, "id %d", (int)i);
      for (int c = 0; c < dim; ++c) {
        double *x = pdk_particles_X(p, c);
        T_ASSERT(((uintptr_t)x % PDK_ALIGN) == 0, "X[%d] aligned", c);
        for (pdk_index i = 0; i < np; ++i) T_ASSERT(x[i] == 0.0, "zero start");
      }
      pdk_particles_destroy(&p);
      T_ASSERT(p == NULL, "destroy clears");
    }
  }

  T_OK(ctx, pdk_particles_create(ctx, 3, 100, &p));
  /* A field exists only once declared. */
  T_ASSERT(!pdk_particles_field_exists(p, "plastic_strain"), "undeclared field absent");
  void *ptr = (void *)1;
  T_FAILS(ctx, pdk_particles_field_get(p, "plastic_strain", 0, &ptr), PDK_ERR_NOT_FOUND, "plastic_strain");
  T_ASSERT(ptr == NULL, "out cleared on failure");
  T_ASSERT(pdk_particles_field_bytes(p, "plastic_strain") == 0, "absent field holds no memory");
  size_t before = pdk_particles_memory_bytes(p);

  T_OK(ctx, pdk_particles_field_add(p, "F", PDK_F64, 9));
  T_OK(ctx, pdk_particles_field_add(p, "theta", PDK_F32, 1));
  T_OK(ctx, pdk_particles_field_add(p, "F", PDK_F64, 9)); /* same shape: no-op */
  T_FAILS(ctx, pdk_particles_field_add(p, "F", PDK_F32, 9), PDK_ERR_ARG, "cannot redeclare");
  T_FAILS(ctx, pdk_particles_field_add(p, "G", PDK_F64, 10), PDK_ERR_ARG, "10 components");
  T_FAILS(ctx, pdk_particles_field_add(p, "", PDK_F64, 1), PDK_ERR_ARG, "field name");
  T_FAILS(ctx, pdk_particles_field_get(p, "F", 9, &ptr), PDK_ERR_ARG, "component 9");
  T_ASSERT(pdk_particles_field_exists(p, "F") && pdk_particles_field_exists(p, "theta"), "declared");

  /* Memory per field: components x padded count x element size. */
  pdk_index np = pdk_particles_count_padded(p);
  T_ASSERT(pdk_particles_field_bytes(p, "F") == 9u * (size_t)np * 8u, "F bytes");
  T_ASSERT(pdk_particles_field_bytes(p, "theta") == (size_t)np * 4u, "theta bytes");
  T_ASSERT(pdk_particles_memory_bytes(p) == before + 9u * (size_t)np * 8u + (size_t)np * 4u, "total");
  pdk_type type;
  int nc;
  T_OK(ctx, pdk_particles_field_info(p, "theta", &type, &nc));
  T_ASSERT(type == PDK_F32 && nc == 1, "info");

  /* The memory report lists every field and the total. */
  char *buf = NULL;
  size_t len = 0;
  FILE *mem = open_memstream(&buf, &len);
  pdk_particles_print_memory(p, mem);
  fclose(mem);
  T_ASSERT(strstr(buf, "theta") && strstr(buf, "F ") && strstr(buf, "total"), "report: %s", buf);
  free(buf);

  T_OK(ctx, pdk_particles_field_remove(p, "theta"));
  T_ASSERT(!pdk_particles_field_exists(p, "theta") && pdk_particles_field_exists(p, "F"), "removed one");
  T_FAILS(ctx, pdk_particles_field_remove(p, "X"), PDK_ERR_ARG, "built in");
  T_FAILS(ctx, pdk_particles_field_remove(p, "theta"), PDK_ERR_NOT_FOUND, "theta");

  /* Non-finite coordinates are named by particle. */
  pdk_particles_X(p, 1)[42] = NAN;
  T_FAILS(ctx, pdk_particles_check_finite(p), PDK_ERR_NUMERIC, "particle 42");
  pdk_particles_X(p, 1)[42] = INFINITY;
  T_FAILS(ctx, pdk_particles_check_finite(p), PDK_ERR_NUMERIC, "X[1] = inf");
  pdk_particles_destroy(&p);

  /* Bad sizes. */
  T_FAILS(ctx, pdk_particles_create(ctx, 3, 0, &p), PDK_ERR_ARG, "at least one particle");
  T_FAILS(ctx, pdk_particles_create(ctx, 4, 10, &p), PDK_ERR_ARG, "dimension must be 2 or 3, got 4");
  T_ASSERT(p == NULL, "no store on failure");
  pdk_ctx_destroy(&ctx);
  return 0;
}
