/* Stability at the extremes: float storage (opts.precision = float).
 *   - correspondence (TL and UL) refuses it: PDK_ERR_UNSUPPORTED, the message names float storage
 *     and says to use precision double;
 *   - PMB and LPS accept it (docs/scenes.md: "storage precision of per-bond data"), but nothing in
 *     their drivers stores anything in float: a body far from the origin (X ~ 1e4 spacings, where
 *     float resolution of the coordinates is ~1e-3 spacing) under a displacement of 1e-6 spacing
 *     (far below float resolution relative to the coordinates, so float storage of positions or
 *     bond vectors would be dominated by round-off) gives forces bitwise equal to double. Asserted
 *     as found; gap (reported): the option is silently ignored instead of refused or honoured.
 * labels: physics extreme */
#include "extreme_util.h"

static void forces(pdk_ctx *ctx, int kind, int precision, double *out, pdk_index *n_out) {
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.spacing = 1.0;
  lo.lo[0] = lo.lo[1] = 1e4;
  lo.hi[0] = lo.hi[1] = 1e4 + 10;
  pdk_particles *p;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, &p));
  pdk_families *fam = cu_families(ctx, p, 3.015);
  pdk_model_opts o = cu_opts(PDK_LAW_LINEAR_ELASTIC, 0, 0, 0);
  o.kind = (pdk_model_kind)kind;
  o.precision = (pdk_precision)precision;
  pdk_model *m = cu_model(ctx, p, fam, &o);
  const pdk_index n = pdk_particles_count(p);
  double *x = cu_field(p, "x", 0);
  for (pdk_index i = 0; i < n; ++i) x[i] += 1e-6 * (pdk_particles_X(p, 0)[i] - 1e4);
  T_OK(ctx, pdk_model_force_trial(m, NULL));
  memcpy(out, cu_field(p, "f", 0), (size_t)n * sizeof(double));
  *n_out = n;
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  for (int ul = 0; ul <= 1; ++ul) {
    pdk_particles *p = cu_lattice(ctx, 2, 6, 0.0, 1);
    pdk_families *fam = cu_families(ctx, p, 2.015);
    pdk_model_opts o = cu_opts(PDK_LAW_NEO_HOOKE, 0, 0, 0);
    o.precision = PDK_PRECISION_FLOAT;
    if (ul) o.connectivity = PDK_CONNECTIVITY_UL;
    pdk_model *m = NULL;
    T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_UNSUPPORTED, "float storage");
    T_ASSERT(strstr(pdk_ctx_error_message(ctx), "precision double"), "no fix in '%s'", pdk_ctx_error_message(ctx));
    T_ASSERT(m == NULL, "no model on refusal");
    pdk_families_destroy(&fam);
    pdk_particles_destroy(&p);
  }
  static double fd[200], ff[200];
  for (int kind = PDK_MODEL_PMB; kind <= PDK_MODEL_LPS; ++kind) {
    pdk_index n, n2;
    forces(ctx, kind, PDK_PRECISION_DOUBLE, fd, &n);
    pdk_ctx_error_clear(ctx);
    forces(ctx, kind, PDK_PRECISION_FLOAT, ff, &n2);
    T_ASSERT(n == n2 && n <= 200, "same body");
    double fmax = 0;
    int same = 1;
    for (pdk_index i = 0; i < n; ++i) {
      fmax = fmax > fabs(fd[i]) ? fmax : fabs(fd[i]);
      if (memcmp(&fd[i], &ff[i], sizeof(double))) same = 0;
    }
    T_ASSERT(fmax > 0 && isfinite(fmax), "%s: forces of the 1e-6 stretch %g", pdk_model_kind_name(kind), fmax);
    if (ex_verbose())
      printf("%s: float storage accepted, forces %s double's (max |f| %g)\n", pdk_model_kind_name(kind),
             same ? "bitwise equal to" : "differ from", fmax);
    /* Found: float is ignored. If float storage gets implemented, this must be replaced by a
     * round-off-domination check (the 1e-6 stretch is below float resolution at X ~ 1e4). */
    T_ASSERT(same, "%s: float storage now changes the forces: replace this check by a round-off check",
             pdk_model_kind_name(kind));
  }
  pdk_ctx_destroy(&ctx);
  return 0;
}
