/* Stability at the extremes: horizon factors m = 1.01 and 6 on a square unit lattice (2-D).
 *   - m = 1.01: 4 neighbours at interior particles (the axis neighbours). Correspondence: K =
 *     2 V I spans the plane (also at edges, 3 neighbours, and corners, 2 orthogonal ones), so no
 *     particle is flagged, and F = F0 exactly at interior particles for x = F0 X;
 *   - m = 6: 112 neighbours at interior particles (lattice points with |k| <= 6, self excluded),
 *     families memory = 8 (n + 1) + 4 bonds bytes;
 *   - for both, PMB, LPS and correspondence under the affine stretch F0 = diag(1.01, 0.995):
 *     forces finite, zero (1e-12 of the largest) at interior particles whose whole family is
 *     interior (full point-symmetric family), and sum_i V_i f_i = 0 (round-off).
 * labels: physics extreme */
#include "extreme_util.h"

static void check(pdk_ctx *ctx, double m_factor, int N, int expect_family) {
  pdk_particles *p = cu_lattice(ctx, 2, N, 0.0, 1);
  pdk_families *fam = cu_families(ctx, p, m_factor);
  const pdk_bond_index *bs = pdk_families_bond_start(fam);
  const pdk_index n = pdk_particles_count(p);
  const int reach = cu_reach(m_factor);
  for (pdk_index i = 0; i < n; ++i)
    if (cu_inside(p, i, N, reach))
      T_ASSERT(bs[i + 1] - bs[i] == expect_family, "m %g: particle %d has %lld neighbours, expected %d",
               m_factor, (int)i, (long long)(bs[i + 1] - bs[i]), expect_family);
  T_ASSERT(pdk_families_memory_bytes(fam) == (size_t)(8 * (n + 1) + 4 * pdk_families_num_bonds(fam)),
           "m %g: memory %zu bytes", m_factor, pdk_families_memory_bytes(fam));
  for (int kind = PDK_MODEL_PMB; kind <= PDK_MODEL_CORRESPONDENCE; ++kind) {
    pdk_model_opts o = cu_opts(PDK_LAW_LINEAR_ELASTIC, 0, 0, 0);
    o.kind = (pdk_model_kind)kind;
    pdk_model *m = cu_model(ctx, p, fam, &o);
    const double F0[4] = {1.01, 0, 0, 0.995}, c[2] = {0, 0};
    cu_affine(p, F0, c);
    T_OK(ctx, pdk_model_force_trial(m, NULL));
    int bad;
    const double fmax = ex_max_force(p, &bad);
    const char *name = pdk_model_kind_name((pdk_model_kind)kind);
    T_ASSERT(!bad && fmax > 0, "m %g %s: forces %g", m_factor, name, fmax);
    double sum[2] = {0, 0};
    for (pdk_index i = 0; i < n; ++i)
      for (int a = 0; a < 2; ++a) {
        const double f = cu_field(p, "f", a)[i];
        sum[a] += pdk_particles_volume(p)[i] * f;
        if (cu_inside(p, i, N, 2 * reach))
          T_NEAR(f, 0, 0, 1e-12 * fmax, "m %g %s: interior force at particle %d", m_factor, name, (int)i);
      }
    T_NEAR(sum[0], 0, 0, 1e-12 * fmax * n, "m %g %s: momentum x", m_factor, name);
    T_NEAR(sum[1], 0, 0, 1e-12 * fmax * n, "m %g %s: momentum y", m_factor, name);
    if (kind == PDK_MODEL_CORRESPONDENCE) {
      T_ASSERT(pdk_model_num_flagged(m) == 0, "m %g: %d flagged", m_factor, (int)pdk_model_num_flagged(m));
      const double centre[2] = {N / 2.0, N / 2.0};
      const pdk_index i = ex_nearest(p, centre);
      for (int t = 0; t < 4; ++t) T_NEAR(cu_field(p, "F", t)[i], F0[t], 0, 1e-12, "m %g F[%d]", m_factor, t);
    }
    if (ex_verbose())
      printf("m %g %s: n %d bonds %lld memory %zu max|f| %g\n", m_factor, name, (int)n,
             (long long)pdk_families_num_bonds(fam), pdk_families_memory_bytes(fam), fmax);
    pdk_model_destroy(&m);
    cu_reset_x(p);
  }
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  check(ctx, 1.01, 10, 4);
  check(ctx, 6.0, 30, 112);
  pdk_ctx_destroy(&ctx);
  return 0;
}
