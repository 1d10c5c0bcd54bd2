/* Stability at the extremes: large homogeneous strain, SVK and neo-Hooke (correspondence, 2-D plane
 * strain, 12 x 12 unit lattice, delta 2.015, K = 2, G = 1: lambda = 4/3, mu = 1).
 * x = F0 X with F0 = diag(s, 1) for s = 3 (stretch), 0.3 (compression to 30%), and neo-Hooke also
 * under F0 = diag(0.1, 0.1) (J = 0.01). At an interior particle (full, point-symmetric family):
 *   - F = F0 exactly (round-off: 1e-12);
 *   - P = A K equals the closed form of the law (1e-10 relative to |P|, round-off);
 *   - forces and strain energy finite everywhere.
 * Known SVK behaviour asserted: uniaxial (lateral fixed) P11(s) = s (lambda + 2 mu)(s^2 - 1)/2 has
 * its largest compressive value at s = 1/sqrt(3) and softens beyond: |P11(0.3)| < |P11(0.577)|,
 * and the model reproduces that softening (no refusal, no warning: SVK is simply not for large
 * compression). Neo-Hooke stiffens: |P11(0.3)| > |P11(0.577)|.
 * labels: physics extreme */
#include "extreme_util.h"

static const double lam = 4.0 / 3.0, mu = 1.0;

/* Closed-form P for F = diag(a, b) in plane strain. */
static void closed_form(int law, double a, double b, double P[4]) {
  P[1] = P[2] = 0;
  if (law == PDK_LAW_SVK) {
    const double E1 = 0.5 * (a * a - 1), E2 = 0.5 * (b * b - 1), tr = E1 + E2;
    P[0] = a * (lam * tr + 2 * mu * E1);
    P[3] = b * (lam * tr + 2 * mu * E2);
  } else {
    const double lnJ = log(a * b);
    P[0] = mu * (a - 1 / a) + lam * lnJ / a;
    P[3] = mu * (b - 1 / b) + lam * lnJ / b;
  }
}

static double run(pdk_ctx *ctx, int law, double a, double b) {
  pdk_particles *p = cu_lattice(ctx, 2, 12, 0.0, 1);
  pdk_families *fam = cu_families(ctx, p, 2.015);
  pdk_model_opts o = cu_opts(law, PDK_INFLUENCE_CONSTANT, PDK_STAB_NONE, 0);
  pdk_model *m = cu_model(ctx, p, fam, &o);
  const double F0[4] = {a, 0, 0, b}, c[2] = {0, 0};
  cu_affine(p, F0, c);
  double W = 0;
  T_OK(ctx, pdk_model_force_trial(m, &W));
  const char *ln = cu_law_name[law];
  int bad;
  const double fmax = ex_max_force(p, &bad);
  T_ASSERT(!bad && isfinite(W), "%s F0 = diag(%g, %g): non-finite force or energy %g", ln, a, b, W);
  const double centre[2] = {6.5, 6.5};
  const pdk_index i = ex_nearest(p, centre);
  for (int t = 0; t < 4; ++t)
    T_NEAR(cu_field(p, "F", t)[i], F0[t], 0, 1e-12, "%s F[%d] at %g, %g", ln, t, a, b);
  double P[4], Pe[4];
  ex_piola_2d(p, i, P);
  closed_form(law, a, b, Pe);
  const double scale = fabs(Pe[0]) + fabs(Pe[3]);
  for (int t = 0; t < 4; ++t)
    T_NEAR(P[t], Pe[t], 0, 1e-10 * scale, "%s P[%d] at F0 = diag(%g, %g)", ln, t, a, b);
  if (ex_verbose()) printf("%s diag(%g, %g): P11 %g (closed %g), W %g, max|f| %g\n", ln, a, b, P[0], Pe[0], W, fmax);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  return P[0];
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  const double s_peak = 1 / sqrt(3.0);
  for (int law = PDK_LAW_SVK; law <= PDK_LAW_NEO_HOOKE; ++law) {
    run(ctx, law, 3.0, 1.0);
    const double p03 = run(ctx, law, 0.3, 1.0), ppk = run(ctx, law, s_peak, 1.0);
    T_ASSERT(p03 < 0 && ppk < 0, "%s: compression gives compressive P11 (%g, %g)", cu_law_name[law], p03, ppk);
    if (law == PDK_LAW_SVK)
      T_ASSERT(fabs(p03) < fabs(ppk), "svk softens in compression: |P11(0.3)| %g < |P11(0.577)| %g", p03, ppk);
    else
      T_ASSERT(fabs(p03) > fabs(ppk), "neo-Hooke stiffens: |P11(0.3)| %g > |P11(0.577)| %g", p03, ppk);
  }
  run(ctx, PDK_LAW_NEO_HOOKE, 0.1, 0.1); /* J = 0.01 */
  pdk_ctx_destroy(&ctx);
  return 0;
}
