/* Bond damage (pdk_model_bond_damage; output fields "bond_damage" and, for models whose law has
 * no damage D, "damage"): d_i = 1 - sum over i's intact bonds of V_j / sum over all its bonds of
 * V_j, as LAMMPS's compute damage/atom.
 * On the pre-cracked plate of crack_plate_util.h pulled until the crack has grown from the tip
 * (120 us), for pmb, lps and correspondence (linear elastic, Silling stabilization, critical
 * stretch):
 *   - every d_i lies in [0, 1] and equals a brute-force count over the bond state exactly (the
 *     same sums in the same order: no tolerance; the stated tolerance 0 is the point: the field is
 *     the bond state's, not an estimate);
 *   - d_i = 0 for every particle more than 2 horizons from the crack line y = 20 mm and from the
 *     grips (the grips' waves, reflected at the opposite grip after about 110 us, break a few
 *     bonds next to them, not in between), d_i > 0 for the particles at the pre-crack's tip (the crack
 *     grew from there), and some particle has d > 0.3 (a crack face);
 *   - after pdk_sim_update_output_fields the fields "bond_damage" and "damage" hold the same bits,
 *     and the history's damage_max (the Johnson-Cook D) stays 0;
 *   - 1 and 2 threads give bitwise the same bond damage and "w_broken".
 * A particle pulled 10 horizons away in one committing pass loses all its bonds: d = 1 exactly,
 * and each former neighbour j loses one bond: d_j = V_i / sum of its bond volumes (brute force).
 * Without a critical stretch d = 0 everywhere. Through a scene run (pdk_sim_run) the last output
 * step of <name>.h5 holds "bond_damage" and "damage" equal to the model's bond damage.
 * labels: physics threads */
#include <hdf5.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pdk/run.h"
#include "test_util.h"
#include "crack_plate_util.h"

#define END_TIME "solver.end_time=1.2e-4"

typedef struct result {
  pdk_index n;
  double *d, *w;
} result;

static result run_plate(int threads, const char *kind_override, const char *extra) {
  pdk_ctx *ctx = t_ctx(threads);
  const char *ov[4] = {END_TIME, "output.fields=[u,bond_damage,damage]", kind_override, extra};
  const int nov = 2 + (kind_override != NULL) + (extra != NULL);
  pdk_sim *sim = cp_build(ctx, "t245.yaml", ov, nov, NULL);
  pdk_model *m = pdk_sim_model(sim);
  pdk_particles *p = pdk_sim_particles(sim);
  const pdk_index n = pdk_particles_count(p);
  pdk_history h;
  T_OK(ctx, pdk_explicit_run(pdk_sim_explicit(sim), pdk_sim_num_steps(sim), &h));
  T_ASSERT(h.broken > 0, "%s: bonds must break", kind_override);
  result r = {n, malloc((size_t)n * sizeof(double)), calloc((size_t)n, sizeof(double))};
  double *brute = malloc((size_t)n * sizeof(double));
  T_OK(ctx, pdk_model_bond_damage(m, r.d));
  cp_damage_brute(m, brute);
  const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1);
  double dmax = 0.0;
  int tip = 0;
  for (pdk_index i = 0; i < n; ++i) {
    T_ASSERT(r.d[i] >= 0.0 && r.d[i] <= 1.0, "%s: d[%d] = %g outside [0, 1]", kind_override,
             (int)i, r.d[i]);
    T_ASSERT(r.d[i] == brute[i], "%s: d[%d] = %.17g, brute force %.17g", kind_override, (int)i,
             r.d[i], brute[i]);
    if (fabs(Y[i] - CP_CRACK_Y) > 2.0 * CP_DELTA && Y[i] > 0.003 + 2.0 * CP_DELTA &&
        Y[i] < 0.037 - 2.0 * CP_DELTA)
      T_ASSERT(r.d[i] == 0.0, "%s: particle %d at (%g, %g), far from the crack, has d = %g",
               kind_override, (int)i, X[i], Y[i], r.d[i]);
    if (fabs(X[i] - (CP_TIP_X - 5e-4)) < 1e-6 && fabs(Y[i] - CP_CRACK_Y) < 1e-3) {
      T_ASSERT(r.d[i] > 0.0, "%s: particle %d at the tip (%g, %g) has d = 0", kind_override,
               (int)i, X[i], Y[i]);
      ++tip;
    }
    dmax = fmax(dmax, r.d[i]);
  }
  T_ASSERT(tip == 2, "%s: %d tip particles found, want 2", kind_override, tip);
  T_ASSERT(dmax > 0.3, "%s: largest bond damage %g: no crack face", kind_override, dmax);
  T_INFO("%s, %d threads: %lld bonds broken, largest d %.4f\n", kind_override, threads,
         (long long)h.broken, dmax);
  T_ASSERT(h.damage_max == 0.0, "%s: history damage_max %g is the law's D", kind_override,
           h.damage_max);
  T_OK(ctx, pdk_sim_update_output_fields(sim));
  const double *fb = pdk_particles_field_data(p, "bond_damage", 0);
  const double *fd = pdk_particles_field_data(p, "damage", 0);
  T_ASSERT(fb && fd, "%s: the output fields bond_damage and damage exist", kind_override);
  T_ASSERT(!memcmp(fb, r.d, (size_t)n * sizeof(double)) &&
               !memcmp(fd, r.d, (size_t)n * sizeof(double)),
           "%s: the fields bond_damage and damage are the bond damage", kind_override);
  const double *w = pdk_particles_field_data(p, "w_broken", 0);
  if (w) memcpy(r.w, w, (size_t)n * sizeof(double));
  free(brute);
  pdk_sim_destroy(&sim);
  pdk_ctx_destroy(&ctx);
  return r;
}

static void check_kind(const char *kind_override, const char *extra) {
  result a = run_plate(2, kind_override, extra), b = run_plate(1, kind_override, extra);
  T_ASSERT(!memcmp(a.d, b.d, (size_t)a.n * sizeof(double)), "%s: bond damage differs on 1 and 2 "
           "threads", kind_override);
  T_ASSERT(!memcmp(a.w, b.w, (size_t)a.n * sizeof(double)), "%s: w_broken differs on 1 and 2 "
           "threads", kind_override);
  free(a.d), free(a.w), free(b.d), free(b.w);
}

/* One particle moved 10 horizons away: every bond of it breaks in one committing pass. */
static void check_isolated(void) {
  pdk_ctx *ctx = t_ctx(2);
  pdk_sim *sim = cp_build(ctx, "t245.yaml", NULL, 0, NULL);
  pdk_model *m = pdk_sim_model(sim);
  pdk_particles *p = pdk_sim_particles(sim);
  const pdk_index n = pdk_particles_count(p);
  const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1);
  pdk_index k = -1;
  for (pdk_index i = 0; i < n; ++i)
    if (fabs(X[i] - 0.0305) < 1e-6 && fabs(Y[i] - 0.0305) < 1e-6) k = i;
  T_ASSERT(k >= 0, "particle at (30.5, 30.5) mm not found");
  ((double *)pdk_particles_field_data(p, "x", 0))[k] += 10.0 * CP_DELTA;
  T_OK(ctx, pdk_model_force(m, NULL));
  double *d = malloc((size_t)n * sizeof(double)), *brute = malloc((size_t)n * sizeof(double));
  T_OK(ctx, pdk_model_bond_damage(m, d));
  cp_damage_brute(m, brute);
  T_ASSERT(d[k] == 1.0, "the particle that lost all its bonds has d = %.17g, want 1", d[k]);
  const pdk_bond_index *bs = pdk_families_bond_start(pdk_model_families(m));
  const pdk_index *bj = pdk_families_bond_j(pdk_model_families(m));
  const pdk_bond_index nk = bs[k + 1] - bs[k];
  int damaged = 0;
  for (pdk_index i = 0; i < n; ++i) {
    T_ASSERT(d[i] == brute[i], "isolated: d[%d] = %.17g, brute force %.17g", (int)i, d[i],
             brute[i]);
    damaged += d[i] > 0.0;
  }
  T_ASSERT(damaged == nk + 1, "%d damaged particles, want the particle and its %d neighbours",
           damaged, (int)nk);
  for (pdk_bond_index b = bs[k]; b < bs[k + 1]; ++b) {
    const pdk_index j = bj[b];
    const double frac = 1.0 / (double)(bs[j + 1] - bs[j]); /* equal volumes: one bond of them */
    T_NEAR(d[j], frac, 1e-14, 0.0, "neighbour %d lost one bond of %d", (int)j,
           (int)(bs[j + 1] - bs[j]));
  }
  free(d), free(brute);
  pdk_sim_destroy(&sim);
  pdk_ctx_destroy(&ctx);
}

static void check_no_breaking(void) {
  pdk_ctx *ctx = t_ctx(2);
  const char *ov[] = {"model.critical_stretch=0", "solver.end_time=2.0e-5",
                      "output.fields=[bond_damage,damage]"};
  pdk_sim *sim = cp_build(ctx, "t245.yaml", ov, 3, NULL);
  T_OK(ctx, pdk_explicit_run(pdk_sim_explicit(sim), pdk_sim_num_steps(sim), NULL));
  T_OK(ctx, pdk_sim_update_output_fields(sim));
  pdk_particles *p = pdk_sim_particles(sim);
  const double *fb = pdk_particles_field_data(p, "bond_damage", 0);
  const double *fd = pdk_particles_field_data(p, "damage", 0);
  for (pdk_index i = 0; i < pdk_particles_count(p); ++i)
    T_ASSERT(fb[i] == 0.0 && fd[i] == 0.0, "no critical stretch: d[%d] = %g, %g", (int)i, fb[i],
             fd[i]);
  T_ASSERT(!pdk_particles_field_exists(p, "w_broken"), "no critical stretch: no w_broken field");
  pdk_sim_destroy(&sim);
  pdk_ctx_destroy(&ctx);
}

/* The last output step's dataset `name` [n] of file path. */
static void read_last(const char *path, const char *name, pdk_index n, double *out) {
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  T_ASSERT(f >= 0, "cannot open %s", path);
  hid_t g = H5Gopen2(f, "steps", H5P_DEFAULT);
  H5G_info_t info;
  T_ASSERT(g >= 0 && H5Gget_info(g, &info) >= 0 && info.nlinks > 0, "%s: no /steps", path);
  char ds[64];
  snprintf(ds, sizeof ds, "%06d/%s", (int)info.nlinks - 1, name);
  hid_t d = H5Dopen2(g, ds, H5P_DEFAULT);
  T_ASSERT(d >= 0, "%s: no /steps/%s", path, ds);
  hid_t sp = H5Dget_space(d);
  T_ASSERT(H5Sget_simple_extent_npoints(sp) == (hssize_t)n, "%s: /steps/%s has another size",
           path, ds);
  T_ASSERT(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) >= 0, "read %s", ds);
  H5Sclose(sp);
  H5Dclose(d);
  H5Gclose(g);
  H5Fclose(f);
}

static void check_scene_output(void) {
  pdk_ctx *ctx = t_ctx(2);
  const char *ov[] = {END_TIME, "output.fields=[u,bond_damage,damage,w_broken]"};
  pdk_scene *s = NULL;
  pdk_sim *sim = cp_build(ctx, "t245.yaml", ov, 2, &s);
  pdk_run_opts ro = pdk_run_opts_default();
  ro.dir = "t245_out";
  pdk_run_report rep;
  T_OK(ctx, pdk_sim_run(sim, s, &ro, &rep));
  pdk_particles *p = pdk_sim_particles(sim);
  const pdk_index n = pdk_particles_count(p);
  double *d = malloc((size_t)n * sizeof(double)), *h5 = malloc((size_t)n * sizeof(double));
  T_OK(ctx, pdk_model_bond_damage(pdk_sim_model(sim), d));
  double dmax = 0.0;
  for (pdk_index i = 0; i < n; ++i) dmax = fmax(dmax, d[i]);
  T_ASSERT(dmax > 0.3, "the scene run broke bonds (largest d %g)", dmax);
  const char *names[] = {"bond_damage", "damage"};
  for (int q = 0; q < 2; ++q) {
    read_last("t245_out/crackplate.h5", names[q], n, h5);
    T_ASSERT(!memcmp(h5, d, (size_t)n * sizeof(double)), "the last %s of the HDF5 output is not "
             "the model's bond damage", names[q]);
  }
  free(d), free(h5);
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  pdk_ctx_destroy(&ctx);
}

int main(void) {
  check_kind("model.kind=pmb", NULL);
  check_kind("model.kind=lps", NULL);
  check_kind("model.kind=correspondence", "model.stabilization=silling");
  check_isolated();
  check_no_breaking();
  check_scene_output();
  remove("t245.yaml");
  return 0;
}
