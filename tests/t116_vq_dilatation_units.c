/* Dilatation laws with any influence function (src/models/model_dil2.c), the smoothing post-process
 * (pdk_smooth_field), per-particle prescribed values (pdk_bc.scale_field) and the V-Q8
 * pressurized crack at a small size.
 * labels: physics threads
 *
 * 1. Silling's plane-strain law with w = 1/r (lps_use_influence = 1, the paper's Inv up to the
 *    factor delta, which cancels in w/m) gives the forces of pdk's LAMMPS-style LPS in 2-D: same
 *    formulas, different code; tolerance 1e-12 of the largest force (summation order differs).
 * 2. Rigid rotation (30 degrees): zero forces up to round-off: the extension r - r0 of a bond at
 *    |x| ~ 10 carries ~1e-15 absolute error, a strain noise ~1e-14, i.e. ~1e-11 of the forces of
 *    the 1e-3 stretch; tolerance 1e-10 of those (measured 1.1e-12).
 * 3. Forces are the energy gradient: V_i f_i = -dE/dx_i by central differences on a jittered
 *    lattice under a random deformation of 1e-3, for Silling (cubic w) and Oterkus (both a):
 *    tolerance 1e-6 relative (difference truncation ~ (step/strain)^2 ~ 1e-8, round-off ~1e-9).
 * 4. Isotropic stretch s = 1e-3: Silling and Oterkus with the calibrated a have the exact
 *    plane-strain energy 2 (lambda + mu) s^2 per unit area at every particle, whatever its family
 *    (theta = 2s and the deviatoric part vanishes exactly): tolerance 1e-10.
 * 5. 1 and 2 threads give bitwise equal forces and energies.
 * 6. Smoothing keeps a constant field exactly and an affine field at particles with full
 *    (point-symmetric) families, to 1e-12; refuses equal in/out names.
 * 7. scale_field: an affine displacement prescribed on the outer two rows of a block (RF 1.5,
 *    correspondence) is the exact solution everywhere (rows >= 3 have families of full-family
 *    particles only, so the affine field is in equilibrium there): 1e-8 relative. The explicit
 *    solver refuses scale_field.
 * 8. V-Q8 at NP = 50: Silling (cubic w, RF 3.5) whole-domain error 0.353 against 0.379 from the
 *    authors' code at the same NP (section 4.2 of the paper's supplementary code; not a published
 *    target, but the same discretization): tolerance 15% (the authors prescribed the same rows and
 *    pressure, but details such as the tip bonds may differ); the F-law at RF 1.5, NP 100: the
 *    linear-w smoothing lowers the error near the crack (Table 7: by 3x at NP 200; 0.32 -> 0.19
 *    here).
 */
#include "test_util.h"
#include "vq_util.h"

typedef struct fixture {
  pdk_particles *p;
  pdk_families *fam;
  pdk_model *m;
} fixture;

static void make(pdk_ctx *ctx, fixture *f, int n, double rf, double jitter, pdk_model_opts mo) {
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.spacing = 1.0;
  lo.hi[0] = n;
  lo.hi[1] = n;
  lo.jitter = jitter;
  lo.seed = 7;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, &f->p));
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = rf;
  T_OK(ctx, pdk_families_build(f->p, &fo, &f->fam));
  T_OK(ctx, pdk_model_create(f->p, f->fam, &mo, &f->m));
}

static void drop(fixture *f) {
  pdk_model_destroy(&f->m);
  pdk_families_destroy(&f->fam);
  pdk_particles_destroy(&f->p);
}

static pdk_model_opts opts(pdk_model_kind kind, pdk_influence w, pdk_oterkus_a oa) {
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = kind;
  mo.bulk_modulus = 70.0;
  mo.shear_modulus = 30.0;
  mo.density = 1.0;
  mo.influence = w;
  mo.lps_use_influence = kind == PDK_MODEL_LPS && w != PDK_INFLUENCE_CONSTANT;
  mo.oterkus_a = oa;
  return mo;
}

/* x = X + u(X), u a fixed smooth non-affine field of amplitude amp. */
static void deform(fixture *f, double amp) {
  const pdk_index n = pdk_particles_count(f->p);
  const double *X = pdk_particles_X(f->p, 0), *Y = pdk_particles_X(f->p, 1);
  double *x = pdk_particles_field_data(f->p, "x", 0), *y = pdk_particles_field_data(f->p, "x", 1);
  for (pdk_index i = 0; i < n; ++i) {
    x[i] = X[i] + amp * (0.7 * X[i] + 0.3 * Y[i] + 2.0 * sin(0.9 * X[i] + 0.4 * Y[i]));
    y[i] = Y[i] + amp * (-0.2 * X[i] + 0.5 * Y[i] + 1.5 * cos(0.5 * X[i] - 0.8 * Y[i]));
  }
}

static double maxabs(fixture *f) {
  double m = 0;
  for (int c = 0; c < 2; ++c) {
    const double *g = pdk_particles_field_data(f->p, "f", c);
    for (pdk_index i = 0; i < pdk_particles_count(f->p); ++i) m = fmax(m, fabs(g[i]));
  }
  return m;
}

static void check_gradient(pdk_ctx *ctx, pdk_model_opts mo, const char *what) {
  fixture f;
  make(ctx, &f, 9, 2.5, 0.2, mo);
  deform(&f, 1e-3);
  T_OK(ctx, pdk_model_force_trial(f.m, NULL));
  const double fmax = maxabs(&f);
  const double *V = pdk_particles_volume(f.p);
  const int probes[3] = {0, 40, 77};
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 2; ++c) {
      const pdk_index i = probes[k];
      double *x = pdk_particles_field_data(f.p, "x", c);
      T_OK(ctx, pdk_model_force_trial(f.m, NULL));
      const double fi = ((const double *)pdk_particles_field_data(f.p, "f", c))[i];
      const double x0 = x[i], step = 1e-6;
      double ep, em;
      x[i] = x0 + step;
      T_OK(ctx, pdk_model_force_trial(f.m, &ep));
      x[i] = x0 - step;
      T_OK(ctx, pdk_model_force_trial(f.m, &em));
      x[i] = x0;
      T_NEAR(V[i] * fi, -(ep - em) / (2 * step), 0.0, 1e-6 * V[i] * fmax,
             "%s: particle %d component %d, V f vs -dE/dx", what, (int)i, c);
    }
  drop(&f);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2), *ctx1 = t_ctx(1);

  /* 1. Silling with w = 1/r equals pdk's LAMMPS-style 2-D LPS */
  {
    fixture a, b;
    make(ctx, &a, 10, 3.015, 0.2, opts(PDK_MODEL_LPS, PDK_INFLUENCE_CONSTANT, 0));
    pdk_model_opts mo = opts(PDK_MODEL_LPS, PDK_INFLUENCE_INV_R, 0);
    make(ctx, &b, 10, 3.015, 0.2, mo);
    deform(&a, 1e-3);
    deform(&b, 1e-3);
    T_OK(ctx, pdk_model_force_trial(a.m, NULL));
    T_OK(ctx, pdk_model_force_trial(b.m, NULL));
    const double fm = maxabs(&a);
    T_ASSERT(fm > 0, "no force under the deformation");
    for (int c = 0; c < 2; ++c) {
      const double *fa = pdk_particles_field_data(a.p, "f", c), *fb = pdk_particles_field_data(b.p, "f", c);
      for (pdk_index i = 0; i < pdk_particles_count(a.p); ++i)
        T_NEAR(fb[i], fa[i], 0.0, 1e-12 * fm, "particle %d comp %d: Silling(1/r) vs LPS", (int)i, c);
    }
    drop(&a);
    drop(&b);
  }

  /* 2, 4, 5: rotation, isotropic energy, threads */
  const pdk_model_opts cases[3] = {opts(PDK_MODEL_LPS, PDK_INFLUENCE_CUBIC, 0),
                                   opts(PDK_MODEL_OTERKUS, PDK_INFLUENCE_LINEAR, PDK_OTERKUS_A_PUBLISHED),
                                   opts(PDK_MODEL_OTERKUS, PDK_INFLUENCE_CUBIC, PDK_OTERKUS_A_CALIBRATED)};
  for (int k = 0; k < 3; ++k) {
    fixture f, g;
    make(ctx, &f, 8, 2.5, 0.2, cases[k]);
    make(ctx1, &g, 8, 2.5, 0.2, cases[k]);
    const pdk_index n = pdk_particles_count(f.p);
    const double *X = pdk_particles_X(f.p, 0), *Y = pdk_particles_X(f.p, 1);
    double *x = pdk_particles_field_data(f.p, "x", 0), *y = pdk_particles_field_data(f.p, "x", 1);
    const double s = 1e-3;
    double area = 0, e = 0;
    for (pdk_index i = 0; i < n; ++i) {
      x[i] = (1 + s) * X[i];
      y[i] = (1 + s) * Y[i];
      area += pdk_particles_volume(f.p)[i];
    }
    T_OK(ctx, pdk_model_force_trial(f.m, &e));
    const double fs = maxabs(&f);
    const double K = 70.0, G = 30.0, lm = K - 2.0 * G / 3.0 + G;
    if (k != 1) T_NEAR(e, 2.0 * lm * s * s * area, 1e-10, 0.0, "case %d: isotropic stretch energy", k);
    const double c30 = cos(M_PI / 6), s30 = sin(M_PI / 6);
    for (pdk_index i = 0; i < n; ++i) {
      x[i] = c30 * X[i] - s30 * Y[i] + 3.0;
      y[i] = s30 * X[i] + c30 * Y[i] - 1.0;
    }
    T_OK(ctx, pdk_model_force_trial(f.m, &e));
    T_ASSERT(maxabs(&f) <= 1e-10 * fs, "case %d: rotation leaves force %g (stretch %g)", k, maxabs(&f), fs);
    deform(&f, 1e-3);
    deform(&g, 1e-3);
    double e1 = 0, e2 = 0;
    T_OK(ctx, pdk_model_force_trial(f.m, &e2));
    T_OK(ctx1, pdk_model_force_trial(g.m, &e1));
    T_ASSERT(e1 == e2, "case %d: energies differ between 1 and 2 threads", k);
    for (int c = 0; c < 2; ++c)
      T_ASSERT(!memcmp(pdk_particles_field_data(f.p, "f", c), pdk_particles_field_data(g.p, "f", c),
                       (size_t)n * sizeof(double)),
               "case %d: forces differ between 1 and 2 threads", k);
    drop(&f);
    drop(&g);
  }

  /* 3. forces are the energy gradient */
  check_gradient(ctx, cases[0], "Silling cubic");
  check_gradient(ctx, cases[1], "Oterkus published");
  check_gradient(ctx, cases[2], "Oterkus calibrated");

  /* errors */
  {
    pdk_lattice_opts lo = pdk_lattice_opts_default();
    lo.type = PDK_LATTICE_CUBIC;
    lo.spacing = 1.0;
    lo.hi[0] = lo.hi[1] = lo.hi[2] = 3;
    pdk_particles *p;
    pdk_families *fam;
    pdk_model *m = NULL;
    T_OK(ctx, pdk_lattice_create(ctx, &lo, &p));
    pdk_families_opts fo = pdk_families_opts_default();
    fo.horizon = 1.5;
    T_OK(ctx, pdk_families_build(p, &fo, &fam));
    pdk_model_opts mo = opts(PDK_MODEL_OTERKUS, PDK_INFLUENCE_CUBIC, 0);
    T_FAILS(ctx, pdk_model_create(p, fam, &mo, &m), PDK_ERR_UNSUPPORTED, "2-D");
    pdk_families_destroy(&fam);
    pdk_particles_destroy(&p);
  }

  /* 6. smoothing */
  {
    fixture f;
    make(ctx, &f, 12, 2.5, 0.0, opts(PDK_MODEL_LPS, PDK_INFLUENCE_CUBIC, 0));
    const pdk_index n = pdk_particles_count(f.p);
    T_OK(ctx, pdk_particles_field_add(f.p, "u", PDK_F64, 2));
    double *u = pdk_particles_field_data(f.p, "u", 0), *v = pdk_particles_field_data(f.p, "u", 1);
    const double *X = pdk_particles_X(f.p, 0), *Y = pdk_particles_X(f.p, 1);
    for (pdk_index i = 0; i < n; ++i) {
      u[i] = 2.5;
      v[i] = 0.3 * X[i] - 0.7 * Y[i] + 1.0;
    }
    const pdk_influence ws[3] = {PDK_INFLUENCE_CONSTANT, PDK_INFLUENCE_LINEAR, PDK_INFLUENCE_INV_R};
    const pdk_bond_index *bs = pdk_families_bond_start(f.fam);
    for (int k = 0; k < 3; ++k) {
      T_OK(ctx, pdk_smooth_field(f.p, f.fam, ws[k], 0.5, "u", "us"));
      const double *us = pdk_particles_field_data(f.p, "us", 0), *vs = pdk_particles_field_data(f.p, "us", 1);
      for (pdk_index i = 0; i < n; ++i) {
        T_NEAR(us[i], 2.5, 1e-14, 0.0, "smoothing a constant, w %d, particle %d", k, (int)i);
        if (bs[i + 1] - bs[i] == 20) /* full family at RF 2.5 */
          T_NEAR(vs[i], v[i], 0.0, 1e-12 * 10, "smoothing an affine field, w %d, particle %d", k, (int)i);
      }
    }
    T_FAILS(ctx, pdk_smooth_field(f.p, f.fam, PDK_INFLUENCE_LINEAR, 0.5, "u", "u"), PDK_ERR_ARG,
            "different");
    drop(&f);
  }

  /* 7. scale_field */
  {
    fixture f;
    pdk_model_opts mo = opts(PDK_MODEL_CORRESPONDENCE, PDK_INFLUENCE_CUBIC, 0);
    make(ctx, &f, 14, 1.5, 0.0, mo);
    const pdk_index n = pdk_particles_count(f.p);
    const double *X = pdk_particles_X(f.p, 0), *Y = pdk_particles_X(f.p, 1);
    T_OK(ctx, pdk_particles_field_add(f.p, "u_a", PDK_F64, 2));
    T_OK(ctx, pdk_particles_field_add(f.p, "set:outer2", PDK_U8, 1));
    double *ua = pdk_particles_field_data(f.p, "u_a", 0), *va = pdk_particles_field_data(f.p, "u_a", 1);
    uint8_t *outer = pdk_particles_field_data(f.p, "set:outer2", 0);
    for (pdk_index i = 0; i < n; ++i) {
      ua[i] = 1e-4 * (X[i] + 0.5 * Y[i]);
      va[i] = 1e-4 * (-0.3 * X[i] + 0.8 * Y[i]);
      outer[i] = X[i] < 2 || Y[i] < 2 || X[i] > 12 || Y[i] > 12;
    }
    pdk_bc bc;
    memset(&bc, 0, sizeof bc);
    bc.kind = PDK_BC_DISPLACEMENT;
    bc.set = "set:outer2";
    bc.components = 3;
    bc.value[0] = bc.value[1] = pdk_tfun_constant(1.0);
    bc.scale_field = "u_a";
    pdk_static_opts so = pdk_static_opts_default(PDK_STATIC_NEWTON);
    so.bcs = &bc;
    so.num_bcs = 1;
    pdk_static *s;
    T_OK(ctx, pdk_static_create(f.m, &so, &s));
    T_OK(ctx, pdk_static_solve(s));
    const double *x = pdk_particles_field_data(f.p, "x", 0), *y = pdk_particles_field_data(f.p, "x", 1);
    for (pdk_index i = 0; i < n; ++i) {
      T_NEAR(x[i] - X[i], ua[i], 1e-8, 1e-14, "scale_field: u_x at particle %d", (int)i);
      T_NEAR(y[i] - Y[i], va[i], 1e-8, 1e-14, "scale_field: u_y at particle %d", (int)i);
    }
    pdk_static_destroy(&s);
    pdk_explicit_opts eo = pdk_explicit_opts_default();
    eo.bcs = &bc;
    eo.num_bcs = 1;
    eo.dt = 1e-3;
    pdk_explicit *e = NULL;
    T_FAILS(ctx, pdk_explicit_create(f.m, &eo, &e), PDK_ERR_UNSUPPORTED, "static solvers only");
    drop(&f);
  }

  /* 8. V-Q8 pressurized crack at small sizes */
  {
    vq_case c = {VQ_CRACK, VQ_SILLING, PDK_INFLUENCE_CUBIC, 3.5, 50, 0, 2, 0.0, 0};
    vq_result r;
    T_ASSERT(vq_run(ctx, &c, &r) == 0, "crack, Silling, NP 50");
    if (getenv("PDK_TEST_VERBOSE")) printf("Silling RF 3.5 NP 50: error %.4f\n", r.err_all);
    T_NEAR(r.err_all, 0.379, 0.15, 0.0, "Silling crack error at NP 50 vs the authors' code");
    vq_case cf = {VQ_CRACK, VQ_F, PDK_INFLUENCE_CUBIC, 1.5, 100, 0, 2, 0.0, 0};
    T_ASSERT(vq_run(ctx, &cf, &r) == 0, "crack, F, NP 100");
    if (getenv("PDK_TEST_VERBOSE"))
      printf("F RF 1.5 NP 100: window error %.4f, linear-smoothed %.4f, opening %.4f\n", r.err_win,
             r.err_win_s[1], r.max_opening);
    T_ASSERT(r.err_win_s[1] < 0.75 * r.err_win, "smoothing: %.4f -> %.4f", r.err_win, r.err_win_s[1]);
    /* exact opening 2 P a / E = 1.1667 mm at the centre; the row next to the crack is h/2 off
     * the face and the F-law is too soft near the cut bonds: within 15% */
    T_NEAR(r.max_opening, 2.0 * VQ_CP * 0.5 * VQ_CL / VQ_CE, 0.15, 0.0, "crack opening");
  }
  pdk_ctx_destroy(&ctx1);
  pdk_ctx_destroy(&ctx);
  return 0;
}
