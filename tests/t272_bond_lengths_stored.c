/* Stored bond lengths (pdk_model_opts.bond_lengths, scene key model.bond_lengths): PMB and LPS on
 * the general (csr) path with each reference length |X_j - X_i| stored per bond (the default) and
 * recomputed in every pass give the same bits.
 *
 * Bodies: a jittered 9 x 8 x 7 cube and a 23 x 19 plate (horizon 3.015 spacings, partial volumes
 * on, volumes with noise), kernel families ref, avx2 and avx512 as far as this CPU runs them, 1 and
 * 2 threads, bond breaking on (critical stretch 0.004): a trial pass, four committing passes at
 * growing random displacements that break bonds, and a trial pass.
 *
 * What must hold, and why:
 *   - after every pass, f, the strain energy, the bond state, the number broken and (LPS) the
 *     dilation have the bits of the computed run: the stored length is computed once with the
 *     operations and order of the force kernels (pdk_kernel_bond_lengths_ref), so each bond's r0,
 *     and therefore every term and every sum, is the same;
 *   - some but not all bonds break (otherwise the failure path would be untested);
 *   - an unknown bond_lengths value is refused with PDK_ERR_ARG.
 * The kernel-level check (every SIMD variant with and without bond_r0d, bit for bit) is t026.
 * labels: unit threads */
#include <stdint.h>

#include "bond_models_test.h"

typedef struct result {
  double *f[3], *w, *theta, energy[6];
  uint8_t *alive;
  pdk_bond_index nb, broken[6];
  pdk_index n;
} result;

static result run(const char *kernels, int threads, int dim, pdk_model_kind kind,
                  pdk_bond_lengths bl) {
  pdk_ctx_opts co = pdk_ctx_opts_default();
  co.num_threads = threads;
  co.kernels = kernels;
  char why[512];
  pdk_ctx *ctx = NULL;
  if (pdk_ctx_create(&co, &ctx, why, sizeof why)) T_FAIL("pdk_ctx_create: %s", why);
  pdk_particles *p = bm_body(ctx, dim, dim == 3 ? 9 : 23, dim == 3 ? 8 : 19, dim == 3 ? 7 : 1,
                             1.0, 0.1, 0.2, 31);
  pdk_families *fam = bm_families(ctx, p, 3.015);
  pdk_model_opts o = pdk_model_opts_default();
  o.kind = kind;
  o.bulk_modulus = 2.0;
  o.shear_modulus = 0.9;
  o.density = 1.0;
  o.critical_stretch = 0.004;
  o.alpha = 0.25;
  o.lattice_constant = 1.0;
  o.bond_lengths = bl;
  pdk_model *m = NULL;
  T_OK(ctx, pdk_model_create(p, fam, &o, &m));
  result r;
  memset(&r, 0, sizeof r);
  r.n = pdk_particles_count(p);
  r.nb = pdk_families_num_bonds(fam);
  for (int pass = 0; pass < 6; ++pass) {
    bm_displace_random(p, 0.0015 * (pass + 1), 500 + (uint64_t)pass);
    if (pass == 0 || pass == 5)
      T_OK(ctx, pdk_model_force_trial(m, &r.energy[pass]));
    else
      T_OK(ctx, pdk_model_force(m, &r.energy[pass]));
    r.broken[pass] = pdk_model_num_broken(m);
  }
  for (int c = 0; c < dim; ++c) {
    r.f[c] = malloc((size_t)r.n * sizeof(double));
    memcpy(r.f[c], pdk_particles_field_data(p, "f", c), (size_t)r.n * sizeof(double));
  }
  r.alive = malloc((size_t)r.nb);
  memcpy(r.alive, pdk_model_bond_alive(m), (size_t)r.nb);
  if (kind == PDK_MODEL_LPS) {
    const double *th = pdk_particles_field_data(p, "theta", 0);
    T_ASSERT(th, "lps: no field theta");
    r.theta = malloc((size_t)r.n * sizeof(double));
    memcpy(r.theta, th, (size_t)r.n * sizeof(double));
  }
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  return r;
}

static void free_result(result *r) {
  for (int c = 0; c < 3; ++c) free(r->f[c]);
  free(r->theta);
  free(r->alive);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  const unsigned isa = t_isa(ctx);
  /* the refusal of an unknown value */
  {
    pdk_particles *p = bm_body(ctx, 2, 6, 6, 1, 1.0, 0.0, 0.0, 1);
    pdk_families *fam = bm_families(ctx, p, 3.015);
    pdk_model_opts o = pdk_model_opts_default();
    o.bulk_modulus = 2.0, o.density = 1.0;
    o.bond_lengths = (pdk_bond_lengths)2;
    pdk_model *m = NULL;
    T_ASSERT(pdk_model_create(p, fam, &o, &m) == PDK_ERR_ARG && !m,
             "bond_lengths 2 was not refused");
    pdk_ctx_error_clear(ctx);
    pdk_families_destroy(&fam);
    pdk_particles_destroy(&p);
  }
  pdk_ctx_destroy(&ctx);
  const char *kern[] = {"ref", "avx2", "avx512"};
  const unsigned need[] = {0, PDK_ISA_AVX2, PDK_ISA_AVX512};
  int simd_ran = 0;
  for (int k = 0; k < 3; ++k) {
    if ((isa & need[k]) != need[k]) continue;
    simd_ran += k > 0;
    for (int dim = 2; dim <= 3; ++dim)
      for (int kind = PDK_MODEL_PMB; kind <= PDK_MODEL_LPS; ++kind)
        for (int threads = 1; threads <= 2; ++threads) {
          result s = run(kern[k], threads, dim, (pdk_model_kind)kind, PDK_BOND_LENGTHS_STORED);
          result c = run(kern[k], threads, dim, (pdk_model_kind)kind, PDK_BOND_LENGTHS_COMPUTED);
          const char *name = kind == PDK_MODEL_PMB ? "pmb" : "lps";
          T_ASSERT(c.broken[5] > 0 && c.broken[5] < c.nb,
                   "%s %s %d-D: %lld of %lld bonds broke; the test needs some but not all",
                   kern[k], name, dim, (long long)c.broken[5], (long long)c.nb);
          for (int pass = 0; pass < 6; ++pass) {
            T_ASSERT(memcmp(&s.energy[pass], &c.energy[pass], sizeof(double)) == 0,
                     "%s %s %d-D %d thr pass %d: energy %.17g stored, %.17g computed", kern[k],
                     name, dim, threads, pass, s.energy[pass], c.energy[pass]);
            T_ASSERT(s.broken[pass] == c.broken[pass], "%s %s %d-D pass %d: broken %lld vs %lld",
                     kern[k], name, dim, pass, (long long)s.broken[pass],
                     (long long)c.broken[pass]);
          }
          for (int d = 0; d < dim; ++d)
            T_ASSERT(memcmp(s.f[d], c.f[d], (size_t)s.n * sizeof(double)) == 0,
                     "%s %s %d-D %d thr: f[%d] differs between stored and computed", kern[k],
                     name, dim, threads, d);
          T_ASSERT(memcmp(s.alive, c.alive, (size_t)s.nb) == 0,
                   "%s %s %d-D %d thr: bond state differs", kern[k], name, dim, threads);
          if (s.theta)
            T_ASSERT(memcmp(s.theta, c.theta, (size_t)s.n * sizeof(double)) == 0,
                     "%s lps %d-D %d thr: theta differs", kern[k], dim, threads);
          free_result(&s), free_result(&c);
        }
  }
  if (!simd_ran)
    T_SKIP("t272: this CPU has neither AVX2 nor AVX-512, the only kernels that read the stored "
           "lengths (the ref part ran)");
  return 0;
}
