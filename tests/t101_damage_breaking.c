/* Johnson-Cook damage breaks bonds: a notched 2-D bar pulled until it tears in two.
 *
 * Bar [0, 40] x [0, 10] mm, square lattice dx = 1 mm, horizon 3.015 dx, plane strain, a pre-crack
 * (notch) at x = 20 mm from the bottom edge to y = 4 mm; left three columns fixed, right three
 * columns pulled at 10 m/s along x (the elastic wave rho c v ~ 450 MPa stays below the yield
 * stress, so plasticity starts at the notch tip). Material: the V-JC steel with a short failure
 * strain (D1 = 0.02, D2 = 0: eps_f = 0.02, failure at eps_p = D_c eps_f = 0.006) so that the
 * tear takes a few thousand steps; correspondence with Silling stabilization.
 * Checked:
 *   - bonds of failed particles are broken, from both ends; the bond state is symmetric and
 *     num_broken counts it;
 *   - the bar separates: the fixed and the pulled ends lie in different connected components of
 *     the intact bond graph, in TL and in semi-TL;
 *   - after separation no force crosses the crack: the internal force summed over the pulled
 *     piece, sum V_i f_i, is 0 to round-off (1e-10 of the peak reaction: internal pair forces
 *     cancel to about 1e-16 of their size);
 *   - bond state, positions and history bitwise identical on 1 and 2 threads (TL and semi-TL);
 *   - TL and semi-TL bitwise identical up to and including the step of the first break;
 *   - with failed_keeps_bonds (TL): particles fail and no bond breaks (the model keeps no bond
 *     state; the history's broken stays 0 while its failed count grows, which is why the count
 *     is there), every failed particle carries no stress (A = 0) and has D >= D_c, and 1 and 2
 *     threads give the same bits;
 *   - the history's failed count and largest damage (pdk_history failed, damage_max, the CSV's
 *     columns) never decrease, are 0 before the first failure, and at the end equal the count
 *     of the "failed" field and the largest value of the "damage" field exactly, with every
 *     failed particle's damage at or above D_c (the model's own D_c, from its options).
 * labels: physics threads */
#include "jc_corr_util.h"

#define MAX_STEPS 8000
#define CHUNK 20
#define EXTRA_STEPS 200 /* steps run after separation before the checks */

typedef jcu_sim sim;

static const char *rsets[2] = {"set:left", "set:right"};

static void build_keep(pdk_ctx *ctx, pdk_connectivity mode, int keeps_bonds, sim *s) {
  jcu_bar(ctx, 1, &s->p, &s->fam);
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = PDK_MODEL_CORRESPONDENCE;
  mo.law = PDK_LAW_JC;
  mo.jc.D1 = 0.02;
  mo.jc.D2 = 0.0;
  mo.stabilization = PDK_STAB_SILLING;
  mo.connectivity = mode;
  mo.failed_keeps_bonds = keeps_bonds;
  T_OK(ctx, pdk_model_create(s->p, s->fam, &mo, &s->m));
  jcu_bar_pull(s->bcs, 0, 10.0);
  pdk_explicit_opts eo = pdk_explicit_opts_default();
  eo.bcs = s->bcs;
  eo.num_bcs = 2;
  eo.reaction_sets = rsets;
  eo.num_reaction_sets = 2;
  eo.dt = 1.5e-7; /* fixed so every run takes the same steps; stable step about 2e-7 s */
  T_OK(ctx, pdk_explicit_create(s->m, &eo, &s->e));
}

static void build(pdk_ctx *ctx, pdk_connectivity mode, sim *s) { build_keep(ctx, mode, 0, s); }

/* First member of a set. */
static pdk_index first_of(pdk_particles *p, const char *set) {
  const uint8_t *mem = pdk_particles_field_data(p, set, 0);
  for (pdk_index i = 0; i < pdk_particles_count(p); ++i)
    if (mem[i]) return i;
  T_FAIL("set %s is empty", set);
}

/* 1 when the fixed and the pulled ends are no longer connected by intact bonds. */
static int separated(sim *s, pdk_index *comp) {
  jcu_components(s->m, comp);
  return comp[first_of(s->p, "set:left")] != comp[first_of(s->p, "set:right")];
}

/* Everything a step depends on, as bytes: x, v, history, bond state. */
static unsigned char *state_bytes(sim *s, size_t *bytes) {
  const pdk_index n = pdk_particles_count(s->p);
  const size_t xv = 4 * (size_t)n * sizeof(double);
  jcu_snapshot h = jcu_snapshot_take(s->m);
  unsigned char *out = malloc(xv + h.bytes);
  T_ASSERT(out, "out of memory");
  for (int c = 0; c < 2; ++c) {
    memcpy(out + (size_t)c * n * sizeof(double), pdk_particles_field_data(s->p, "x", c),
           (size_t)n * sizeof(double));
    memcpy(out + (size_t)(2 + c) * n * sizeof(double), pdk_particles_field_data(s->p, "v", c),
           (size_t)n * sizeof(double));
  }
  memcpy(out + xv, h.data, h.bytes);
  free(h.data);
  *bytes = xv + h.bytes;
  return out;
}

/* Runs until separation plus EXTRA_STEPS; returns the step count. Checks the failed particles'
 * bonds, the bond state and the force across the crack. */
static long run_to_separation(pdk_ctx *ctx, sim *s, const char *what) {
  const pdk_index n = pdk_particles_count(s->p);
  pdk_index *comp = malloc((size_t)n * sizeof *comp);
  T_ASSERT(comp, "out of memory");
  double peak = 0.0;
  long steps = 0, sep_step = -1;
  pdk_history h;
  pdk_index last_failed = 0;
  double last_dmax = 0.0;
  while (steps < MAX_STEPS) {
    T_OK(ctx, pdk_explicit_run(s->e, CHUNK, &h));
    steps += CHUNK;
    peak = fmax(peak, fabs(h.reaction[1][0]));
    /* the history's failure columns: never decreasing, failed 0 while no bond has broken */
    T_ASSERT(h.failed >= last_failed && h.damage_max >= last_dmax,
             "%s: step %ld: failed %d after %d, largest damage %g after %g", what, steps,
             (int)h.failed, (int)last_failed, h.damage_max, last_dmax);
    T_ASSERT(h.broken > 0 || h.failed == 0, "%s: step %ld: %d failed, no bond broken", what, steps,
             (int)h.failed);
    last_failed = h.failed;
    last_dmax = h.damage_max;
    if (sep_step < 0 && separated(s, comp)) sep_step = steps;
    if (sep_step >= 0 && steps >= sep_step + EXTRA_STEPS) break;
  }
  T_ASSERT(sep_step >= 0, "%s: the bar did not separate in %d steps (%lld bonds broken, %d failed)",
           what, MAX_STEPS, (long long)pdk_model_num_broken(s->m), (int)pdk_model_num_failed(s->m));
  T_ASSERT(separated(s, comp), "%s: separated pieces reconnected", what);
  if (getenv("PDK_TEST_VERBOSE"))
    printf("%s: separated by step %ld; %lld bonds broken, %d failed, %d flagged, peak reaction "
           "%g N, plastic work %g J, damage %g J, released %g J, compactions %ld\n",
           what, sep_step, (long long)pdk_model_num_broken(s->m), (int)pdk_model_num_failed(s->m),
           (int)pdk_model_num_flagged(s->m), peak, h.plastic_work, h.damage_work, h.breaking_work,
           pdk_model_num_compactions(s->m));

  /* failed particles: every bond broken, from both ends (the reverse is in jcu_check_bond_state) */
  const uint8_t *failed = pdk_particles_field_data(s->p, "failed", 0);
  const pdk_bond_index *start = pdk_families_bond_start(s->fam);
  const uint8_t *alive = pdk_model_bond_alive(s->m);
  pdk_index num_failed = 0;
  for (pdk_index i = 0; i < n; ++i) {
    if (!failed[i]) continue;
    ++num_failed;
    for (pdk_bond_index b = start[i]; b < start[i + 1]; ++b)
      T_ASSERT(!alive[b], "%s: failed particle %d keeps bond %lld", what, (int)i, (long long)b);
  }
  T_ASSERT(num_failed > 0 && num_failed == pdk_model_num_failed(s->m), "%s: %d failed (model %d)",
           what, (int)num_failed, (int)pdk_model_num_failed(s->m));
  /* the last history record: its failed count and largest damage are the fields' */
  const double *damage = pdk_particles_field_data(s->p, "damage", 0);
  const double D_c = pdk_model_opts_default().jc.D_c; /* build() keeps the default */
  double dmax = 0.0;
  for (pdk_index i = 0; i < n; ++i) {
    dmax = fmax(dmax, damage[i]);
    T_ASSERT(!failed[i] || damage[i] >= D_c, "%s: failed particle %d has damage %g < D_c %g", what,
             (int)i, damage[i], D_c);
  }
  T_ASSERT(h.failed == num_failed && h.damage_max == dmax,
           "%s: history failed %d, largest damage %.17g; fields %d, %.17g", what, (int)h.failed,
           h.damage_max, (int)num_failed, dmax);
  jcu_check_bond_state(s->m, what);

  /* no force across the crack: internal force on the pulled piece */
  const pdk_index piece = comp[first_of(s->p, "set:right")];
  const double *vol = pdk_particles_volume(s->p);
  for (int c = 0; c < 2; ++c) {
    const double *f = pdk_particles_field_data(s->p, "f", c);
    double sum = 0.0;
    for (pdk_index i = 0; i < n; ++i)
      if (comp[i] == piece) sum += vol[i] * f[i];
    T_NEAR(sum, 0.0, 0.0, 1e-10 * peak, "%s: force across the crack, component %d (peak %g N)",
           what, c, peak);
  }
  T_ASSERT(h.plastic_work > 0.0 && h.damage_work > 0.0, "%s: plastic %g, damage %g", what,
           h.plastic_work, h.damage_work);
  free(comp);
  return steps;
}

/* The run of `s` on 2 threads to `steps` ends in the state `ref` of the 1-thread run, bit for
 * bit. */
static void same_on_two_threads(pdk_ctx *ctx, sim *s, long steps, const unsigned char *ref,
                                size_t ref_bytes, const char *what) {
  T_OK(ctx, pdk_explicit_run(s->e, steps, NULL));
  size_t bytes;
  unsigned char *now = state_bytes(s, &bytes);
  T_ASSERT(bytes == ref_bytes && !memcmp(now, ref, bytes),
           "%s: state after %ld steps differs from 1 thread", what, steps);
  free(now);
}

/* failed_keeps_bonds (TL): runs until 10 particles have failed; checks that no bond broke, the
 * history's counts, and that every failed particle has D >= D_c and no stress. Returns the steps.
 */
static long run_keeping_bonds(pdk_ctx *ctx, sim *s, const char *what) {
  pdk_history h;
  pdk_index last = 0;
  long steps = 0;
  /* until a band of failed particles has formed (the notch tip fails first) */
  while (steps < MAX_STEPS) {
    T_OK(ctx, pdk_explicit_run(s->e, CHUNK, &h));
    steps += CHUNK;
    T_ASSERT(h.broken == 0 && h.failed >= last, "%s: step %ld: %lld broken, %d failed after %d",
             what, steps, (long long)h.broken, (int)h.failed, (int)last);
    last = h.failed;
    if (h.failed >= 10) break;
  }
  T_ASSERT(h.failed >= 10, "%s: %d failed in %d steps", what, (int)h.failed, MAX_STEPS);
  const pdk_index n = pdk_particles_count(s->p);
  const uint8_t *failed = pdk_particles_field_data(s->p, "failed", 0);
  const double *damage = pdk_particles_field_data(s->p, "damage", 0);
  const double D_c = pdk_model_opts_default().jc.D_c;
  pdk_index count = 0;
  for (pdk_index i = 0; i < n; ++i) {
    if (!failed[i]) continue;
    ++count;
    T_ASSERT(damage[i] >= D_c, "%s: failed particle %d has D %g", what, (int)i, damage[i]);
    for (int t = 0; t < 4; ++t) {
      const double *A = pdk_particles_field_data(s->p, "A", t);
      T_ASSERT(A[i] == 0.0, "%s: failed particle %d carries stress (A[%d] = %g)", what, (int)i, t,
               A[i]);
    }
  }
  T_ASSERT(count == h.failed && pdk_model_num_broken(s->m) == 0,
           "%s: history %d failed, fields %d; %lld bonds broken", what, (int)h.failed, (int)count,
           (long long)pdk_model_num_broken(s->m));
  if (getenv("PDK_TEST_VERBOSE"))
    printf("%s: %d failed by step %ld, largest damage %g, no bond broken\n", what, (int)h.failed,
           steps, h.damage_max);
  return steps;
}

/* `run` on 1 thread, then the same steps on 2 threads: the same bits. */
static void one_and_two_threads(pdk_ctx *ctx, pdk_connectivity mode, int keeps_bonds,
                                long (*run)(pdk_ctx *, sim *, const char *), const char *name) {
  unsigned char *ref = NULL;
  size_t ref_bytes = 0;
  long ref_steps = 0;
  for (int threads = 1; threads <= 2; ++threads) {
    T_OK(ctx, pdk_ctx_set_num_threads(ctx, threads));
    sim s;
    build_keep(ctx, mode, keeps_bonds, &s);
    char what[64];
    snprintf(what, sizeof what, "%s, %d thread%s", name, threads, threads > 1 ? "s" : "");
    T_ASSERT(!keeps_bonds || pdk_model_bond_alive(s.m) == NULL, "%s: the model keeps a bond state",
             what);
    if (threads == 1) {
      ref_steps = run(ctx, &s, what);
      ref = state_bytes(&s, &ref_bytes);
    } else {
      same_on_two_threads(ctx, &s, ref_steps, ref, ref_bytes, what);
    }
    jcu_sim_destroy(&s);
  }
  free(ref);
  T_OK(ctx, pdk_ctx_set_num_threads(ctx, 1));
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  const pdk_connectivity modes[2] = {PDK_CONNECTIVITY_TL, PDK_CONNECTIVITY_SEMI_TL};
  const char *names[2] = {"TL", "semi-TL"};

  /* 1. TL and semi-TL in lockstep: bitwise equal up to and including the first break. */
  {
    sim a, b;
    build(ctx, PDK_CONNECTIVITY_TL, &a);
    build(ctx, PDK_CONNECTIVITY_SEMI_TL, &b);
    long step = 0;
    for (; step < MAX_STEPS; ++step) {
      T_OK(ctx, pdk_explicit_run(a.e, 1, NULL));
      T_OK(ctx, pdk_explicit_run(b.e, 1, NULL));
      size_t na, nb;
      unsigned char *sa = state_bytes(&a, &na), *sb = state_bytes(&b, &nb);
      T_ASSERT(na == nb && !memcmp(sa, sb, na),
               "TL and semi-TL differ at step %ld, before the "
               "first break",
               step + 1);
      free(sa);
      free(sb);
      if (pdk_model_num_broken(a.m) > 0) break;
    }
    T_ASSERT(step < MAX_STEPS && pdk_model_num_broken(b.m) == pdk_model_num_broken(a.m),
             "first break: TL %lld, semi-TL %lld bonds", (long long)pdk_model_num_broken(a.m),
             (long long)pdk_model_num_broken(b.m));
    jcu_sim_destroy(&a);
    jcu_sim_destroy(&b);
  }

  /* 2. Each mode tears the bar; 2 threads give the same bits. */
  for (int k = 0; k < 2; ++k)
    one_and_two_threads(ctx, modes[k], 0, run_to_separation, names[k]);

  /* 3. failed_keeps_bonds: failures without broken bonds, counted by the history. */
  one_and_two_threads(ctx, PDK_CONNECTIVITY_TL, 1, run_keeping_bonds, "keeps bonds");
  pdk_ctx_destroy(&ctx);
  return 0;
}
