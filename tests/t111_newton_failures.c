/* Newton: clear failures (body not held, zero-energy modes, a loose piece, bad conditions, CHOLMOD
 * on a non-symmetric tangent), the colored difference tangent (equal to the column-by-column one,
 * with 2 dim colors force passes, far fewer than the unknowns), and the LU path.
 * labels: unit
 */
#include "solvers/static_impl.h"
#include "test_util.h"

typedef struct body {
  pdk_particles *p;
  pdk_families *fam;
  pdk_model *m;
} body;

/* Node-type lattice [0, a] x [0, b] (x [0, c]), spacing 1, sets "left" (x = 0), "ring" (the outer
 * layer), "corner" (the particle at the origin). */
static body build(pdk_ctx *ctx, int dim, double a, double b, double c, double rf,
                  const pdk_model_opts *mo, const pdk_precrack *crack) {
  body bd;
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = dim == 2 ? PDK_LATTICE_SQUARE : PDK_LATTICE_CUBIC;
  lo.node_type = 1;
  lo.spacing = 1.0;
  lo.hi[0] = a;
  lo.hi[1] = b;
  lo.hi[2] = c;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, &bd.p));
  T_OK(ctx, pdk_particles_reorder_morton(bd.p, rf, NULL));
  const double e = 0.25;
  double l0[3] = {-1, -1, -1}, l1[3] = {e, b + 1, c + 1};
  double i0[3] = {e, e, dim == 3 ? e : -1}, i1[3] = {a - e, b - e, dim == 3 ? c - e : 1};
  double o0[3] = {-1, -1, -1}, o1[3] = {e, e, e};
  pdk_region left = pdk_region_box(l0, l1), ring = pdk_region_box(i0, i1),
             corner = pdk_region_box(o0, o1);
  ring.invert = 1;
  T_OK(ctx, pdk_particles_set_define(bd.p, "left", &left, NULL));
  T_OK(ctx, pdk_particles_set_define(bd.p, "ring", &ring, NULL));
  T_OK(ctx, pdk_particles_set_define(bd.p, "corner", &corner, NULL));
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = rf;
  fo.precracks = crack;
  fo.num_precracks = crack ? 1 : 0;
  T_OK(ctx, pdk_families_build(bd.p, &fo, &bd.fam));
  T_OK(ctx, pdk_model_create(bd.p, bd.fam, mo, &bd.m));
  return bd;
}

static void destroy(body *b) {
  pdk_model_destroy(&b->m);
  pdk_families_destroy(&b->fam);
  pdk_particles_destroy(&b->p);
}

static pdk_model_opts model(pdk_model_kind kind) {
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = kind;
  mo.bulk_modulus = 1000.0 / 3.0;
  mo.shear_modulus = 500.0;
  mo.density = 1.0;
  mo.influence = PDK_INFLUENCE_CUBIC;
  mo.stabilization = PDK_STAB_SILLING;
  return mo;
}

static pdk_bc held(const char *set, unsigned components) {
  pdk_bc bc;
  memset(&bc, 0, sizeof bc);
  bc.kind = PDK_BC_DISPLACEMENT;
  bc.set = set;
  bc.components = components;
  return bc;
}

static pdk_bc pulled(unsigned components) { /* unit body force on every particle */
  pdk_bc bc;
  memset(&bc, 0, sizeof bc);
  bc.kind = PDK_BC_BODY_FORCE;
  bc.components = components;
  for (int c = 0; c < 3; ++c)
    bc.value[c] = pdk_tfun_constant(1.0);
  return bc;
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  pdk_static *s = NULL;
  pdk_static_opts so;
  pdk_model_opts mo;
  body b;

  /* 1. Not held: no displacement condition at all, then only u_x on the left edge (y free),
   * then in 3-D one particle fixed (it still rotates about it). */
  mo = model(PDK_MODEL_PMB);
  b = build(ctx, 2, 10, 4, 0, 3.015, &mo, NULL);
  pdk_bc bcs[4] = {pulled(3)};
  so = pdk_static_opts_default(PDK_STATIC_NEWTON);
  so.bcs = bcs;
  so.num_bcs = 1;
  T_FAILS(ctx, pdk_static_create(b.m, &so, &s), PDK_ERR_ARG, "the body is not held");
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "constrain at least"), "%s",
           pdk_ctx_error_message(ctx));
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "translation in x") &&
               strstr(pdk_ctx_error_message(ctx), "translation in y") &&
               strstr(pdk_ctx_error_message(ctx), "rotation about z"),
           "all three rigid motions should be named: %s", pdk_ctx_error_message(ctx));
  T_ASSERT(s == NULL, "no solver on failure");
  bcs[1] = held("set:left", 1);
  so.num_bcs = 2;
  /* u_x on a whole edge stops x and rotation: only the y translation is left */
  T_FAILS(ctx, pdk_static_create(b.m, &so, &s), PDK_ERR_ARG,
          "1 rigid motion free (translation in y)");
  bcs[1] = held("set:left", 3);
  T_OK(ctx, pdk_static_create(b.m, &so, &s)); /* held: fine */
  pdk_static_destroy(&s);
  /* A velocity condition is refused by static solvers. */
  bcs[1].kind = PDK_BC_VELOCITY;
  T_FAILS(ctx, pdk_static_create(b.m, &so, &s), PDK_ERR_ARG, "displacement and body-force");
  destroy(&b);
  b = build(ctx, 3, 4, 3, 3, 1.515, &mo, NULL);
  bcs[1] = held("set:corner", 7);
  T_FAILS(ctx, pdk_static_create(b.m, &so, &s), PDK_ERR_ARG, "rotation about");
  destroy(&b);

  /* 2. Zero-energy modes. A bounded lattice has no exact ones besides rigid motions (one-sided
   * surface families break the periodic patterns), so the "periodic-like" block is the closest
   * thing: the outer layer clamped, every free particle with a full, point-symmetric family as on
   * a periodic lattice, and omega = 1/r^2 at RF 1.5, whose periodic-lattice gradient vanishes on
   * the whole lines q_x = pi and q_y = pi (V-Z: 32 zero eigenvalues at n = 8). Unstabilized, the
   * smallest eigenvalue of this 28 x 28 block is ~1e-6 of the largest diagonal (stabilized: ~1e-2);
   * with singular_rtol = 1e-5 (between the two) Newton must call it singular and blame zero-energy
   * modes, from the shape of the near-null vector; with Silling stabilization it solves. */
  mo = model(PDK_MODEL_CORRESPONDENCE);
  mo.influence = PDK_INFLUENCE_INV_R2;
  mo.stabilization = PDK_STAB_NONE;
  b = build(ctx, 2, 27, 27, 0, 1.5, &mo, NULL);
  bcs[0] = held("set:ring", 3);
  bcs[1] = pulled(1);
  so = pdk_static_opts_default(PDK_STATIC_NEWTON);
  so.bcs = bcs;
  so.num_bcs = 2;
  so.singular_rtol = 1e-5;
  T_OK(ctx, pdk_static_create(b.m, &so, &s));
  T_FAILS(ctx, pdk_static_solve(s), PDK_ERR_NUMERIC, "zero-energy modes");
  if (getenv("PDK_TEST_VERBOSE")) printf("%s\n", pdk_ctx_error_message(ctx));
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "stabilization"), "%s", pdk_ctx_error_message(ctx));
  T_ASSERT(pdk_static_stats_get(s)->null_nonaffine > 0.9, "near-null vector non-affine fraction %g",
           pdk_static_stats_get(s)->null_nonaffine);
  pdk_static_destroy(&s);
  destroy(&b);
  mo.stabilization = PDK_STAB_SILLING;
  b = build(ctx, 2, 27, 27, 0, 1.5, &mo, NULL);
  T_OK(ctx, pdk_static_create(b.m, &so, &s));
  T_OK(ctx, pdk_static_solve(s));
  T_ASSERT(pdk_static_stats_get(s)->min_eig_ratio > 1e-3, "stabilized smallest eigenvalue %g",
           pdk_static_stats_get(s)->min_eig_ratio);
  pdk_static_destroy(&s);
  destroy(&b);

  /* 3. A loose piece: a crack through the whole height cuts a bar in two; only the left part is
   * held. The global check passes, the tangent is singular, and its near-null vector is a rigid
   * motion: the message says a part is not held. */
  mo = model(PDK_MODEL_PMB);
  double seg[4] = {5.5, -1.0, 5.5, 5.0};
  pdk_precrack crack = {2, seg};
  b = build(ctx, 2, 10, 4, 0, 2.015, &mo, &crack);
  bcs[0] = held("set:left", 3);
  bcs[1] = pulled(3);
  so = pdk_static_opts_default(PDK_STATIC_NEWTON);
  so.bcs = bcs;
  so.num_bcs = 2;
  T_OK(ctx, pdk_static_create(b.m, &so, &s));
  T_FAILS(ctx, pdk_static_solve(s), PDK_ERR_NUMERIC, "is not held");
  if (getenv("PDK_TEST_VERBOSE")) printf("%s\n", pdk_ctx_error_message(ctx));
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "rigid motion"), "%s", pdk_ctx_error_message(ctx));
  T_ASSERT(pdk_static_stats_get(s)->null_nonaffine < 0.1, "near-null vector non-affine fraction %g",
           pdk_static_stats_get(s)->null_nonaffine);
  pdk_static_destroy(&s);
  destroy(&b);

  /* 4. The colored tangent: equal to the one built a particle at a time (round-off: both are
   * central differences of the same forces with the same steps; entries agree to 1e-9 of the
   * largest), at 2 dim colors trial passes. 2-D LPS and 3-D correspondence. */
  for (int dim = 2; dim <= 3; ++dim) {
    mo = model(dim == 2 ? PDK_MODEL_LPS : PDK_MODEL_CORRESPONDENCE);
    b = dim == 2 ? build(ctx, 2, 12, 6, 0, 2.015, &mo, NULL)
                 : build(ctx, 3, 5, 3, 3, 1.515, &mo, NULL);
    bcs[0] = held("set:left", dim == 2 ? 3 : 7);
    so = pdk_static_opts_default(PDK_STATIC_NEWTON);
    so.bcs = bcs;
    so.num_bcs = 1;
    so.tangent = PDK_TANGENT_DIFFERENCE; /* LPS has an analytic one (t161) */
    T_OK(ctx, pdk_static_create(b.m, &so, &s));
    int ncol;
    const int *Ap, *Ai;
    const double *Ax;
    const pdk_static_stats *st = pdk_static_stats_get(s);
    long before = st->force_passes;
    T_OK(ctx, pdk_newton_tangent(s, 1, &ncol, &Ap, &Ai, &Ax));
    T_ASSERT(st->force_passes - before == 2L * dim * st->num_colors &&
                 st->passes_per_tangent == 2L * dim * st->num_colors,
             "%dD: %ld passes for %d colors", dim, st->force_passes - before, st->num_colors);
    const int64_t nnz = Ap[ncol];
    double *colored = malloc((size_t)nnz * sizeof *colored), kmax = 0.0;
    memcpy(colored, Ax, (size_t)nnz * sizeof *colored);
    before = st->force_passes;
    T_OK(ctx, pdk_newton_tangent(s, 0, &ncol, &Ap, &Ai, &Ax));
    T_ASSERT(st->force_passes - before == 2L * dim * pdk_particles_count(b.p),
             "reference tangent: one pair of passes per particle and component");
    for (int64_t k = 0; k < nnz; ++k)
      kmax = fmax(kmax, fabs(Ax[k]));
    for (int64_t k = 0; k < nnz; ++k)
      T_NEAR(colored[k], Ax[k], 0.0, 1e-9 * kmax, "%dD tangent entry %lld", dim, (long long)k);
    free(colored);
    pdk_static_destroy(&s);
    destroy(&b);
  }

  /* 5. Coloring count << unknowns: a 2-D LPS plate of 81 x 41 particles with delta = 3.015 h.
   * Colors are bounded by the lattice points within 2 hops delta = 12.06 h of a particle
   * (pi 12.06^2 = 457, plus one); the force passes of a tangent are 2 dim colors, independent of
   * the 6560 unknowns. */
  mo = model(PDK_MODEL_LPS);
  b = build(ctx, 2, 80, 40, 0, 3.015, &mo, NULL);
  bcs[0] = held("set:left", 3);
  so = pdk_static_opts_default(PDK_STATIC_NEWTON);
  so.bcs = bcs;
  so.num_bcs = 1;
  T_OK(ctx, pdk_static_create(b.m, &so, &s));
  {
    const pdk_static_stats *st = pdk_static_stats_get(s);
    int ncol;
    const int *Ap, *Ai;
    const double *Ax;
    const long before = st->force_passes;
    T_OK(ctx, pdk_newton_tangent(s, 1, &ncol, &Ap, &Ai, &Ax));
    const long passes = st->force_passes - before;
    if (getenv("PDK_TEST_VERBOSE"))
      printf("colors %d, passes %ld, unknowns %ld\n", st->num_colors, passes, st->num_unknowns);
    T_ASSERT(st->num_unknowns == 2L * 81 * 41 - 2 * 41, "unknowns %ld", st->num_unknowns);
    T_ASSERT(st->num_colors <= 458, "%d colors exceed the ball bound", st->num_colors);
    T_ASSERT(passes == 4L * st->num_colors, "%ld passes for %d colors", passes, st->num_colors);
    T_ASSERT(passes * 4 <= st->num_unknowns, "%ld passes are not << %ld unknowns", passes,
             st->num_unknowns);
  }
  pdk_static_destroy(&s);
  destroy(&b);

  /* 6. Non-symmetric tangent (hourglass stabilization is not the gradient of an energy): CHOLMOD on
   * request is refused with the reason; auto goes to UMFPACK and converges. */
  mo = model(PDK_MODEL_CORRESPONDENCE);
  mo.stabilization = PDK_STAB_HOURGLASS;
  b = build(ctx, 2, 12, 4, 0, 2.015, &mo, NULL);
  bcs[0] = held("set:left", 3);
  bcs[1] = pulled(1);
  so = pdk_static_opts_default(PDK_STATIC_NEWTON);
  so.bcs = bcs;
  so.num_bcs = 2;
  so.linear_solver = PDK_LINEAR_CHOLMOD;
  T_OK(ctx, pdk_static_create(b.m, &so, &s));
  T_FAILS(ctx, pdk_static_solve(s), PDK_ERR_ARG, "not hyperelastic");
  pdk_static_destroy(&s);
  so.linear_solver = PDK_LINEAR_AUTO;
  T_OK(ctx, pdk_static_create(b.m, &so, &s));
  T_OK(ctx, pdk_static_solve(s));
  T_ASSERT(pdk_static_stats_get(s)->umfpack_factorizations > 0 &&
               pdk_static_stats_get(s)->cholmod_factorizations == 0,
           "hourglass tangent went to CHOLMOD");
  pdk_static_destroy(&s);
  destroy(&b);

  pdk_ctx_destroy(&ctx);
  return 0;
}
