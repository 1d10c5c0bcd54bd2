/* Helpers shared by the Johnson-Cook correspondence and damage tests (t10x): history snapshots
 * compared bit for bit, bond-state checks, connected components of the intact bond graph, and a
 * 2-D bar built by hand. */
#ifndef PDK_JC_CORR_UTIL_H
#define PDK_JC_CORR_UTIL_H

#include "pdk/explicit.h"
#include "pdk/geometry.h"
#include "pdk/model.h"
#include "test_util.h"

/* Every per-particle history field a JC correspondence model may declare. */
static const char *const jcu_history_fields[] = {
    "cp_inv",   "eps_p",    "damage",      "temp_rise", "failed", "eps_p_rate",  "w_plastic",
    "w_damage", "w_broken", "stab_factor", "w_stab",    "w_silling", "sigma_m", "sigma_m_avg"};
#define JCU_NUM_HISTORY ((int)(sizeof jcu_history_fields / sizeof jcu_history_fields[0]))

/* The bar of t101-t105: [0, 40] x [0, 10] mm, spacing 1 mm, square lattice in Morton order, sets
 * "left" (x <= 3 mm, held) and "right" (x >= 37 mm, pulled), families with horizon 3.015 mm
 * and, when notch, a pre-crack along x = 20 mm from below the bar to y = 4 mm. */
static inline void jcu_bar(pdk_ctx *ctx, int notch, pdk_particles **p, pdk_families **fam) {
  const double dx = 1e-3;
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.spacing = dx;
  lo.hi[0] = 40 * dx;
  lo.hi[1] = 10 * dx;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, p));
  T_OK(ctx, pdk_particles_reorder_morton(*p, 3.015 * dx, NULL));
  double a[3] = {-1, -1, -1}, b[3] = {3 * dx, 1, 1}, c[3] = {37 * dx, -1, -1}, d[3] = {1, 1, 1};
  pdk_region left = pdk_region_box(a, b), right = pdk_region_box(c, d);
  T_OK(ctx, pdk_particles_set_define(*p, "left", &left, NULL));
  T_OK(ctx, pdk_particles_set_define(*p, "right", &right, NULL));
  static const double cut[4] = {20e-3, -1e-3, 20e-3, 4e-3};
  pdk_precrack crack = {2, cut};
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = 3.015 * dx;
  if (notch) {
    fo.precracks = &crack;
    fo.num_precracks = 1;
  }
  T_OK(ctx, pdk_families_build(*p, &fo, fam));
}

/* The model of t106's (and t052's) tearing bar: Johnson-Cook correspondence with damage (D1 0.02,
 * D2 0.3, D3 -2.12: failure within the run), Silling stabilization softened with the plastic
 * modulus, family triaxiality, and the given stress at a break. */
static inline pdk_model_opts jcu_tearing_opts(pdk_break_stress bs) {
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = PDK_MODEL_CORRESPONDENCE;
  mo.law = PDK_LAW_JC;
  mo.bulk_modulus = mo.shear_modulus = mo.density = 0.0; /* from mo.jc */
  mo.jc.damage = 1;
  mo.jc.D1 = 0.02;
  mo.jc.D2 = 0.3;
  mo.jc.D3 = -2.12;
  mo.stabilization = PDK_STAB_SILLING;
  mo.stab_softening = 1;
  mo.damage_triaxiality = PDK_TRIAX_FAMILY;
  mo.break_stress = bs;
  return mo;
}

/* The bar's loads: "left" held (all components), "right" pulled along x at v, by a velocity
 * condition (by_displacement = 0) or by the displacement u = v t (1: positions exact at every
 * step). */
static inline void jcu_bar_pull(pdk_bc bcs[2], int by_displacement, double v) {
  memset(bcs, 0, 2 * sizeof *bcs);
  bcs[0].kind = PDK_BC_DISPLACEMENT;
  bcs[0].set = "set:left";
  bcs[0].components = 3;
  bcs[1].kind = by_displacement ? PDK_BC_DISPLACEMENT : PDK_BC_VELOCITY;
  bcs[1].set = "set:right";
  bcs[1].components = 1;
  bcs[1].value[0] = by_displacement ? (pdk_tfun){PDK_TFUN_LINEAR, 0.0, v} : pdk_tfun_constant(v);
}

/* One bar run: its store, families, model, solver and loads. */
typedef struct jcu_sim {
  pdk_particles *p;
  pdk_families *fam;
  pdk_model *m;
  pdk_explicit *e;
  pdk_bc bcs[2];
} jcu_sim;

static inline void jcu_sim_destroy(jcu_sim *s) {
  pdk_explicit_destroy(&s->e);
  pdk_model_destroy(&s->m);
  pdk_families_destroy(&s->fam);
  pdk_particles_destroy(&s->p);
}

/* A copy of every history field that exists, plus the bond state. */
typedef struct jcu_snapshot {
  unsigned char *data;
  size_t bytes;
} jcu_snapshot;

static inline size_t jcu_snapshot_fill(pdk_model *m, unsigned char *out) {
  pdk_particles *p = pdk_model_particles(m);
  const pdk_index n = pdk_particles_count(p);
  size_t off = 0;
  for (int k = 0; k < JCU_NUM_HISTORY; ++k) {
    pdk_type type;
    int num_comp;
    if (!pdk_particles_field_exists(p, jcu_history_fields[k])) continue;
    pdk_particles_field_info(p, jcu_history_fields[k], &type, &num_comp);
    const size_t len = (size_t)n * pdk_type_size(type);
    for (int c = 0; c < num_comp; ++c) {
      if (out) memcpy(out + off, pdk_particles_field_data(p, jcu_history_fields[k], c), len);
      off += len;
    }
  }
  const uint8_t *alive = pdk_model_bond_alive(m);
  const size_t nb = (size_t)pdk_families_num_bonds(pdk_model_families(m));
  if (alive) {
    if (out) memcpy(out + off, alive, nb);
    off += nb;
  }
  return off;
}

static inline jcu_snapshot jcu_snapshot_take(pdk_model *m) {
  jcu_snapshot s;
  s.bytes = jcu_snapshot_fill(m, NULL);
  s.data = malloc(s.bytes ? s.bytes : 1);
  if (!s.data) T_FAIL("out of memory");
  jcu_snapshot_fill(m, s.data);
  return s;
}

/* 1 when the model's history and bond state equal the snapshot bit for bit. */
static inline int jcu_snapshot_equal(pdk_model *m, const jcu_snapshot *s) {
  jcu_snapshot now = jcu_snapshot_take(m);
  const int eq = now.bytes == s->bytes && !memcmp(now.data, s->data, s->bytes);
  free(now.data);
  return eq;
}

/* Bond state symmetric (alive i->j == alive j->i) and num_broken equal to the broken count. */
static inline void jcu_check_bond_state(pdk_model *m, const char *what) {
  pdk_families *fam = pdk_model_families(m);
  const pdk_index n = pdk_families_num_particles(fam);
  const pdk_bond_index *start = pdk_families_bond_start(fam);
  const pdk_index *bj = pdk_families_bond_j(fam);
  const uint8_t *alive = pdk_model_bond_alive(m);
  if (!alive) T_FAIL("%s: the model has no bond state", what);
  pdk_bond_index broken = 0;
  for (pdk_index i = 0; i < n; ++i)
    for (pdk_bond_index b = start[i]; b < start[i + 1]; ++b) {
      const pdk_index j = bj[b];
      broken += !alive[b];
      pdk_bond_index r = start[j];
      while (r < start[j + 1] && bj[r] != i)
        ++r;
      T_ASSERT(r < start[j + 1], "%s: bond %d-%d has no reverse", what, (int)i, (int)j);
      T_ASSERT(alive[b] == alive[r], "%s: bond %d-%d is %d from %d and %d from %d", what, (int)i,
               (int)j, alive[b], (int)i, alive[r], (int)j);
    }
  T_ASSERT(broken == pdk_model_num_broken(m), "%s: %lld bonds broken, num_broken says %lld", what,
           (long long)broken, (long long)pdk_model_num_broken(m));
}

/* Connected components of the intact bond graph: comp[i] = smallest index in i's component.
 * Returns the number of components. */
static inline pdk_index jcu_components(pdk_model *m, pdk_index *comp) {
  pdk_families *fam = pdk_model_families(m);
  const pdk_index n = pdk_families_num_particles(fam);
  const pdk_bond_index *start = pdk_families_bond_start(fam);
  const pdk_index *bj = pdk_families_bond_j(fam);
  const uint8_t *alive = pdk_model_bond_alive(m);
  pdk_index *stack = malloc((size_t)n * sizeof *stack);
  if (!stack) T_FAIL("out of memory");
  for (pdk_index i = 0; i < n; ++i)
    comp[i] = -1;
  pdk_index num = 0;
  for (pdk_index s = 0; s < n; ++s) {
    if (comp[s] >= 0) continue;
    ++num;
    pdk_index top = 0;
    stack[top++] = s;
    comp[s] = s;
    while (top) {
      const pdk_index i = stack[--top];
      for (pdk_bond_index b = start[i]; b < start[i + 1]; ++b)
        if ((!alive || alive[b]) && comp[bj[b]] < 0) {
          comp[bj[b]] = s;
          stack[top++] = bj[b];
        }
    }
  }
  free(stack);
  return num;
}

/* Every double component of field `name` finite. */
static inline void jcu_check_finite(pdk_particles *p, const char *name, const char *what) {
  pdk_type type;
  int num_comp;
  if (pdk_particles_field_info(p, name, &type, &num_comp) || type != PDK_F64) return;
  for (int c = 0; c < num_comp; ++c) {
    const double *v = pdk_particles_field_data(p, name, c);
    for (pdk_index i = 0; i < pdk_particles_count(p); ++i)
      T_ASSERT(isfinite(v[i]), "%s: %s[%d] of particle %d is %g", what, name, c, (int)i, v[i]);
  }
}

/* The same bar run with the reference kernels, the CPU's best general path and its stencil path
 * (2 threads each), `steps` steps: build(ctx, stencil, s) makes it. Positions agree with the
 * reference's to 1e-9 of its largest displacement and eps_p to 1e-9 absolute (the variants sum in
 * different orders; round-off grows through the return map and the steps). Returns the
 * reference run's largest eps_p and broken-bond count, for the caller's own preconditions. */
static inline void jcu_kernel_variants(void (*build)(pdk_ctx *, pdk_stencil_mode, jcu_sim *),
                                       long steps, int verbose, double *ep_max,
                                       pdk_bond_index *broken) {
  const char *names[3] = {"ref", NULL, NULL}; /* reference; the CPU's best; its stencil */
  jcu_sim s[3];
  pdk_ctx *ctx[3] = {NULL, NULL, NULL};
  for (int k = 0; k < 3; ++k) {
    pdk_ctx_opts co = pdk_ctx_opts_default();
    co.kernels = names[k];
    co.num_threads = 2;
    char why[512];
    if (pdk_ctx_create(&co, &ctx[k], why, sizeof why)) T_FAIL("pdk_ctx_create: %s", why);
    build(ctx[k], k == 2 ? PDK_STENCIL_ON : PDK_STENCIL_OFF, &s[k]);
    pdk_history h;
    T_OK(ctx[k], pdk_explicit_run(s[k].e, steps, &h));
  }
  const pdk_index n = pdk_particles_count(s[0].p);
  const double *x0[2] = {pdk_particles_field_data(s[0].p, "x", 0),
                         pdk_particles_field_data(s[0].p, "x", 1)};
  const double *e0 = pdk_particles_field_data(s[0].p, "eps_p", 0);
  double umax = 0.0;
  *ep_max = 0.0;
  for (pdk_index i = 0; i < n; ++i) {
    umax = fmax(umax, fabs(x0[0][i] - pdk_particles_X(s[0].p, 0)[i]));
    *ep_max = fmax(*ep_max, e0[i]);
  }
  *broken = pdk_model_num_broken(s[0].m);
  for (int k = 1; k < 3; ++k) {
    const char *what = k == 1 ? "optimized" : "stencil";
    const double *ek = pdk_particles_field_data(s[k].p, "eps_p", 0);
    double dx = 0.0, dep = 0.0;
    for (pdk_index i = 0; i < n; ++i) {
      for (int d = 0; d < 2; ++d)
        dx = fmax(dx, fabs(((const double *)pdk_particles_field_data(s[k].p, "x", d))[i] -
                           x0[d][i]));
      dep = fmax(dep, fabs(ek[i] - e0[i]));
    }
    if (verbose)
      printf("%s: |dx| %.3g of u_max %.3g, |d eps_p| %.3g (eps_p up to %.3g)\n", what, dx, umax,
             dep, *ep_max);
    T_NEAR(dx, 0.0, 0.0, 1e-9 * umax, "%s against ref: positions", what);
    T_NEAR(dep, 0.0, 0.0, 1e-9, "%s against ref: eps_p", what);
  }
  for (int k = 0; k < 3; ++k) {
    jcu_sim_destroy(&s[k]);
    pdk_ctx_destroy(&ctx[k]);
  }
}

#endif
