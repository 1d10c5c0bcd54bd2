/* Critical-stretch bond breaking, the LAMMPS s0 rule, for PMB and LPS in 2-D and 3-D:
 *  - a trial pass (pdk_model_force_trial) changes no bond and no s0, and gives the same forces as a
 *    committing pass on the same state (to round-off: the loops are specialised separately);
 *  - a committing pass breaks exactly the intact bonds with s > min(s0_i, s0_j), s0 from the
 *    previous pass (s00 before the first), and sets s0_i = max over the bonds intact at entry of
 *    (s00 - alpha s); checked over two passes, the second reading the first's s0;
 *  - a bond breaks from both ends in the same pass; num_broken counts directed bonds;
 *  - forces after breaking omit the broken bonds (independent evaluation here);
 *  - every state and force is bitwise the same on 1 and 2 threads.
 * Stretches are recomputed here from X and x; a bond whose stretch lies within 1e-12 of its
 * threshold would be ambiguous to round-off and is not judged (the test requires there are none).
 * labels: unit threads */
#include <float.h>

#include "bond_models_test.h"

#define K_BULK 2.0
#define G_SHEAR 0.7
#define H_SPACING 0.37
#define S00 0.02
#define ALPHA 0.25

typedef struct run {
  uint8_t *alive[2]; /* bond state after pass 1 and pass 2 */
  double *f[2][3];   /* forces of pass 1 and pass 2 */
  double *theta[2];
  double energy[2];
  pdk_bond_index broken[2];
  pdk_bond_index num_bonds;
} run;

static double stretch(pdk_particles *p, pdk_index i, pdk_index j) {
  int dim = pdk_particles_dim(p);
  double r2 = 0, r02 = 0;
  for (int a = 0; a < dim; ++a) {
    double d = ((double *)pdk_particles_field_data(p, "x", a))[j] -
               ((double *)pdk_particles_field_data(p, "x", a))[i];
    double d0 = pdk_particles_X(p, a)[j] - pdk_particles_X(p, a)[i];
    r2 += d * d;
    r02 += d0 * d0;
  }
  return (sqrt(r2) - sqrt(r02)) / sqrt(r02);
}

/* Forces with the given bond state, written out plainly (omega = 1/r0, lattice_constant = H). */
static void expected_forces(pdk_model_kind kind, pdk_particles *p, pdk_families *f,
                            const uint8_t *alive, double *fe[3], double *fscale) {
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  const pdk_bond_index *bs = pdk_families_bond_start(f);
  const pdk_index *bj = pdk_families_bond_j(f);
  const double delta = pdk_families_horizon(f), *V = pdk_particles_volume(p);
  double *m = calloc((size_t)n, sizeof(double)), *th = calloc((size_t)n, sizeof(double));
  const double K = K_BULK, G = G_SHEAR;
  for (int pass = 0; pass < 3; ++pass)
    for (pdk_index i = 0; i < n; ++i) {
      if (pass == 2)
        for (int a = 0; a < dim; ++a)
          fe[a][i] = 0, fscale[i] = 0;
      for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
        const pdk_index j = bj[b];
        double eta[3] = {0}, r2 = 0, r02 = 0;
        for (int a = 0; a < dim; ++a) {
          eta[a] = ((double *)pdk_particles_field_data(p, "x", a))[j] -
                   ((double *)pdk_particles_field_data(p, "x", a))[i];
          double d0 = pdk_particles_X(p, a)[j] - pdk_particles_X(p, a)[i];
          r2 += eta[a] * eta[a];
          r02 += d0 * d0;
        }
        const double r = sqrt(r2), r0 = sqrt(r02), s = (r - r0) / r0;
        const double beta =
            fabs(r0 - delta) <= 0.5 * H_SPACING ? (delta + 0.5 * H_SPACING - r0) / H_SPACING : 1.0;
        const double vol = V[j] * beta;
        if (pass == 0) m[i] += r0 * vol; /* all bonds: m is fixed at set-up */
        if (!alive[b]) continue;
        if (pass == 1) th[i] += (r - r0) * vol;
        if (pass == 2) {
          double t;
          if (kind == PDK_MODEL_PMB)
            t = (dim == 3 ? 18.0 * K / (M_PI * pow(delta, 4))
                          : 72.0 * K / (5.0 * M_PI * pow(delta, 3))) *
                s;
          else if (dim == 3)
            t = (3 * K - 5 * G) * (th[i] / m[i] + th[j] / m[j]) +
                15 * G * (1 / m[i] + 1 / m[j]) * s;
          else
            t = 2 * (K - 2 * G / 3 - G) * (th[i] / m[i] + th[j] / m[j]) +
                8 * G * (1 / m[i] + 1 / m[j]) * s;
          for (int a = 0; a < dim; ++a)
            fe[a][i] += vol * t * eta[a] / r;
          fscale[i] += fabs(vol * t);
        }
      }
      if (pass == 1) th[i] *= dim / m[i];
    }
  free(m);
  free(th);
}

static void run_sequence(pdk_ctx *ctx, int dim, pdk_model_kind kind, run *out, int check) {
  const char *name = pdk_model_kind_name(kind);
  pdk_particles *p = bm_body(ctx, dim, dim == 3 ? 14 : 50, dim == 3 ? 13 : 45, 12, H_SPACING, 0.1,
                             0.1, 555 + (uint64_t)dim);
  const pdk_index n = pdk_particles_count(p);
  pdk_families *f = bm_families(ctx, p, 3.015 * H_SPACING);
  const pdk_bond_index nb = pdk_families_num_bonds(f);
  const pdk_bond_index *bs = pdk_families_bond_start(f);
  const pdk_index *bj = pdk_families_bond_j(f);
  pdk_model *m = bm_model(ctx, p, f, kind, K_BULK, G_SHEAR, H_SPACING, S00, ALPHA);
  const uint8_t *alive = pdk_model_bond_alive(m);
  T_ASSERT(alive != NULL, "bond state exists with a critical stretch");
  for (pdk_bond_index b = 0; b < nb; ++b)
    T_ASSERT(alive[b] == 1, "all bonds intact at creation");

  double *s0 = malloc((size_t)n * sizeof(double)); /* expected s0 of the previous pass */
  for (pdk_index i = 0; i < n; ++i)
    s0[i] = S00;
  uint8_t *expect = malloc((size_t)nb);
  memset(expect, 1, (size_t)nb);
  double *fe[3], *ftrial[3], *fscale = malloc((size_t)n * sizeof(double));
  for (int a = 0; a < 3; ++a) {
    fe[a] = calloc((size_t)n, sizeof(double));
    ftrial[a] = calloc((size_t)n, sizeof(double));
  }
  pdk_bond_index total_broken = 0;
  out->num_bonds = nb;

  for (int pass = 0; pass < 2; ++pass) {
    bm_displace_random(p, (pass == 0 ? 0.02 : 0.025) * H_SPACING, 1000 + (uint64_t)pass);

    /* Trial passes: same forces twice, no state change. */
    double e_trial = 0;
    T_OK(ctx, pdk_model_force_trial(m, &e_trial));
    for (int a = 0; a < dim; ++a)
      memcpy(ftrial[a], pdk_particles_field_data(p, "f", a), (size_t)n * sizeof(double));
    T_OK(ctx, pdk_model_force_trial(m, NULL));
    T_ASSERT(pdk_model_num_broken(m) == total_broken, "%s: a trial pass broke bonds", name);
    for (pdk_bond_index b = 0; b < nb; ++b)
      T_ASSERT(alive[b] == expect[b], "%s %d-D pass %d: trial pass changed bond %lld", name, dim,
               pass, (long long)b);

    /* Expected outcome of the committing pass, from the previous pass's s0. */
    uint8_t *next = malloc((size_t)nb);
    double *s0_next = malloc((size_t)n * sizeof(double));
    pdk_bond_index num_new = 0, ambiguous = 0;
    for (pdk_index i = 0; i < n; ++i) {
      double mx = -DBL_MAX;
      for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
        next[b] = expect[b];
        if (!expect[b]) continue;
        const pdk_index j = bj[b];
        const double s = stretch(p, i, j), thr = fmin(s0[i], s0[j]);
        if (fabs(s - thr) <= 1e-12) ++ambiguous;
        if (s > thr) next[b] = 0, ++num_new;
        mx = fmax(mx, S00 - ALPHA * s);
      }
      s0_next[i] = mx == -DBL_MAX ? DBL_MAX : mx;
    }
    T_ASSERT(ambiguous == 0, "%lld bonds within 1e-12 of their threshold; change the seed",
             (long long)ambiguous);

    double e = 0;
    T_OK(ctx, pdk_model_force(m, &e));
    /* Same formulas, but the compiler specialises the trial and the committing loops separately
     * (vector reductions may associate differently): equal to round-off, 1e-12 of the largest. */
    T_NEAR(e, e_trial, 1e-12, 0.0, "%s %d-D pass %d: committing pass energy vs trial", name, dim,
           pass);
    double fbig = 0;
    for (int a = 0; a < dim; ++a)
      for (pdk_index i = 0; i < n; ++i)
        fbig = fmax(fbig, fabs(ftrial[a][i]));
    for (int a = 0; a < dim; ++a)
      for (pdk_index i = 0; i < n; ++i)
        T_NEAR(((double *)pdk_particles_field_data(p, "f", a))[i], ftrial[a][i], 0.0, 1e-12 * fbig,
               "%s %d-D pass %d: commit and trial forces differ at %d", name, dim, pass, (int)i);
    total_broken += num_new;
    T_ASSERT(pdk_model_num_broken(m) == total_broken,
             "%s %d-D pass %d: num_broken %lld, expected %lld", name, dim, pass,
             (long long)pdk_model_num_broken(m), (long long)total_broken);
    for (pdk_index i = 0; i < n; ++i)
      for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
        T_ASSERT(alive[b] == next[b],
                 "%s %d-D pass %d: bond %d -> %d is %d, expected %d (s = %.17g, "
                 "s0 = %g, %g)",
                 name, dim, pass, (int)i, (int)bj[b], alive[b], next[b], stretch(p, i, bj[b]),
                 s0[i], s0[bj[b]]);
        int64_t rb = bm_find_bond(bs, bj, bj[b], i);
        T_ASSERT(rb >= 0 && alive[rb] == alive[b], "%s: bond %d-%d broken from one end only", name,
                 (int)i, (int)bj[b]);
      }
    if (check) { /* some bonds break, most survive */
      T_ASSERT(num_new > nb / 1000 && num_new < nb / 4, "%s %d-D pass %d: %lld of %lld bonds broke",
               name, dim, pass, (long long)num_new, (long long)nb);
    }

    /* Forces of the next pass use the new state: check them now with a trial pass. */
    memcpy(expect, next, (size_t)nb);
    memcpy(s0, s0_next, (size_t)n * sizeof(double));
    free(next);
    free(s0_next);
    T_OK(ctx, pdk_model_force_trial(m, &out->energy[pass]));
    expected_forces(kind, p, f, expect, fe, fscale);
    for (pdk_index i = 0; i < n; ++i)
      for (int a = 0; a < dim; ++a)
        T_NEAR(((double *)pdk_particles_field_data(p, "f", a))[i], fe[a][i], 0.0, 1e-11 * fscale[i],
               "%s %d-D after pass %d: force on %d without the broken bonds", name, dim, pass,
               (int)i);
    out->alive[pass] = malloc((size_t)nb);
    memcpy(out->alive[pass], alive, (size_t)nb);
    for (int a = 0; a < dim; ++a) {
      out->f[pass][a] = malloc((size_t)n * sizeof(double));
      memcpy(out->f[pass][a], pdk_particles_field_data(p, "f", a), (size_t)n * sizeof(double));
    }
    out->theta[pass] = NULL;
    if (kind == PDK_MODEL_LPS) {
      out->theta[pass] = malloc((size_t)n * sizeof(double));
      memcpy(out->theta[pass], pdk_particles_field_data(p, "theta", 0), (size_t)n * sizeof(double));
    }
    out->broken[pass] = pdk_model_num_broken(m);
  }
  for (int a = 0; a < 3; ++a)
    free(fe[a]), free(ftrial[a]);
  free(fscale);
  free(s0);
  free(expect);
  pdk_model_destroy(&m);
  pdk_families_destroy(&f);
  pdk_particles_destroy(&p);
}

int main(void) {
  pdk_ctx *ctx1 = t_ctx(1), *ctx2 = t_ctx(2);
  for (int dim = 2; dim <= 3; ++dim)
    for (int kind = PDK_MODEL_PMB; kind <= PDK_MODEL_LPS; ++kind) {
      run r1, r2;
      run_sequence(ctx1, dim, (pdk_model_kind)kind, &r1, 1);
      run_sequence(ctx2, dim, (pdk_model_kind)kind, &r2, 0);
      const char *name = pdk_model_kind_name((pdk_model_kind)kind);
      const size_t n = (size_t)(dim == 3 ? 14 * 13 * 12 : 50 * 45);
      for (int pass = 0; pass < 2; ++pass) {
        T_ASSERT(r1.broken[pass] == r2.broken[pass] && r1.num_bonds == r2.num_bonds &&
                     !memcmp(r1.alive[pass], r2.alive[pass], (size_t)r1.num_bonds),
                 "%s %d-D pass %d: bond states differ between 1 and 2 threads", name, dim, pass);
        T_ASSERT(!memcmp(&r1.energy[pass], &r2.energy[pass], sizeof(double)),
                 "%s %d-D pass %d: energy differs between 1 and 2 threads", name, dim, pass);
        for (int a = 0; a < dim; ++a)
          T_ASSERT(!memcmp(r1.f[pass][a], r2.f[pass][a], n * sizeof(double)),
                   "%s %d-D pass %d: forces differ between 1 and 2 threads", name, dim, pass);
        if (r1.theta[pass])
          T_ASSERT(!memcmp(r1.theta[pass], r2.theta[pass], n * sizeof(double)),
                   "%d-D pass %d: dilation differs between 1 and 2 threads", dim, pass);
        free(r1.alive[pass]), free(r2.alive[pass]), free(r1.theta[pass]), free(r2.theta[pass]);
        for (int a = 0; a < dim; ++a)
          free(r1.f[pass][a]), free(r2.f[pass][a]);
      }
    }
  pdk_ctx_destroy(&ctx1);
  pdk_ctx_destroy(&ctx2);
  return 0;
}
