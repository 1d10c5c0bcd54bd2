/* Checkpoint and restart: N steps in one go versus N/2 steps, checkpoint, everything destroyed and
 * rebuilt from scratch, restore, N/2 steps. Positions, velocities, forces, bond state and every
 * history record are bitwise identical, for PMB, LPS and correspondence with bond breaking (bonds
 * break in the first half), on 1 and 2 threads (and the same across thread counts). A field that
 * exists only in the checkpoint is added on restore. Mismatches (particle count, bond state, a
 * field the checkpoint lacks, not a checkpoint, no file) are clear errors that change nothing.
 * labels: unit threads */
#include <hdf5.h>

#include "pdk/output.h"
#include "test_util.h"

#define N_STEPS 400
#define CHUNK 20 /* steps between history records */
#define NUM_REC (N_STEPS / CHUNK)

typedef struct sim {
  pdk_particles *p;
  pdk_families *fam;
  pdk_model *m;
  pdk_explicit *e;
} sim;

static pdk_bc bcs[2];
static const char *rsets[2] = {"set:left", "set:right"};

/* A 2-D bar [0, len_cells dx] x [0, 6 dx], dx = 1 mm: left end fixed, right end pulled at a steady
 * rate to 0.3 mm at the end of the run (strain 1%, critical stretch 0.2%: bonds break early). */
static void build(pdk_ctx *ctx, pdk_model_kind kind, int len_cells, double s00, sim *s) {
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.spacing = 1e-3;
  lo.hi[0] = len_cells * 1e-3;
  lo.hi[1] = 6e-3;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, &s->p));
  T_OK(ctx, pdk_particles_reorder_morton(s->p, 3.015e-3, NULL));
  double a[3] = {-1, -1, -1}, b[3] = {2.5e-3, 1, 1}, c[3] = {(len_cells - 2.5) * 1e-3, -1, -1},
         d[3] = {1, 1, 1};
  pdk_region left = pdk_region_box(a, b), right = pdk_region_box(c, d);
  T_OK(ctx, pdk_particles_set_define(s->p, "left", &left, NULL));
  T_OK(ctx, pdk_particles_set_define(s->p, "right", &right, NULL));
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = 3.015e-3;
  T_OK(ctx, pdk_families_build(s->p, &fo, &s->fam));
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = kind;
  mo.bulk_modulus = 1.6e11;
  mo.shear_modulus = 8e10;
  mo.density = 8000;
  mo.critical_stretch = s00;
  mo.alpha = 0.25; /* LAMMPS: s0 depends on the last pass, so a restart must restore it */
  if (kind == PDK_MODEL_CORRESPONDENCE) mo.stabilization = PDK_STAB_SILLING;
  T_OK(ctx, pdk_model_create(s->p, s->fam, &mo, &s->m));
  memset(bcs, 0, sizeof bcs);
  bcs[0].kind = PDK_BC_DISPLACEMENT;
  bcs[0].set = "set:left";
  bcs[0].components = 3;
  bcs[1].kind = PDK_BC_DISPLACEMENT;
  bcs[1].set = "set:right";
  bcs[1].components = 1;
  pdk_explicit_opts eo = pdk_explicit_opts_default();
  eo.bcs = bcs;
  eo.num_bcs = 2;
  eo.reaction_sets = rsets;
  eo.num_reaction_sets = 2;
  eo.dt = 1.2e-7; /* fixed, below the stable step of this lattice (about 1.9e-7 s) */
  bcs[1].value[0] = (pdk_tfun){PDK_TFUN_SMOOTH, 3e-4, N_STEPS * eo.dt};
  T_OK(ctx, pdk_explicit_create(s->m, &eo, &s->e));
}

static int file_exists(const char *path) {
  FILE *f = fopen(path, "r");
  if (f) fclose(f);
  return f != NULL;
}

static void destroy(sim *s) {
  pdk_explicit_destroy(&s->e);
  pdk_model_destroy(&s->m);
  pdk_families_destroy(&s->fam);
  pdk_particles_destroy(&s->p);
}

/* Runs `records` chunks of CHUNK steps, one history record per chunk. */
static void run(pdk_ctx *ctx, sim *s, int records, pdk_history *hist) {
  for (int r = 0; r < records; ++r) {
    T_OK(ctx, pdk_explicit_run(s->e, CHUNK, &hist[r]));
    if (getenv("PDK_TEST_VERBOSE"))
      printf("step %ld broken %lld kinetic %g strain %g R %g\n", hist[r].step,
             (long long)hist[r].broken, hist[r].kinetic, hist[r].strain, hist[r].reaction[1][0]);
  }
}

/* The final state: x, v, f (2 x n each) and the bond state. */
typedef struct state {
  double *xvf;
  uint8_t *alive;
  pdk_bond_index num_bonds, num_broken;
  pdk_history hist[NUM_REC];
} state;

static void capture(sim *s, state *st) {
  pdk_index n = pdk_particles_count(s->p);
  const char *names[3] = {"x", "v", "f"};
  st->xvf = malloc(6 * (size_t)n * sizeof(double));
  for (int q = 0; q < 3; ++q)
    for (int c = 0; c < 2; ++c)
      memcpy(st->xvf + (2 * q + c) * n, pdk_particles_field_data(s->p, names[q], c),
             (size_t)n * sizeof(double));
  st->num_bonds = pdk_families_num_bonds(s->fam);
  st->alive = malloc((size_t)st->num_bonds);
  memcpy(st->alive, pdk_model_bond_alive(s->m), (size_t)st->num_bonds);
  st->num_broken = pdk_model_num_broken(s->m);
}

static void compare(const state *a, const state *b, pdk_index n, const char *what) {
  const char *names[3] = {"x", "v", "f"};
  for (int k = 0; k < 6; ++k)
    for (pdk_index i = 0; i < n; ++i)
      T_ASSERT(!memcmp(&a->xvf[k * n + i], &b->xvf[k * n + i], sizeof(double)),
               "%s: %s[%d] of particle %d: %.17g vs %.17g", what, names[k / 2], k % 2, (int)i,
               a->xvf[k * n + i], b->xvf[k * n + i]);
  T_ASSERT(a->num_broken == b->num_broken, "%s: %lld vs %lld broken bonds", what,
           (long long)a->num_broken, (long long)b->num_broken);
  T_ASSERT(!memcmp(a->alive, b->alive, (size_t)a->num_bonds), "%s: bond state differs", what);
  for (int r = 0; r < NUM_REC; ++r)
    T_ASSERT(
        !memcmp(&a->hist[r], &b->hist[r], sizeof a->hist[r]),
        "%s: history record %d (step %ld) differs: kinetic %.17g vs %.17g, strain %.17g vs %.17g, "
        "work %.17g vs %.17g",
        what, r, a->hist[r].step, a->hist[r].kinetic, b->hist[r].kinetic, a->hist[r].strain,
        b->hist[r].strain, a->hist[r].external_work, b->hist[r].external_work);
}

static void free_state(state *st) {
  free(st->xvf);
  free(st->alive);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  const pdk_model_kind kinds[3] = {PDK_MODEL_PMB, PDK_MODEL_LPS, PDK_MODEL_CORRESPONDENCE};
  const char *path = "t071_checkpoint.h5";
  const char *scene = "name: t071\nsolver: {steps: 240}\n";
  for (int kk = 0; kk < 3; ++kk) {
    state by_threads[2];
    pdk_index n_particles = 0;
    for (int threads = 1; threads <= 2; ++threads) {
      T_OK(ctx, pdk_ctx_set_num_threads(ctx, threads));
      char what[128];
      snprintf(what, sizeof what, "%s, %d thread(s)", pdk_model_kind_name(kinds[kk]), threads);
      sim s;
      /* Continuous run. */
      state cont, resumed;
      build(ctx, kinds[kk], 30, 2e-3, &s);
      run(ctx, &s, NUM_REC, cont.hist);
      capture(&s, &cont);
      destroy(&s);
      /* Half, checkpoint, destroy, rebuild, restore, half. A field only the first half knows
       * ("u") must come back. */
      build(ctx, kinds[kk], 30, 2e-3, &s);
      run(ctx, &s, NUM_REC / 2, resumed.hist);
      T_ASSERT(pdk_model_num_broken(s.m) > 0, "%s: no bond broke in the first half", what);
      T_ASSERT(pdk_model_num_broken(s.m) < cont.num_broken,
               "%s: bonds keep breaking in the second half", what);
      pdk_index n = pdk_particles_count(s.p);
      n_particles = n;
      T_OK(ctx, pdk_particles_field_add(s.p, "u", PDK_F64, 2));
      for (int c = 0; c < 2; ++c)
        for (pdk_index i = 0; i < n; ++i)
          ((double *)pdk_particles_field_data(s.p, "u", c))[i] = (double)(i + c) / 7.0;
      long half_step = pdk_explicit_step(s.e);
      double half_time = pdk_explicit_time(s.e);
      T_OK(ctx, pdk_checkpoint_write(ctx, path, s.e, scene));
      destroy(&s);
      T_ASSERT(file_exists(path) && !file_exists("t071_checkpoint.h5.part"),
               "the checkpoint exists under its final name only");
      long info_step = -1;
      double info_time = -1;
      char *info_scene = NULL;
      T_OK(ctx, pdk_checkpoint_info(ctx, path, &info_step, &info_time, &info_scene));
      T_ASSERT(info_step == half_step && info_time == half_time && info_scene &&
                   !strcmp(info_scene, scene),
               "checkpoint info: step %ld time %g scene '%s'", info_step, info_time, info_scene);
      free(info_scene);
      build(ctx, kinds[kk], 30, 2e-3, &s);
      T_OK(ctx, pdk_checkpoint_read(ctx, path, s.e));
      T_ASSERT(pdk_explicit_step(s.e) == half_step && pdk_explicit_time(s.e) == half_time,
               "%s: restored step %ld time %g", what, pdk_explicit_step(s.e),
               pdk_explicit_time(s.e));
      T_ASSERT(pdk_particles_field_exists(s.p, "u"), "%s: field u restored", what);
      for (int c = 0; c < 2; ++c)
        for (pdk_index i = 0; i < n; ++i)
          T_ASSERT(((double *)pdk_particles_field_data(s.p, "u", c))[i] == (double)(i + c) / 7.0,
                   "u[%d][%d]", c, (int)i);
      run(ctx, &s, NUM_REC - NUM_REC / 2, resumed.hist + NUM_REC / 2);
      capture(&s, &resumed);
      destroy(&s);
      compare(&cont, &resumed, n, what);
      free_state(&resumed);
      by_threads[threads - 1] = cont;
    }
    compare(&by_threads[0], &by_threads[1], n_particles, "1 vs 2 threads");
    free_state(&by_threads[0]);
    free_state(&by_threads[1]);
  }

  /* Mismatches: each a clear error, and nothing changes. */
  T_OK(ctx, pdk_ctx_set_num_threads(ctx, 1));
  sim s;
  build(ctx, PDK_MODEL_PMB, 30, 2e-3, &s);
  T_OK(ctx, pdk_explicit_run(s.e, 10, NULL));
  T_OK(ctx, pdk_checkpoint_write(ctx, path, s.e, NULL));
  destroy(&s);
  build(ctx, PDK_MODEL_PMB, 31, 2e-3, &s); /* a longer bar */
  T_FAILS(ctx, pdk_checkpoint_read(ctx, path, s.e), PDK_ERR_ARG, "particles");
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "scene changed"),
           "the message suggests the scene changed: %s", pdk_ctx_error_message(ctx));
  T_ASSERT(pdk_explicit_step(s.e) == 0, "a failed restore changes nothing");
  destroy(&s);
  build(ctx, PDK_MODEL_PMB, 30, 0.0, &s); /* no bond breaking */
  T_FAILS(ctx, pdk_checkpoint_read(ctx, path, s.e), PDK_ERR_ARG, "break");
  destroy(&s);
  build(ctx, PDK_MODEL_LPS, 30, 2e-3, &s);
  T_FAILS(ctx, pdk_checkpoint_read(ctx, path, s.e), PDK_ERR_ARG, "model");
  destroy(&s);
  build(ctx, PDK_MODEL_PMB, 30, 2e-3, &s);
  T_OK(ctx, pdk_particles_field_add(s.p, "extra", PDK_F64, 1));
  T_FAILS(ctx, pdk_checkpoint_read(ctx, path, s.e), PDK_ERR_ARG, "extra");
  T_ASSERT(pdk_explicit_step(s.e) == 0 && pdk_model_num_broken(s.m) == 0,
           "a failed restore changes nothing");
  T_FAILS(ctx, pdk_checkpoint_read(ctx, "t071_no_such_checkpoint.h5", s.e), PDK_ERR_IO,
          "does not exist");
  hid_t f = H5Fcreate("t071_not_a_checkpoint.h5", H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  H5Fclose(f);
  T_FAILS(ctx, pdk_checkpoint_read(ctx, "t071_not_a_checkpoint.h5", s.e), PDK_ERR_IO,
          "not a pdk checkpoint");
  destroy(&s);
  remove("t071_not_a_checkpoint.h5");
  pdk_ctx_destroy(&ctx);
  return 0;
}
