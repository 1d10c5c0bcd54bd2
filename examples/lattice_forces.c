/* Lattice to forces: the smallest use of pdk's C API.
 *
 * Builds a simple-cubic block of particles, its families (every neighbour within the horizon),
 * a bond-based PMB model, stretches the block uniformly by s in every direction and evaluates the
 * force density once. In the interior of a uniformly stretched body every bond pulls as hard as
 * its opposite one, so the force on the centre particle is zero to round-off, and the strain
 * energy per volume there is the continuum's 9/2 K s^2; the block's total energy is lower because
 * the particles near the surface miss part of their family.
 *
 *   example_lattice_forces [particles per side]       (default 20)
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <pdk/pdk.h>

#define CHECK(call)                                                                                \
  do {                                                                                             \
    if (call) {                                                                                    \
      fprintf(stderr, "%s\n", pdk_ctx_error_message(ctx));                                         \
      return 1;                                                                                    \
    }                                                                                              \
  } while (0)

int main(int argc, char **argv) {
  const int side = argc > 1 ? atoi(argv[1]) : 20;
  if (side < 8) {
    fprintf(stderr, "usage: %s [particles per side, at least 8]\n", argv[0]);
    return 2;
  }
  const double dx = 1e-3, horizon = 3.015 * dx, K = 140e9, s = 1e-4;
  char why[256];
  pdk_ctx *ctx = NULL;
  if (pdk_ctx_create(NULL, &ctx, why, sizeof why)) {
    fprintf(stderr, "%s\n", why);
    return 1;
  }

  /* Particles: a cube of side * dx, one particle at the centre of each cell. */
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_CUBIC;
  lo.spacing = dx;
  for (int c = 0; c < 3; ++c)
    lo.hi[c] = side * dx;
  pdk_particles *p = NULL;
  CHECK(pdk_lattice_create(ctx, &lo, &p));
  CHECK(pdk_particles_reorder_morton(p, horizon, NULL)); /* neighbours near in memory */

  /* Families and the model. */
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = horizon;
  pdk_families *fam = NULL;
  CHECK(pdk_families_build(p, &fo, &fam));
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = PDK_MODEL_PMB;
  mo.bulk_modulus = K;
  mo.density = 7800.0;
  pdk_model *m = NULL;
  CHECK(pdk_model_create(p, fam, &mo, &m));

  /* Current positions x = (1 + s) X, then one force pass (trial: no bond may break). */
  const pdk_index n = pdk_particles_count(p);
  for (int c = 0; c < 3; ++c) {
    const double *X = pdk_particles_X(p, c);
    double *x = pdk_particles_field_data(p, "x", c);
    for (pdk_index i = 0; i < n; ++i)
      x[i] = (1.0 + s) * X[i];
  }
  double energy = 0.0;
  CHECK(pdk_model_force_trial(m, &energy));

  /* The particle nearest the centre: its force density. */
  const double mid = 0.5 * side * dx;
  pdk_index centre = 0;
  double best = INFINITY;
  for (pdk_index i = 0; i < n; ++i) {
    double r2 = 0.0;
    for (int c = 0; c < 3; ++c)
      r2 += pow(pdk_particles_X(p, c)[i] - mid, 2);
    if (r2 < best) best = r2, centre = i;
  }
  double fc = 0.0;
  for (int c = 0; c < 3; ++c)
    fc = fmax(fc, fabs(((double *)pdk_particles_field_data(p, "f", c))[centre]));
  const double volume = pow(side * dx, 3), w_continuum = 4.5 * K * s * s;
  printf("particles %ld, bonds %ld\n", (long)n, (long)pdk_families_num_bonds(fam));
  printf("centre force density %.3e N/m^3 (a single bond's pull: %.3e)\n", fc,
         18.0 * K / (3.14159265358979323846 * pow(horizon, 4)) * s * dx * dx * dx);
  printf("energy per volume %.6e J/m^3, continuum 9/2 K s^2 = %.6e (ratio %.4f)\n", energy / volume,
         w_continuum, energy / volume / w_continuum);

  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  return 0;
}
