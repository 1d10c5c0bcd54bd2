/* Cost of the ductile (Johnson-Cook) correspondence step against the elastic one, per phase.
 *
 *   bench_ductile [--side L] [--m M] [--threads T] [--repeat R] [--steps S]
 *
 * Problem: a 2-D square lattice L x L (plane strain, spacing 1 mm, Morton order), horizon M
 * spacings, constant influence, Silling stabilization 0.1, the V-JC steel (E 200 GPa, nu 0.29,
 * A 792 MPa, B 510 MPa, n 0.26, D1..D3, D_c 0.3), stretched affinely by 1% along y (yield strain
 * 0.4%), so every particle's trial state is plastic and the radial return runs everywhere.
 *
 * Part 1, phases (kernels/ref/corr.c called directly on one thread, over all particles, on the
 * model's own fields; trial passes, so every repeat does the same plastic return):
 *   shape        K = sum w V xi (x) xi, K^-1, m: the family gather alone (what a reshape costs
 *                per row; also the bond loop pass 1 repeats for N)
 *   pass1 elastic   N, F = N K^-1, Neo-Hooke P, A = P K^-1
 *   pass1 JC        the same with pdk_jc_update (exponential-map return, damage)
 *   pass1 JC, no damage   damage switched off (the difference is the damage update)
 *   JC update only  pdk_jc_update per particle on the F of pass 1, no family loop: the material
 *                   update (return mapping and damage) alone
 *   pass2           force gather f = sum w V (A_i + A_j) xi + Silling term (law independent)
 *   break check     the bond-failure kernel over every bond (failed ends; nothing breaks): what
 *                   the connectivity update would cost per step if it ran every step
 *   reshape batch   a batch of 1% of the rows lost bonds: reshape + released energy of those
 *                   rows (the cost when something broke)
 *   Printed: median process CPU time, ns per directed bond, ns per particle.
 *
 * Part 2, whole explicit steps through the public API (pdk_explicit_run, T threads): elastic
 * (Neo-Hooke) vs Johnson-Cook with failed particles breaking their bonds (bond state present,
 * nothing fails in the run) vs Johnson-Cook with failed_keeps_bonds (no bond state at all): if
 * the connectivity update stayed on the per-step path when nothing broke, the second would cost
 * more than the third. The grips pull the top rows at 2 m/s from the 1% stretched state. The
 * last rows run elastic, JC and JC with softened stabilization and family triaxiality (the
 * shipped plate scenes' choices) on the lattice stencil path (model.stencil on, the scenes'
 * default auto takes it for these models).
 * Printed: median process CPU time per step and thread over R runs of S steps each (CPU time,
 * not wall time: on a shared machine the wall time includes other processes' turns).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "kernels.h"
#include "pdk/pdk.h"

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, cmp_double);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

#define CHECK(ctx, expr)                                                                           \
  do {                                                                                             \
    if (expr) {                                                                                    \
      fprintf(stderr, "%s failed: %s\n", #expr, pdk_ctx_error_message(ctx));                       \
      exit(1);                                                                                     \
    }                                                                                              \
  } while (0)

#define MAX_REPEAT 64

/* Process CPU time: the machine this runs on is shared, so wall time overstates the cost by the
 * time other processes held the core; with one thread CPU time is the compute time. */
static double cpu_time(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct setup {
  pdk_particles *p;
  pdk_families *fam;
  pdk_index n;
  pdk_bond_index nb;
} setup;

static void build(pdk_ctx *ctx, int side, double mfac, setup *s) {
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.spacing = 1e-3;
  lo.thickness = 1e-3;
  lo.hi[0] = lo.hi[1] = side * 1e-3;
  CHECK(ctx, pdk_lattice_create(ctx, &lo, &s->p));
  CHECK(ctx, pdk_particles_reorder_morton(s->p, pdk_families_cell_edge(s->p, mfac * 1e-3), NULL));
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = mfac * 1e-3;
  CHECK(ctx, pdk_families_build(s->p, &fo, &s->fam));
  s->n = pdk_particles_count(s->p);
  s->nb = pdk_families_num_bonds(s->fam);
  const double b = 1e-3 * (side - 3.0);
  double a0[3] = {-1, -1, -1}, a1[3] = {1, 2.5e-3, 1}, c0[3] = {-1, b, -1}, c1[3] = {1, 1, 1};
  pdk_region bot = pdk_region_box(a0, a1), top = pdk_region_box(c0, c1);
  CHECK(ctx, pdk_particles_set_define(s->p, "bottom", &bot, NULL));
  CHECK(ctx, pdk_particles_set_define(s->p, "top", &top, NULL));
}

static void stretch(setup *s, double eps) {
  double *x0 = pdk_particles_field_data(s->p, "x", 0), *x1 = pdk_particles_field_data(s->p, "x", 1);
  const double *X0 = pdk_particles_X(s->p, 0), *X1 = pdk_particles_X(s->p, 1);
  for (pdk_index i = 0; i < s->n; ++i) {
    x0[i] = X0[i];
    x1[i] = X1[i] * (1.0 + eps);
  }
}

static pdk_model_opts model_opts(int jc, int keeps_bonds) {
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = PDK_MODEL_CORRESPONDENCE;
  mo.influence = PDK_INFLUENCE_CONSTANT;
  mo.stabilization = PDK_STAB_SILLING;
  mo.stab_coefficient = 0.1;
  mo.density = 7830.0;
  const double E = 200e9, nu = 0.29;
  mo.bulk_modulus = E / (3.0 * (1.0 - 2.0 * nu));
  mo.shear_modulus = E / (2.0 * (1.0 + nu));
  mo.law = jc ? PDK_LAW_JC : PDK_LAW_NEO_HOOKE;
  if (jc) {
    mo.jc = pdk_jc_params_default(); /* the V-JC steel */
    mo.failed_keeps_bonds = keeps_bonds;
  }
  return mo;
}

/* The kernel arrays of a model's fields (the private ones: our own, computed as the model does:
 * constant influence gives omega = 1 on every bond). */
typedef struct karrays {
  pdk_corr_arrays a;
  pdk_corr_consts k;
  double *omega, *W, *m;
  int32_t *num_alive;
  uint8_t *alive, *changed;
} karrays;

static void karrays_make(setup *s, const pdk_model_opts *mo, karrays *ka) {
  memset(ka, 0, sizeof *ka);
  const pdk_index np = pdk_particles_count_padded(s->p);
  ka->omega = malloc((size_t)s->nb * sizeof(double));
  ka->alive = malloc((size_t)s->nb);
  ka->W = calloc((size_t)np, sizeof(double));
  ka->m = calloc((size_t)np, sizeof(double));
  ka->num_alive = calloc((size_t)np, sizeof(int32_t));
  ka->changed = calloc((size_t)np, 1);
  for (pdk_bond_index b = 0; b < s->nb; ++b) {
    ka->omega[b] = 1.0;
    ka->alive[b] = 1;
  }
  pdk_corr_arrays *a = &ka->a;
  pdk_particles *p = s->p;
  a->bond_start = pdk_families_bond_start(s->fam);
  a->bond_j = pdk_families_bond_j(s->fam);
  a->bond_omega = ka->omega;
  a->bond_alive = ka->alive;
  for (int d = 0; d < 2; ++d) {
    a->X[d] = pdk_particles_X(p, d);
    a->x[d] = pdk_particles_field_data(p, "x", d);
    a->f[d] = pdk_particles_field_data(p, "f", d);
  }
  a->volume = pdk_particles_volume(p);
  for (int t = 0; t < 4; ++t) {
    a->Kinv[t] = pdk_particles_field_data(p, "Kinv", t);
    a->F[t] = pdk_particles_field_data(p, "F", t);
    a->A[t] = pdk_particles_field_data(p, "A", t);
  }
  a->m = ka->m;
  a->flag = pdk_particles_field_data(p, "flag", 0);
  a->num_alive = ka->num_alive;
  a->W = ka->W;
  if (mo->law == PDK_LAW_JC) {
    for (int t = 0; t < 6; ++t)
      a->cp_inv[t] = pdk_particles_field_data(p, "cp_inv", t);
    a->eps_p = pdk_particles_field_data(p, "eps_p", 0);
    a->damage = pdk_particles_field_data(p, "damage", 0);
    a->failed = pdk_particles_field_data(p, "failed", 0);
    a->eps_p_rate = pdk_particles_field_data(p, "eps_p_rate", 0);
    a->w_plastic = pdk_particles_field_data(p, "w_plastic", 0);
    a->w_damage = pdk_particles_field_data(p, "w_damage", 0);
    a->w_broken = pdk_particles_field_data(p, "w_broken", 0);
  }
  a->changed = ka->changed;
  pdk_corr_consts *k = &ka->k;
  k->dim = 2;
  k->law = (int)mo->law;
  k->mu = mo->shear_modulus;
  k->lambda = mo->bulk_modulus - 2.0 * mo->shear_modulus / 3.0;
  k->stab = (int)mo->stabilization;
  k->stab_modulus = mo->stab_coefficient * 36.0 / 5.0 * mo->bulk_modulus;
  k->horizon = pdk_families_horizon(s->fam);
  k->span_rtol = PDK_CORR_SPAN_RTOL;
  k->jc = mo->law == PDK_LAW_JC ? &mo->jc : NULL;
  k->dt = 1e-7;
  k->commit = 0;
  k->break_failed = mo->law == PDK_LAW_JC;
}

static void karrays_free(karrays *ka) {
  free(ka->omega);
  free(ka->alive);
  free(ka->W);
  free(ka->m);
  free(ka->num_alive);
  free(ka->changed);
}

typedef enum { PH_SHAPE, PH_PASS1, PH_PASS2, PH_JC_ONLY, PH_BREAK, PH_RESHAPE } phase;

/* Median time of one phase over all particles (one thread). */
static double time_phase(karrays *ka, setup *s, phase ph, int repeat) {
  double t[MAX_REPEAT];
  const pdk_corr_arrays *a = &ka->a;
  const pdk_corr_consts *k = &ka->k;
  for (int r = -1; r < repeat; ++r) { /* r = -1: warm-up */
    const double t0 = cpu_time();
    switch (ph) {
    case PH_SHAPE:
      pdk_kernel_corr_shape_ref(k, a, 0, s->n);
      break;
    case PH_PASS1:
      pdk_kernel_corr_pass1_ref(k, a, 0, s->n);
      break;
    case PH_PASS2:
      pdk_kernel_corr_pass2_ref(k, a, 0, s->n);
      break;
    case PH_JC_ONLY:
      for (pdk_index i = 0; i < s->n; ++i) {
        double F[3][3] = {{a->F[0][i], a->F[1][i], 0}, {a->F[2][i], a->F[3][i], 0}, {0, 0, 1}};
        double P[3][3];
        pdk_jc_state in, out;
        pdk_jc_result res;
        for (int c = 0; c < 6; ++c)
          in.cp_inv[c] = a->cp_inv[c][i];
        in.eps_p = a->eps_p[i];
        in.damage = a->damage[i];
        in.temp_rise = 0.0;
        in.failed = a->failed[i];
        pdk_jc_update(k->jc, 2, F, k->dt, &in, &out, P, &res);
        a->W[i] = res.W; /* keep the result alive */
      }
      break;
    case PH_BREAK:
      pdk_kernel_corr_break_ref(k, a, 0, s->n);
      break;
    case PH_RESHAPE:
      /* 1% of the rows, spread over the body, lost bonds */
      for (pdk_index i = 0; i < s->n; ++i)
        a->changed[i] = i % 100 == 0 ? 3u : 0u;
      pdk_kernel_corr_reshape_ref(k, a, 0, s->n);
      pdk_kernel_corr_release_ref(k, a, 0, s->n, 0);
      break;
    }
    if (r >= 0) t[r] = cpu_time() - t0;
  }
  return median(t, repeat);
}

/* dt_interval > 0: re-estimate the stable step every dt_interval steps (solver.dt_update
 * periodic), to time what an estimate costs. */
static double time_steps(pdk_ctx *ctx, setup *s, const pdk_model_opts *mo, int repeat, long steps,
                         long dt_interval, pdk_bond_index *broken) {
  double t[MAX_REPEAT];
  *broken = 0;
  for (int r = 0; r < repeat; ++r) {
    /* fresh state every run: fields of an earlier model are reset by the new model's setup for
     * x only through stretch(); history fields are removed below */
    pdk_model *m = NULL;
    CHECK(ctx, pdk_model_create(s->p, s->fam, mo, &m));
    stretch(s, 0.01);
    if (mo->law == PDK_LAW_JC) { /* virgin history */
      for (int c = 0; c < 6; ++c) {
        double *cp = pdk_particles_field_data(s->p, "cp_inv", c);
        for (pdk_index i = 0; i < s->n; ++i)
          cp[i] = c < 3 ? 1.0 : 0.0;
      }
      const char *zero[] = {"eps_p", "damage", "w_plastic", "w_damage", "eps_p_rate"};
      for (int z = 0; z < 5; ++z)
        memset(pdk_particles_field_data(s->p, zero[z], 0), 0, (size_t)s->n * sizeof(double));
      memset(pdk_particles_field_data(s->p, "failed", 0), 0, (size_t)s->n);
      const char *opt[] = {"w_stab", "w_silling", "sigma_m", "sigma_m_avg"};
      for (int z = 0; z < 4; ++z)
        if (pdk_particles_field_exists(s->p, opt[z]))
          memset(pdk_particles_field_data(s->p, opt[z], 0), 0, (size_t)s->n * sizeof(double));
      if (pdk_particles_field_exists(s->p, "stab_factor")) {
        double *f = pdk_particles_field_data(s->p, "stab_factor", 0);
        for (pdk_index i = 0; i < s->n; ++i)
          f[i] = 1.0;
      }
    }
    pdk_bc bcs[2];
    memset(bcs, 0, sizeof bcs);
    bcs[0].kind = PDK_BC_DISPLACEMENT;
    bcs[0].set = "set:bottom";
    bcs[0].components = 3;
    bcs[1].kind = PDK_BC_VELOCITY;
    bcs[1].set = "set:top";
    bcs[1].components = 3;
    bcs[1].value[1] = pdk_tfun_constant(2.0);
    pdk_explicit_opts eo = pdk_explicit_opts_default();
    eo.bcs = bcs;
    eo.num_bcs = 2;
    if (dt_interval > 0) {
      eo.dt_update = PDK_DT_UPDATE_PERIODIC;
      eo.dt_update_interval = dt_interval;
    }
    pdk_explicit *e = NULL;
    CHECK(ctx, pdk_explicit_create(m, &eo, &e));
    for (int d = 0; d < 2; ++d) /* at rest in the stretched state */
      memset(pdk_particles_field_data(s->p, "v", d), 0, (size_t)s->n * sizeof(double));
    pdk_history h;
    CHECK(ctx, pdk_explicit_run(e, 5, &h)); /* warm-up */
    const double t0 = cpu_time();
    CHECK(ctx, pdk_explicit_run(e, steps, &h));
    t[r] = (cpu_time() - t0) / (double)steps / (double)pdk_ctx_num_threads(ctx);
    *broken += pdk_model_num_broken(m);
    pdk_explicit_destroy(&e);
    pdk_model_destroy(&m);
  }
  return median(t, repeat);
}

int main(int argc, char **argv) {
  int side = 200, threads = 1, repeat = 7;
  long steps = 50;
  double mfac = 3.015;
  for (int a = 1; a < argc; ++a) {
    if (!strcmp(argv[a], "--side") && a + 1 < argc)
      side = atoi(argv[++a]);
    else if (!strcmp(argv[a], "--m") && a + 1 < argc)
      mfac = atof(argv[++a]);
    else if (!strcmp(argv[a], "--threads") && a + 1 < argc)
      threads = atoi(argv[++a]);
    else if (!strcmp(argv[a], "--repeat") && a + 1 < argc)
      repeat = atoi(argv[++a]);
    else if (!strcmp(argv[a], "--steps") && a + 1 < argc)
      steps = atol(argv[++a]);
    else {
      fprintf(stderr, "usage: bench_ductile [--side L] [--m M] [--threads T] [--repeat R] "
                      "[--steps S]\n");
      return 2;
    }
  }
  if (repeat < 1) repeat = 1;
  if (repeat > MAX_REPEAT) repeat = MAX_REPEAT;
  if (steps < 1) steps = 1;
  pdk_ctx_opts co = pdk_ctx_opts_default();
  co.num_threads = threads;
  char why[256];
  pdk_ctx *ctx = NULL;
  if (pdk_ctx_create(&co, &ctx, why, sizeof why)) {
    fprintf(stderr, "pdk_ctx_create: %s\n", why);
    return 1;
  }
  setup s;
  build(ctx, side, mfac, &s);
  printf("bench_ductile: 2-D square %d x %d, %d particles, %lld directed bonds (%.1f per "
         "particle), horizon %.3f spacings, repeat %d\n",
         side, side, (int)s.n, (long long)s.nb, (double)s.nb / (double)s.n, mfac, repeat);

  /* Part 1: phases, one thread, kernels called directly. */
  pdk_model_opts mo_el = model_opts(0, 0), mo_jc = model_opts(1, 0);
  pdk_model *m_el = NULL, *m_jc = NULL;
  CHECK(ctx, pdk_model_create(s.p, s.fam, &mo_el, &m_el));
  stretch(&s, 0.01);
  karrays ke;
  karrays_make(&s, &mo_el, &ke);
  pdk_kernel_corr_shape_ref(&ke.k, &ke.a, 0, s.n);
  const double t_shape = time_phase(&ke, &s, PH_SHAPE, repeat);
  const double t_p1_el = time_phase(&ke, &s, PH_PASS1, repeat);
  const double t_p2_el = time_phase(&ke, &s, PH_PASS2, repeat);
  pdk_model_destroy(&m_el);
  karrays_free(&ke);
  CHECK(ctx, pdk_model_create(s.p, s.fam, &mo_jc, &m_jc));
  karrays kj;
  karrays_make(&s, &mo_jc, &kj);
  pdk_kernel_corr_shape_ref(&kj.k, &kj.a, 0, s.n);
  const double t_p1_jc = time_phase(&kj, &s, PH_PASS1, repeat);
  int plastic = 0;
  {
    pdk_index i = s.n / 2;
    double F[3][3] = {{kj.a.F[0][i], kj.a.F[1][i], 0}, {kj.a.F[2][i], kj.a.F[3][i], 0}, {0, 0, 1}};
    double P[3][3];
    pdk_jc_state in = pdk_jc_state_initial(), out;
    pdk_jc_result res;
    pdk_jc_update(kj.k.jc, 2, F, kj.k.dt, &in, &out, P, &res);
    plastic = res.plastic;
  }
  const double t_jc_only = time_phase(&kj, &s, PH_JC_ONLY, repeat);
  const double t_p2_jc = time_phase(&kj, &s, PH_PASS2, repeat);
  const double t_break = time_phase(&kj, &s, PH_BREAK, repeat);
  mo_jc.jc.damage = 0;
  kj.k.jc = &mo_jc.jc;
  const double t_p1_nodmg = time_phase(&kj, &s, PH_PASS1, repeat);
  const double t_jc_nodmg = time_phase(&kj, &s, PH_JC_ONLY, repeat);
  mo_jc.jc.damage = 1;
  const double t_reshape = time_phase(&kj, &s, PH_RESHAPE, repeat);
  pdk_model_destroy(&m_jc);
  karrays_free(&kj);

  const double nbd = (double)s.nb, npd = (double)s.n;
  printf("\nPart 1: phases, 1 thread, medians (trial state plastic at every particle: %s)\n",
         plastic ? "yes" : "NO");
  printf("%-34s %10s %9s %11s\n", "phase", "ms", "ns/bond", "ns/particle");
#define ROW(name, t) printf("%-34s %10.3f %9.2f %11.1f\n", name, 1e3 * (t), 1e9 * (t) / nbd, \
                            1e9 * (t) / npd)
  ROW("shape (K, K^-1, m)", t_shape);
  ROW("pass1 elastic (N, F, Neo-Hooke)", t_p1_el);
  ROW("pass1 JC (N, F, return, damage)", t_p1_jc);
  ROW("pass1 JC, damage off", t_p1_nodmg);
  ROW("JC update only (return, damage)", t_jc_only);
  ROW("JC update only, damage off", t_jc_nodmg);
  ROW("pass2 elastic (force, Silling)", t_p2_el);
  ROW("pass2 JC (force, Silling)", t_p2_jc);
  ROW("break check, every bond", t_break);
  ROW("reshape + release, 1% of rows", t_reshape);
  printf("elastic pass (pass1 + pass2) %.3f ms, JC pass %.3f ms: ratio %.2f\n",
         1e3 * (t_p1_el + t_p2_el), 1e3 * (t_p1_jc + t_p2_jc),
         (t_p1_jc + t_p2_jc) / (t_p1_el + t_p2_el));
  printf("material update share of the JC pass %.0f%% (damage %.0f%%); a break check every step "
         "would add %.0f%%\n",
         100.0 * t_jc_only / (t_p1_jc + t_p2_jc), 100.0 * (t_jc_only - t_jc_nodmg) / (t_p1_jc + t_p2_jc),
         100.0 * t_break / (t_p1_jc + t_p2_jc));

  /* Part 2: whole steps. */
  pdk_bond_index br_el, br_jc, br_keep;
  const double st_el = time_steps(ctx, &s, &mo_el, repeat, steps, 0, &br_el);
  const double st_jc = time_steps(ctx, &s, &mo_jc, repeat, steps, 0, &br_jc);
  pdk_model_opts mo_keep = model_opts(1, 1);
  const double st_keep = time_steps(ctx, &s, &mo_keep, repeat, steps, 0, &br_keep);
  pdk_model_opts mo_soft = mo_jc, mo_fam = mo_jc, mo_both = mo_jc;
  mo_soft.stab_softening = mo_both.stab_softening = 1;
  mo_fam.damage_triaxiality = mo_both.damage_triaxiality = PDK_TRIAX_FAMILY;
  pdk_bond_index br_x;
  const double st_soft = time_steps(ctx, &s, &mo_soft, repeat, steps, 0, &br_x);
  const double st_fam = time_steps(ctx, &s, &mo_fam, repeat, steps, 0, &br_x);
  const double st_both = time_steps(ctx, &s, &mo_both, repeat, steps, 0, &br_x);
  const double st_du = time_steps(ctx, &s, &mo_jc, repeat, steps, 10, &br_x);
  /* the same steps on the lattice stencil path (model.stencil, the scenes' default) */
  pdk_model_opts mo_el_st = mo_el, mo_jc_st = mo_jc, mo_both_st = mo_both;
  mo_el_st.stencil = mo_jc_st.stencil = mo_both_st.stencil = PDK_STENCIL_ON;
  const double st_el_st = time_steps(ctx, &s, &mo_el_st, repeat, steps, 0, &br_x);
  const double st_jc_st = time_steps(ctx, &s, &mo_jc_st, repeat, steps, 0, &br_x);
  const double st_both_st = time_steps(ctx, &s, &mo_both_st, repeat, steps, 0, &br_x);
  printf("\nPart 2: explicit steps, %d thread(s), %ld steps per run, medians of %d runs\n",
         pdk_ctx_num_threads(ctx), steps, repeat);
  printf("%-44s %10s %9s %9s\n", "step", "ms/step", "ns/bond", "vs elastic");
  printf("%-44s %10.3f %9.2f %9.2f\n", "elastic (Neo-Hooke)", 1e3 * st_el, 1e9 * st_el / nbd, 1.0);
  printf("%-44s %10.3f %9.2f %9.2f\n", "JC, failed particles break bonds", 1e3 * st_jc,
         1e9 * st_jc / nbd, st_jc / st_el);
  printf("%-44s %10.3f %9.2f %9.2f\n", "JC, failed_keeps_bonds (no bond state)", 1e3 * st_keep,
         1e9 * st_keep / nbd, st_keep / st_el);
  printf("%-44s %10.3f %9.2f %9.2f  (%.3f of JC)\n", "JC, softened stabilization", 1e3 * st_soft,
         1e9 * st_soft / nbd, st_soft / st_el, st_soft / st_jc);
  printf("%-44s %10.3f %9.2f %9.2f  (%.3f of JC)\n", "JC, family triaxiality", 1e3 * st_fam,
         1e9 * st_fam / nbd, st_fam / st_el, st_fam / st_jc);
  printf("%-44s %10.3f %9.2f %9.2f  (%.3f of JC)\n", "JC, softened + family", 1e3 * st_both,
         1e9 * st_both / nbd, st_both / st_el, st_both / st_jc);
  printf("%-44s %10.3f %9.2f %9.2f  (%.3f of JC: one estimate costs %.1f JC steps)\n",
         "JC, stable step re-estimated every 10 steps", 1e3 * st_du, 1e9 * st_du / nbd,
         st_du / st_el, st_du / st_jc, 10.0 * (st_du / st_jc - 1.0));
  printf("%-44s %10.3f %9.2f %9.2f\n", "stencil path: elastic", 1e3 * st_el_st,
         1e9 * st_el_st / nbd, st_el_st / st_el);
  printf("%-44s %10.3f %9.2f %9.2f  (%.3f of general; %.2f of stencil elastic)\n",
         "stencil path: JC", 1e3 * st_jc_st, 1e9 * st_jc_st / nbd, st_jc_st / st_el,
         st_jc_st / st_jc, st_jc_st / st_el_st);
  printf("%-44s %10.3f %9.2f %9.2f  (%.3f of general)\n", "stencil path: JC, softened + family",
         1e3 * st_both_st, 1e9 * st_both_st / nbd, st_both_st / st_el, st_both_st / st_both);
  const long long broken_all = (long long)(br_el + br_jc + br_keep);
  printf("bonds broken in these runs: %lld%s; breaking on / off = %.3f\n", broken_all,
         broken_all ? " (some runs broke bonds: use fewer --steps to time the steps where nothing "
                      "breaks)"
                    : " (connectivity never had anything to do)",
         st_jc / st_keep);
  pdk_families_destroy(&s.fam);
  pdk_particles_destroy(&s.p);
  pdk_ctx_destroy(&ctx);
  return 0;
}
