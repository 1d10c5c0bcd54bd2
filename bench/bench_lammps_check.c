/* Force-for-force check against LAMMPS (driven by bench/lammps/check_forces.sh): reads the two
 * dumps of bench/lammps/in.peri_forces (reference positions at rest; displaced positions with
 * LAMMPS's forces), evaluates the pdk model of the same style on the same configuration (horizon
 * 3.015 dx, lattice constant dx, volume dx^3, K = 160 GPa, G = 80 GPa) and compares.
 *
 *   bench_lammps_check --style pmb|lps --ref ref.dump --cur cur.dump [--dx 5e-4] [--pe PE]
 *
 * Prints the bond counts, the largest force difference relative to the largest LAMMPS force, and,
 * with --pe (LAMMPS's potential energy), the energy comparison: LAMMPS reports sum_i W_i without
 * particle volumes, and for peri/lps half of the deviatoric term, so the value pdk predicts for
 * LAMMPS is sum_i W_i (pmb) or sum_i (W_i + K theta_i^2 / 2) / 2 (lps). Exit status 1 when the
 * forces differ by more than 1e-10 of the largest force (round-off is ~1e-14).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "models/model_bond.h"
#include "pdk/pdk.h"

typedef struct dump {
  long n;
  double *x[3], *f[3]; /* by id - 1 */
} dump;

static int read_dump(const char *path, int with_forces, dump *d) {
  FILE *fp = fopen(path, "r");
  if (!fp) {
    fprintf(stderr, "bench_lammps_check: cannot open %s\n", path);
    return 1;
  }
  char line[1024];
  d->n = -1;
  while (fgets(line, sizeof line, fp)) {
    if (!strncmp(line, "ITEM: NUMBER OF ATOMS", 21)) {
      if (!fgets(line, sizeof line, fp)) break;
      d->n = atol(line);
    } else if (!strncmp(line, "ITEM: ATOMS", 11)) {
      break;
    }
  }
  if (d->n <= 0) {
    fprintf(stderr, "bench_lammps_check: %s: no atom count\n", path);
    fclose(fp);
    return 1;
  }
  for (int a = 0; a < 3; ++a) {
    d->x[a] = calloc((size_t)d->n, sizeof(double));
    d->f[a] = calloc((size_t)d->n, sizeof(double));
  }
  for (long k = 0; k < d->n; ++k) {
    long id;
    double v[6] = {0};
    int want = with_forces ? 7 : 4;
    if (!fgets(line, sizeof line, fp) ||
        sscanf(line, "%ld %lf %lf %lf %lf %lf %lf", &id, &v[0], &v[1], &v[2], &v[3], &v[4], &v[5]) <
            want ||
        id < 1 || id > d->n) {
      fprintf(stderr, "bench_lammps_check: %s: bad atom line %ld\n", path, k + 1);
      fclose(fp);
      return 1;
    }
    for (int a = 0; a < 3; ++a) {
      d->x[a][id - 1] = v[a];
      d->f[a][id - 1] = v[3 + a];
    }
  }
  fclose(fp);
  return 0;
}

int main(int argc, char **argv) {
  const char *style = NULL, *ref = NULL, *cur = NULL;
  double dx = 5e-4, pe = NAN;
  for (int k = 1; k + 1 < argc; k += 2) {
    if (!strcmp(argv[k], "--style"))
      style = argv[k + 1];
    else if (!strcmp(argv[k], "--ref"))
      ref = argv[k + 1];
    else if (!strcmp(argv[k], "--cur"))
      cur = argv[k + 1];
    else if (!strcmp(argv[k], "--dx"))
      dx = atof(argv[k + 1]);
    else if (!strcmp(argv[k], "--pe"))
      pe = atof(argv[k + 1]);
  }
  if (!style || !ref || !cur || (strcmp(style, "pmb") && strcmp(style, "lps"))) {
    fprintf(stderr, "usage: bench_lammps_check --style pmb|lps --ref ref.dump --cur cur.dump "
                    "[--dx DX] [--pe PE]\n");
    return 2;
  }
  dump r, c;
  if (read_dump(ref, 0, &r) || read_dump(cur, 1, &c)) return 1;
  if (r.n != c.n) {
    fprintf(stderr, "bench_lammps_check: the dumps hold %ld and %ld atoms\n", r.n, c.n);
    return 1;
  }
  const double K = 1.6e11, G = 0.8e11, delta = 3.015 * dx;

  pdk_ctx *ctx = NULL;
  char why[512];
  if (pdk_ctx_create(NULL, &ctx, why, sizeof why)) {
    fprintf(stderr, "bench_lammps_check: %s\n", why);
    return 1;
  }
  pdk_particles *p = NULL;
  pdk_families *fam = NULL;
  pdk_model *m = NULL;
  int fail = 1;
  if (pdk_particles_create(ctx, 3, (pdk_index)r.n, &p)) goto done;
  const pdk_index n = (pdk_index)r.n;
  for (pdk_index i = 0; i < n; ++i)
    pdk_particles_volume(p)[i] = dx * dx * dx;
  for (int a = 0; a < 3; ++a)
    memcpy(pdk_particles_X(p, a), r.x[a], (size_t)n * sizeof(double));
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = delta;
  if (pdk_families_build(p, &fo, &fam)) goto done;
  if (pdk_particles_field_add(p, "x", PDK_F64, 3)) goto done;
  for (int a = 0; a < 3; ++a)
    memcpy(pdk_particles_field_data(p, "x", a), c.x[a], (size_t)n * sizeof(double));
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = strcmp(style, "pmb") ? PDK_MODEL_LPS : PDK_MODEL_PMB;
  mo.bulk_modulus = K;
  mo.shear_modulus = G;
  mo.density = 7800;
  mo.lattice_constant = dx;
  if (pdk_model_create(p, fam, &mo, &m)) goto done;
  double energy = 0;
  if (pdk_model_force(m, &energy)) goto done;

  double fbig = 0, dmax = 0;
  long worst = -1;
  for (pdk_index i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) {
      double fp = ((double *)pdk_particles_field_data(p, "f", a))[i], fl = c.f[a][i];
      fbig = fmax(fbig, fabs(fl));
      if (fabs(fp - fl) > dmax) dmax = fabs(fp - fl), worst = i;
    }
  printf("%s: %ld particles, %lld directed bonds (%.3f per particle)\n", style, r.n,
         (long long)pdk_families_num_bonds(fam), (double)pdk_families_num_bonds(fam) / n);
  printf("%s: max |f_pdk - f_lammps| = %.3e = %.3e of max |f_lammps| (%.6e), at id %ld\n", style,
         dmax, dmax / fbig, fbig, worst + 1);
  if (!isnan(pe)) {
    const double *W = mo.kind == PDK_MODEL_PMB ? pdk_model_pmb_energy_density(m)
                                               : pdk_model_lps_energy_density(m);
    const double *theta = pdk_particles_field_data(p, "theta", 0);
    double sum_w = 0, predicted = 0;
    for (pdk_index i = 0; i < n; ++i) {
      sum_w += W[i];
      predicted += mo.kind == PDK_MODEL_PMB ? W[i] : 0.5 * (W[i] + 0.5 * K * theta[i] * theta[i]);
    }
    printf("%s: energy: pdk sum V W = %.12e J; sum W = %.12e; predicted LAMMPS pe = %.12e, "
           "LAMMPS pe = %.12e (relative difference %.2e)\n",
           style, energy, sum_w, predicted, pe, fabs(predicted - pe) / fabs(pe));
  }
  fail = !(dmax <= 1e-10 * fbig);
  printf("%s: %s (tolerance 1e-10 of the largest force)\n", style, fail ? "FAIL" : "PASS");
done:
  if (fail && pdk_ctx_error_message(ctx)[0])
    fprintf(stderr, "bench_lammps_check: %s\n", pdk_ctx_error_message(ctx));
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  for (int a = 0; a < 3; ++a)
    free(r.x[a]), free(r.f[a]), free(c.x[a]), free(c.f[a]);
  return fail;
}
