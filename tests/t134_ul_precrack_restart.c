/* Updated-Lagrangian correspondence: pre-cracks across rebuilds, and restart after rebuilds.
 *
 * Pre-cracks. A 2-D 24 x 24 unit lattice with a pre-crack segment from the left edge to the
 * centre along y = 12 (between two rows), delta 3.015. The crack faces are pressed together and
 * sheared along the crack (x = X + shear and closing displacements, up to 0.8 spacings), then the
 * families are rebuilt at x (pdk_model_rebuild). Asserted: the families in x without the crack's
 * rule would hold bonds across it (counted by brute force here: pairs within delta in x whose
 * initial segment crosses the crack; > 0, so the assertion below can fail), and no bond of the
 * rebuilt families crosses the crack in the initial configuration, while the rebuild did change
 * the families (pairs that were not neighbours initially are bonded now). The same in 3-D with a
 * square polygon pre-crack (10 x 10 x 10 lattice).
 *
 * Restart. A 16 x 16 block pulled biaxially by grips (as t133, cubic influence, Silling 0.1,
 * ul_skin 0.1 so that rebuilds happen in both halves): 2 x 300 steps in one go versus 300 steps,
 * checkpoint, everything destroyed and rebuilt, restore, 300 steps. x, v, f, the strain energy,
 * the rebuild count and the current families are bitwise identical (the checkpoint stores the
 * rebuilt families; weights and shape are recomputed from the stored reference of the last
 * rebuild). A ul checkpoint read into a TL model is refused, naming ul.
 * labels: unit physics */
#include <hdf5.h>

#include "corr_util.h"
#include "pdk/explicit.h"
#include "pdk/output.h"

/* 1 if segment p-q crosses the segment a-b in 2-D (proper or touching, not collinear). */
static int seg_cross2(const double p[2], const double q[2], const double a[2], const double b[2]) {
  const double d1 = (q[0] - p[0]) * (a[1] - p[1]) - (q[1] - p[1]) * (a[0] - p[0]);
  const double d2 = (q[0] - p[0]) * (b[1] - p[1]) - (q[1] - p[1]) * (b[0] - p[0]);
  const double d3 = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
  const double d4 = (b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0]);
  if (d3 == 0 && d4 == 0) return 0;
  return d1 * d2 <= 0 && d3 * d4 <= 0;
}

/* 1 if segment p-q crosses the axis-aligned square z = zc, lo <= x, y <= hi (3-D). */
static int seg_cross_square(const double p[3], const double q[3], double zc, double lo, double hi) {
  if ((p[2] - zc) * (q[2] - zc) > 0 || p[2] == q[2]) return 0;
  const double t = (zc - p[2]) / (q[2] - p[2]);
  const double x = p[0] + t * (q[0] - p[0]), y = p[1] + t * (q[1] - p[1]);
  return x >= lo && x <= hi && y >= lo && y <= hi;
}

static int crosses(int dim, const double *const X[3], pdk_index i, pdk_index j, const double *v) {
  if (dim == 2) {
    const double p[2] = {X[0][i], X[1][i]}, q[2] = {X[0][j], X[1][j]};
    return seg_cross2(p, q, v, v + 2);
  }
  const double p[3] = {X[0][i], X[1][i], X[2][i]}, q[3] = {X[0][j], X[1][j], X[2][j]};
  return seg_cross_square(p, q, v[2], v[0], v[6]);
}

static void precrack_case(pdk_ctx *ctx, int dim) {
  const int N = dim == 2 ? 24 : 10;
  const double h = 0.5 * N;
  pdk_particles *p = cu_lattice(ctx, dim, N, 0.0, 1);
  /* 2-D: segment (-1, h) - (h, h); 3-D: square z = h over [-1, e]^2, e = h + 0.1 (vertices in
   * order; e is off every point where a lattice bond meets the plane, so no bond touches an edge
   * of the square and the brute-force predicate below cannot disagree with pdk's on a tie). */
  const double e = h + 0.1;
  const double v2[4] = {-1.0, h, h, h};
  const double v3[12] = {-1, -1, h, e, -1, h, e, e, h, -1, e, h};
  const double *v = dim == 2 ? v2 : v3;
  pdk_precrack pc = {dim == 2 ? 2 : 4, v};
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = 3.015;
  fo.precracks = &pc;
  fo.num_precracks = 1;
  pdk_families *fam = NULL;
  T_OK(ctx, pdk_families_build(p, &fo, &fam));
  pdk_model_opts o = cu_opts(PDK_LAW_NEO_HOOKE, PDK_INFLUENCE_CUBIC, PDK_STAB_SILLING, 0.1);
  o.connectivity = PDK_CONNECTIVITY_UL;
  o.ul_skin = 0.0;
  pdk_model *m = cu_model(ctx, p, fam, &o);
  const pdk_index n = pdk_particles_count(p);
  const double *X[3] = {pdk_particles_X(p, 0), pdk_particles_X(p, 1),
                        dim == 3 ? pdk_particles_X(p, 2) : NULL};
  double *x[3] = {cu_field(p, "x", 0), cu_field(p, "x", 1), dim == 3 ? cu_field(p, "x", 2) : NULL};
  /* Close the crack (the faces move towards it by 0.4 each) and shear along it (0.8 between the
   * faces), within a band of 3 spacings about the crack's line or plane. */
  const int ax = dim - 1; /* the axis normal to the crack */
  for (pdk_index i = 0; i < n; ++i) {
    const double s = X[ax][i] - h, w = fabs(s) < 3.0 ? 1.0 - fabs(s) / 3.0 : 0.0;
    x[ax][i] = X[ax][i] - (s > 0 ? 0.4 : -0.4) * w;
    x[0][i] = X[0][i] + (s > 0 ? 0.4 : -0.4) * w;
  }
  /* Pairs within delta in x whose initial segment crosses the crack: what a rebuild without the
   * crack's rule would bond. */
  long would_cross = 0;
  const double r2max = 3.015 * 3.015;
  for (pdk_index i = 0; i < n; ++i)
    for (pdk_index j = 0; j < n; ++j) {
      if (i == j) continue;
      double r2 = 0;
      for (int a = 0; a < dim; ++a) r2 += (x[a][j] - x[a][i]) * (x[a][j] - x[a][i]);
      if (r2 <= r2max && crosses(dim, X, i, j, v)) ++would_cross;
    }
  T_ASSERT(would_cross > 0, "%d-D: the closing motion brings no pair across the crack", dim);
  T_OK(ctx, pdk_model_rebuild(m));
  T_ASSERT(pdk_model_num_rebuilds(m) == 1, "%d-D: rebuilds %ld", dim, pdk_model_num_rebuilds(m));
  pdk_families *cur = pdk_model_current_families(m);
  const pdk_bond_index *bs = pdk_families_bond_start(cur), *bs0 = pdk_families_bond_start(fam);
  const pdk_index *bj = pdk_families_bond_j(cur), *bj0 = pdk_families_bond_j(fam);
  long crossing = 0, fresh = 0, initial = 0;
  for (pdk_index i = 0; i < n; ++i)
    for (pdk_bond_index b = bs0[i]; b < bs0[i + 1]; ++b) initial += crosses(dim, X, i, bj0[b], v);
  T_ASSERT(initial == 0, "%d-D: %ld initial bonds cross the pre-crack (the test's predicate "
           "disagrees with the families')", dim, initial);
  for (pdk_index i = 0; i < n; ++i)
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      const pdk_index j = bj[b];
      crossing += crosses(dim, X, i, j, v);
      int old = 0;
      for (pdk_bond_index c = bs0[i]; c < bs0[i + 1] && !old; ++c) old = bj0[c] == j;
      fresh += !old;
    }
  if (getenv("PDK_TEST_VERBOSE"))
    printf("%d-D: %ld pairs would cross the crack, %ld rebuilt bonds do; %ld new bonds\n", dim,
           would_cross, crossing, fresh);
  T_ASSERT(crossing == 0, "%d-D: %ld rebuilt bonds cross the pre-crack (it healed)", dim, crossing);
  T_ASSERT(fresh > 0, "%d-D: the rebuild created no new bond", dim);
  T_OK(ctx, pdk_model_force(m, NULL));
  int bad = 0;
  for (int a = 0; a < dim; ++a)
    for (pdk_index i = 0; i < n; ++i) bad += !isfinite(cu_field(p, "f", a)[i]);
  T_ASSERT(!bad, "%d-D: %d non-finite forces after the rebuild", dim, bad);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
}

/* ---- restart ---------------------------------------------------------------------------------- */

#define RN 16

typedef struct sim {
  pdk_particles *p;
  pdk_families *fam;
  pdk_model *m;
  pdk_explicit *e;
} sim;

static pdk_bc bcs[4];

static void build(pdk_ctx *ctx, pdk_connectivity mode, sim *s) {
  s->m = cu_pulled_block(ctx, RN, mode, bcs, &s->p, &s->fam);
  pdk_explicit_opts eo = pdk_explicit_opts_default();
  eo.bcs = bcs;
  eo.num_bcs = 4;
  T_OK(ctx, pdk_explicit_create(s->m, &eo, &s->e));
}

static void destroy(sim *s) {
  pdk_explicit_destroy(&s->e);
  pdk_model_destroy(&s->m);
  pdk_families_destroy(&s->fam);
  pdk_particles_destroy(&s->p);
}

static void same_field(pdk_particles *a, pdk_particles *b, const char *name) {
  for (int c = 0; c < pdk_particles_dim(a); ++c)
    T_ASSERT(!memcmp(cu_field(a, name, c), cu_field(b, name, c),
                     (size_t)pdk_particles_count(a) * sizeof(double)),
             "restart: field %s[%d] differs from the uninterrupted run", name, c);
}

static void restart_case(pdk_ctx *ctx) {
  const long half = 300;
  const char *path = "t134_ul.ckpt.h5";
  sim a, b;
  pdk_history ha, hb;
  build(ctx, PDK_CONNECTIVITY_UL, &a);
  T_OK(ctx, pdk_explicit_run(a.e, half, NULL));
  const long r_half = pdk_model_num_rebuilds(a.m);
  T_OK(ctx, pdk_checkpoint_write(ctx, path, a.e, NULL));
  T_OK(ctx, pdk_explicit_run(a.e, half, &ha));
  const long r_end = pdk_model_num_rebuilds(a.m);
  if (getenv("PDK_TEST_VERBOSE"))
    printf("restart: %ld rebuilds in the first %ld steps, %ld in all\n", r_half, half, r_end);
  T_ASSERT(r_half >= 1 && r_end > r_half, "restart: rebuilds %ld then %ld (need both halves)",
           r_half, r_end);

  build(ctx, PDK_CONNECTIVITY_UL, &b);
  T_OK(ctx, pdk_checkpoint_read(ctx, path, b.e));
  T_ASSERT(pdk_model_num_rebuilds(b.m) == r_half, "restart: restored rebuild count %ld, not %ld",
           pdk_model_num_rebuilds(b.m), r_half);
  T_OK(ctx, pdk_explicit_run(b.e, half, &hb));
  T_ASSERT(pdk_model_num_rebuilds(b.m) == r_end, "restart: %ld rebuilds, uninterrupted %ld",
           pdk_model_num_rebuilds(b.m), r_end);
  same_field(a.p, b.p, "x");
  same_field(a.p, b.p, "v");
  same_field(a.p, b.p, "f");
  T_ASSERT(!memcmp(&ha.strain, &hb.strain, sizeof ha.strain) &&
               !memcmp(&ha.kinetic, &hb.kinetic, sizeof ha.kinetic),
           "restart: energies %.17g %.17g vs %.17g %.17g", ha.strain, ha.kinetic, hb.strain,
           hb.kinetic);
  pdk_families *fa = pdk_model_current_families(a.m), *fb = pdk_model_current_families(b.m);
  const pdk_index n = pdk_particles_count(a.p);
  T_ASSERT(pdk_families_num_bonds(fa) == pdk_families_num_bonds(fb) &&
               !memcmp(pdk_families_bond_start(fa), pdk_families_bond_start(fb),
                       ((size_t)n + 1) * sizeof(pdk_bond_index)) &&
               !memcmp(pdk_families_bond_j(fa), pdk_families_bond_j(fb),
                       (size_t)pdk_families_num_bonds(fa) * sizeof(pdk_index)),
           "restart: the current families differ");
  destroy(&b);

  /* A ul checkpoint does not fit a TL simulation. */
  build(ctx, PDK_CONNECTIVITY_TL, &b);
  T_FAILS(ctx, pdk_checkpoint_read(ctx, path, b.e), PDK_ERR_ARG, "ul");
  destroy(&b);
  destroy(&a);
  remove(path);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  precrack_case(ctx, 2);
  precrack_case(ctx, 3);
  restart_case(ctx);
  pdk_ctx_destroy(&ctx);
  return 0;
}
