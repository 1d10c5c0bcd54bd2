/* 2-D PMB and the out-of-plane thickness. 2-D particle volumes are area x thickness t, so the sum
 * over a family carries a factor t, and the plane-strain micromodulus must be divided by it
 * (c = 72 K / (5 pi delta^3 t)); before that, a plate of thickness 2.5 was 2.5 times too stiff.
 * Asserts, for t = 1, 2.5 and 0.01 (opts.thickness = the lattice's):
 *   - force and energy densities under an isotropic stretch s = 1e-3 equal those of t = 1 to
 *     1e-12 relative (they are intensive: only the rounding of V_j = area x t may differ);
 *   - the energy density of the centre particle equals the lattice sum written here,
 *     W = sum over offsets xi (|xi| <= delta) of c s^2 |xi| beta (1 x 1 x t) / 4 with
 *     c = 72 K / (5 pi delta^3 t), to 1e-12 relative (round-off of ~28 terms); the sum is also
 *     printed against the continuum 2 (lambda + mu) s^2 = 12/5 K s^2 it approximates.
 * (t060 checks that a scene's geometry.thickness reaches the model options.)
 * labels: unit physics */
#include "bond_models_test.h"
#include "models/model_bond.h"

/* sum over square-lattice offsets within delta (the families' rule) of c s^2 r0 beta V / 4, with
 * V = t and c = 72 K / (5 pi delta^3 t): t cancels, so it is written for t = 1. beta is LAMMPS's
 * partial-volume factor for lattice constant 1: min(1, (delta + 1/2 - r0)). */
static double lattice_energy(double K, double s, double delta) {
  const double c = 72.0 * K / (5.0 * M_PI * delta * delta * delta);
  double W = 0;
  for (int a = -4; a <= 4; ++a)
    for (int b = -4; b <= 4; ++b) {
      const double r0 = sqrt((double)(a * a + b * b));
      if ((a == 0 && b == 0) || r0 * r0 > delta * delta * (1 + 1e-12)) continue;
      W += c * s * s * r0 * fmin(1.0, delta + 0.5 - r0) / 4.0;
    }
  return W;
}

static void run(pdk_ctx *ctx, double t, double *f, double *W, pdk_index *n_out, pdk_index *centre) {
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.hi[0] = lo.hi[1] = 15.0;
  lo.spacing = 1.0;
  lo.thickness = t;
  pdk_particles *p = NULL;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, &p));
  pdk_families *fam = bm_families(ctx, p, 3.015);
  pdk_model_opts o = pdk_model_opts_default();
  o.kind = PDK_MODEL_PMB;
  o.bulk_modulus = 5.0;
  o.density = 1.0;
  o.lattice_constant = 1.0;
  o.thickness = t;
  pdk_model *m = NULL;
  T_OK(ctx, pdk_model_create(p, fam, &o, &m));
  const double F[4] = {1.001, 0, 0, 1.001}, shift[2] = {0, 0};
  bm_displace_affine(p, F, shift);
  double e;
  T_OK(ctx, pdk_model_force(m, &e));
  const pdk_index n = pdk_particles_count(p);
  for (int c = 0; c < 2; ++c)
    memcpy(f + c * n, pdk_particles_field_data(p, "f", c), (size_t)n * sizeof(double));
  memcpy(W, pdk_model_pmb_energy_density(m), (size_t)n * sizeof(double));
  *n_out = n;
  for (pdk_index i = 0; i < n; ++i) /* the particle at (7.5, 7.5) */
    if (fabs(pdk_particles_X(p, 0)[i] - 7.5) < 1e-9 && fabs(pdk_particles_X(p, 1)[i] - 7.5) < 1e-9)
      *centre = i;
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  static double f1[2 * 225], W1[225], ft[2 * 225], Wt[225];
  pdk_index n, centre = -1;
  run(ctx, 1.0, f1, W1, &n, &centre);
  T_ASSERT(n == 225 && centre >= 0, "15 x 15 plate with a centre particle (n %d)", (int)n);
  const double K = 5.0, s = 1e-3, W_cont = 12.0 / 5.0 * K * s * s;
  const double delta = 3.015, lattice_sum = lattice_energy(K, s, delta);
  T_INFO("centre W = %.6e, lattice sum %.6e, continuum %.6e (ratio %.4f)\n", W1[centre],
         lattice_sum, W_cont, lattice_sum / W_cont);
  T_NEAR(W1[centre], lattice_sum, 1e-12, 0, "t = 1: centre energy density vs the lattice sum");
  double fmax = 0;
  for (pdk_index i = 0; i < 2 * n; ++i) fmax = fmax > fabs(f1[i]) ? fmax : fabs(f1[i]);
  T_ASSERT(fmax > 0, "the stretch gives forces at the edges");
  const double ts[2] = {2.5, 0.01};
  for (int k = 0; k < 2; ++k) {
    run(ctx, ts[k], ft, Wt, &n, &centre);
    T_NEAR(Wt[centre], lattice_sum, 1e-12, 0, "t = %g: centre energy density vs the lattice sum",
           ts[k]);
    for (pdk_index i = 0; i < 2 * n; ++i)
      T_NEAR(ft[i], f1[i], 0, 1e-12 * fmax, "thickness %g: force entry %d", ts[k], (int)i);
    for (pdk_index i = 0; i < n; ++i)
      T_NEAR(Wt[i], W1[i], 1e-12, 0, "thickness %g: energy density of particle %d", ts[k], (int)i);
  }
  pdk_ctx_destroy(&ctx);
  return 0;
}
