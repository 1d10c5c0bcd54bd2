/* V-Q problems of Queiruga & Moridis 2017 (docs/validation/targets.md V-Q), shared by the
 * tests t113, t116, t117, t118 and the study program bench/study_vq.c. Units N-mm-GPa (forces in kN).
 *
 * Constant-strain blocks (section 5, Table 1, Fig. 5): H = W = 10 mm, E = 1000 GPa, nu = 0, plane
 * strain, T = 1e-3 GPa; node-type square grid of (NP+1)^2 particles, h = W/NP (particles on the
 * boundary lines); traction as a body force b = T W / (N_edge V) on the edge row (eq. (22));
 * Dirichlet conditions on single rows/columns (eliminated by the Newton solver).
 *   uniaxial:  bottom clamped, sides u_x = 0, top b_y = -T W/(N V); probe mean u_y, top, 0.4-0.6 W;
 *              exact -T H (1+nu)(1-2nu)/(E(1-nu)) = -1e-5 mm
 *   isotropic: bottom u_y = 0, left u_x = 0, top b_y and right b_x compressive; probe mean u_x on
 *              the right edge, 0.4-0.6 H; exact -T H (1 - nu - 2nu^2)/E = -1e-5 mm
 *   shear:     bottom clamped, sides u_y = 0, top b_x = +T W/(N V); probe mean u_x, top, 0.4-0.6 W;
 *              exact T H / G = 2e-5 mm
 * Pressurized crack (section 6; W = H = 16000 mm as the authors' analysis, not the 160 m printed in
 * Table 6; notes 4.2): E = 60 GPa, nu = 0, P = 0.1 GPa, L = 700 mm centred and horizontal;
 * cell-type grid NP x NP (NP even: the crack line lies between rows), bonds crossing the crack do
 * not exist (alpha = 0), bond pressure P/|xi| on the cut nearest-neighbour (vertical) bonds, i.e.
 * a body force +-P/h on the particles of the two rows next to the crack with |x - x_c| <= a, and
 * the Westergaard displacements prescribed on the outermost row/column of every side.
 */
#ifndef PDK_VQ_UTIL_H
#define PDK_VQ_UTIL_H

#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "pdk/pdk.h"

typedef enum vq_problem { VQ_UNIAXIAL = 0, VQ_ISOTROPIC = 1, VQ_SHEAR = 2, VQ_CRACK = 3 } vq_problem;
typedef enum vq_law { VQ_F = 0, VQ_SILLING = 1, VQ_OTERKUS = 2 } vq_law;

static const char *const vq_problem_name[4] = {"uniaxial", "isotropic", "shear", "crack"};
static const char *const vq_law_name[3] = {"F-based", "Silling", "Oterkus"};
/* The paper's five influence functions (Table 2), in its order. */
static const pdk_influence vq_omega[5] = {PDK_INFLUENCE_CONSTANT, PDK_INFLUENCE_INV_R,
                                          PDK_INFLUENCE_LINEAR, PDK_INFLUENCE_QUADRATIC,
                                          PDK_INFLUENCE_CUBIC};
static const char *const vq_omega_name[5] = {"Const", "Inv", "Linear", "Quadr", "Cubic"};

typedef struct vq_case {
  vq_problem problem;
  vq_law law;
  pdk_influence omega;
  double rf; /* delta / h */
  int np;    /* h = W / np */
  pdk_oterkus_a oterkus_a;
  int threads;
  double crack_shift; /* crack: its centre moved along x by this many spacings (0: W/2) */
  int crack_rows;     /* crack: outer rows/columns holding the exact field (0 or 1: one) */
} vq_case;

typedef struct vq_result {
  double probe, exact, rel_error; /* constant-strain problems */
  int probe_count;                 /* particles averaged by the probe */
  double spurious;  /* shear: max |u_y| over the block / |exact top u_x| */
  double spurious_centre; /* the same on the column(s) nearest x = W/2 (within h/2) */
  double err_all;   /* crack: sqrt(sum |u - u_a|^2 / sum |u_a|^2) over all particles */
  double err_win;   /* crack: the same over |x - x_c|, |y - y_c| <= L (Table 7's window) */
  double err_win_s[3], err_all_s[3]; /* crack, after smoothing with const, linear, cubic w */
  double max_opening;                /* crack: max u_y over particles above the crack */
  pdk_index n;
  double seconds;
  long tangent_nnz;
} vq_result;

#define VQ_W 10.0
#define VQ_E 1000.0
#define VQ_T 1e-3
#define VQ_CW 16000.0
#define VQ_CE 60.0
#define VQ_CP 0.1
#define VQ_CL 700.0

/* Westergaard: plane strain, nu = 0 unless given; displacement at (dx, dy) from the crack centre.
 * Evaluated at z = |dx| + i|dy|, signs restored (the authors' way around the branch cut). */
static inline void vq_westergaard(double dx, double dy, double P, double a, double E, double nu,
                           double u[2]) {
  const double G = E / (2.0 * (1.0 + nu));
  const double complex z = fabs(dx) + I * fabs(dy);
  const double complex root = csqrt(z * z - a * a);
  const double complex Zh = P * (root - z), Z = P * (z / root - 1.0);
  const double yy = fabs(dy);
  u[0] = copysign(1.0, dx) * ((1.0 - 2.0 * nu) * creal(Zh) - yy * cimag(Z)) / (2.0 * G);
  u[1] = copysign(1.0, dy) * (2.0 * (1.0 - nu) * cimag(Zh) - yy * creal(Z)) / (2.0 * G);
}

static inline int vq_fail(pdk_ctx *ctx, const char *what) {
  fprintf(stderr, "vq: %s failed: %s\n", what, pdk_ctx_error_message(ctx));
  return 1;
}
#define VQ_OK(ctx, expr)                                                                          \
  do {                                                                                            \
    if ((expr) != PDK_SUCCESS) return vq_fail(ctx, #expr);                                        \
  } while (0)

static inline int vq_define_box(pdk_particles *p, const char *name, double x0, double y0, double x1,
                         double y1, pdk_index *count) {
  double lo[3] = {x0, y0, -1}, hi[3] = {x1, y1, 1};
  pdk_region r = pdk_region_box(lo, hi);
  return pdk_particles_set_define(p, name, &r, count);
}

/* Mean and max helpers over a set of particles selected by a box. */
static inline double vq_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Solves one case with the Newton solver; 0 on success. */
static inline int vq_run(pdk_ctx *ctx, const vq_case *c, vq_result *res) {
  memset(res, 0, sizeof *res);
  const double t0 = vq_now();
  const int crack = c->problem == VQ_CRACK;
  const double W = crack ? VQ_CW : VQ_W, H = W, h = W / c->np, delta = c->rf * h;
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.node_type = crack ? 0 : 1;
  lo.spacing = h;
  lo.hi[0] = W;
  lo.hi[1] = H;
  pdk_particles *p = NULL;
  pdk_families *fam = NULL;
  pdk_model *m = NULL;
  pdk_static *s = NULL;
  VQ_OK(ctx, pdk_lattice_create(ctx, &lo, &p));
  VQ_OK(ctx, pdk_particles_reorder_morton(p, pdk_families_cell_edge(p, delta), NULL));
  const pdk_index n = res->n = pdk_particles_count(p);
  const double V = pdk_particles_volume(p)[0];
  const double e = 0.25 * h, big = 2.0 * W;
  const double a = 0.5 * VQ_CL, xc = 0.5 * W + (crack ? c->crack_shift * h : 0.0), yc = 0.5 * H;
  pdk_bc bcs[8];
  memset(bcs, 0, sizeof bcs);
  int nb = 0;
  pdk_index count = 0;
#define VQ_DISP(setname, comps)                                                                   \
  do {                                                                                            \
    bcs[nb].kind = PDK_BC_DISPLACEMENT;                                                           \
    bcs[nb].set = setname;                                                                        \
    bcs[nb].components = comps;                                                                   \
    ++nb;                                                                                         \
  } while (0)
#define VQ_BODY(setname, comp, val)                                                             \
  do {                                                                                            \
    bcs[nb].kind = PDK_BC_BODY_FORCE;                                                             \
    bcs[nb].set = setname;                                                                        \
    bcs[nb].components = 1u << (comp);                                                            \
    bcs[nb].value[comp] = pdk_tfun_constant(val);                                               \
    ++nb;                                                                                         \
  } while (0)
  pdk_precrack pc;
  double pcv[4] = {xc - a, yc, xc + a, yc};
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = delta;
  if (crack) {
    pc.num_vertices = 2;
    pc.vertices = pcv;
    fo.precracks = &pc;
    fo.num_precracks = 1;
  }
  switch (c->problem) {
  case VQ_UNIAXIAL:
    VQ_OK(ctx, vq_define_box(p, "bottom", -big, -big, big, e, NULL));
    VQ_OK(ctx, vq_define_box(p, "sides", -big, e, e, big, NULL));
    VQ_OK(ctx, vq_define_box(p, "sides2", W - e, e, big, big, NULL));
    VQ_OK(ctx, vq_define_box(p, "top", -big, H - e, big, big, &count));
    VQ_DISP("set:bottom", 3);
    VQ_DISP("set:sides", 1);
    VQ_DISP("set:sides2", 1);
    VQ_BODY("set:top", 1, -VQ_T * W / ((double)count * V));
    res->exact = -VQ_T * H / VQ_E;
    break;
  case VQ_ISOTROPIC: {
    pdk_index cr = 0;
    VQ_OK(ctx, vq_define_box(p, "bottom", -big, -big, big, e, NULL));
    VQ_OK(ctx, vq_define_box(p, "left", -big, -big, e, big, NULL));
    VQ_OK(ctx, vq_define_box(p, "top", -big, H - e, big, big, &count));
    VQ_OK(ctx, vq_define_box(p, "right", W - e, -big, big, big, &cr));
    VQ_DISP("set:bottom", 2);
    VQ_DISP("set:left", 1);
    VQ_BODY("set:top", 1, -VQ_T * W / ((double)count * V));
    VQ_BODY("set:right", 0, -VQ_T * H / ((double)cr * V));
    res->exact = -VQ_T * H / VQ_E;
    break;
  }
  case VQ_SHEAR:
    VQ_OK(ctx, vq_define_box(p, "bottom", -big, -big, big, e, NULL));
    VQ_OK(ctx, vq_define_box(p, "sides", -big, e, e, big, NULL));
    VQ_OK(ctx, vq_define_box(p, "sides2", W - e, e, big, big, NULL));
    VQ_OK(ctx, vq_define_box(p, "top", -big, H - e, big, big, &count));
    VQ_DISP("set:bottom", 3);
    VQ_DISP("set:sides", 2);
    VQ_DISP("set:sides2", 2);
    VQ_BODY("set:top", 0, VQ_T * W / ((double)count * V));
    res->exact = VQ_T * H / (VQ_E / 2.0);
    break;
  case VQ_CRACK: {
    /* outermost row/column: prescribed Westergaard displacement (scale field "u_a") */
    VQ_OK(ctx, pdk_particles_field_add(p, "u_a", PDK_F64, 2));
    double *ua = pdk_particles_field_data(p, "u_a", 0), *va = pdk_particles_field_data(p, "u_a", 1);
    const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1);
    for (pdk_index i = 0; i < n; ++i) {
      double u[2];
      vq_westergaard(X[i] - xc, Y[i] - yc, VQ_CP, a, VQ_CE, 0.0, u);
      ua[i] = u[0];
      va[i] = u[1];
    }
    VQ_OK(ctx, pdk_particles_field_add(p, "set:outer", PDK_U8, 1));
    uint8_t *outer = pdk_particles_field_data(p, "set:outer", 0);
    {
      const double rows = c->crack_rows > 1 ? (double)c->crack_rows : 1.0;
      for (pdk_index i = 0; i < n; ++i)
        outer[i] = X[i] < rows * h || X[i] > W - rows * h || Y[i] < rows * h || Y[i] > H - rows * h;
    }
    bcs[nb].kind = PDK_BC_DISPLACEMENT;
    bcs[nb].set = "set:outer";
    bcs[nb].components = 3;
    bcs[nb].value[0] = bcs[nb].value[1] = pdk_tfun_constant(1.0);
    bcs[nb].scale_field = "u_a";
    ++nb;
    /* cut vertical nearest-neighbour bonds: rows at y_c -+ h/2, |x - x_c| <= a */
    VQ_OK(ctx, vq_define_box(p, "face_up", xc - a, yc, xc + a, yc + h, &count));
    VQ_OK(ctx, vq_define_box(p, "face_down", xc - a, yc - h, xc + a, yc, NULL));
    VQ_BODY("set:face_up", 1, VQ_CP / h);
    VQ_BODY("set:face_down", 1, -VQ_CP / h);
    break;
  }
  }
  VQ_OK(ctx, pdk_families_build(p, &fo, &fam));
  pdk_model_opts mo = pdk_model_opts_default();
  const double E = crack ? VQ_CE : VQ_E;
  mo.bulk_modulus = E / 3.0; /* nu = 0 */
  mo.shear_modulus = E / 2.0;
  mo.density = 1.0;
  mo.influence = c->omega;
  mo.kind = c->law == VQ_F ? PDK_MODEL_CORRESPONDENCE
                           : (c->law == VQ_SILLING ? PDK_MODEL_LPS : PDK_MODEL_OTERKUS);
  mo.lps_use_influence = c->law == VQ_SILLING;
  mo.oterkus_a = c->oterkus_a;
  mo.stabilization = PDK_STAB_NONE;
  mo.law = PDK_LAW_LINEAR_ELASTIC;
  VQ_OK(ctx, pdk_model_create(p, fam, &mo, &m));
  pdk_static_opts so = pdk_static_opts_default(PDK_STATIC_NEWTON);
  so.bcs = bcs;
  so.num_bcs = nb;
  /* Unstabilized correspondence at large RF has very soft spurious modes (V-Z); they are part of
   * what the paper measures, so the near-singularity check must not stop the solve. */
  so.singular_rtol = 0.0;
  /* The problems are linear (linear-elastic F law; the dilatation laws at strains ~1e-6), so a
   * forward-difference tangent (half the passes of central differences) is exact up to round-off
   * and O(fd_step) truncation; Newton's residual iteration removes both. */
  so.fd_scheme = PDK_FD_FORWARD;
  /* The dilatation laws take their analytic tangent (auto); PDK_VQ_TANGENT=difference forces the
   * difference one (bench/README.md compares the two). */
  const char *tangent_env = getenv("PDK_VQ_TANGENT");
  if (tangent_env && !strcmp(tangent_env, "difference")) so.tangent = PDK_TANGENT_DIFFERENCE;
  VQ_OK(ctx, pdk_static_create(m, &so, &s));
  VQ_OK(ctx, pdk_static_solve(s));
  res->tangent_nnz = (long)pdk_static_stats_get(s)->tangent_nnz;
  if (getenv("PDK_VQ_STATS")) pdk_static_stats_print(pdk_static_stats_get(s), stderr);
  const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1);
  const double *x = pdk_particles_field_data(p, "x", 0), *y = pdk_particles_field_data(p, "x", 1);
  if (!crack) {
    double sum = 0.0, smax = 0.0;
    int cnt = 0;
    for (pdk_index i = 0; i < n; ++i) {
      const int on_right = c->problem == VQ_ISOTROPIC;
      const double along = on_right ? Y[i] : X[i], across = on_right ? X[i] : Y[i];
      if (across > H - e && along >= 0.4 * W - 1e-9 * W && along <= 0.6 * W + 1e-9 * W) {
        sum += c->problem == VQ_UNIAXIAL ? y[i] - Y[i] : x[i] - X[i];
        ++cnt;
      }
      smax = fmax(smax, fabs(y[i] - Y[i]));
      if (fabs(X[i] - 0.5 * W) <= 0.51 * h)
        res->spurious_centre = fmax(res->spurious_centre, fabs(y[i] - Y[i]) / fabs(res->exact));
    }
    res->probe = sum / cnt;
    res->probe_count = cnt;
    res->rel_error = fabs(res->probe - res->exact) / fabs(res->exact);
    res->spurious = smax / fabs(res->exact);
  } else {
    VQ_OK(ctx, pdk_particles_field_add(p, "u", PDK_F64, 2));
    double *u = pdk_particles_field_data(p, "u", 0), *v = pdk_particles_field_data(p, "u", 1);
    for (pdk_index i = 0; i < n; ++i) {
      u[i] = x[i] - X[i];
      v[i] = y[i] - Y[i];
    }
    const double *ua = pdk_particles_field_data(p, "u_a", 0);
    const double *va = pdk_particles_field_data(p, "u_a", 1);
    const pdk_influence sw[3] = {PDK_INFLUENCE_CONSTANT, PDK_INFLUENCE_LINEAR, PDK_INFLUENCE_CUBIC};
    for (int k = -1; k < 3; ++k) {
      const double *us = u, *vs = v;
      if (k >= 0) {
        VQ_OK(ctx, pdk_smooth_field(p, fam, sw[k], 0.5, "u", "u_s"));
        us = pdk_particles_field_data(p, "u_s", 0);
        vs = pdk_particles_field_data(p, "u_s", 1);
      }
      double num = 0, den = 0, numw = 0, denw = 0;
      for (pdk_index i = 0; i < n; ++i) {
        const double d2 = (us[i] - ua[i]) * (us[i] - ua[i]) + (vs[i] - va[i]) * (vs[i] - va[i]);
        const double a2 = ua[i] * ua[i] + va[i] * va[i];
        num += d2;
        den += a2;
        if (fabs(X[i] - xc) <= VQ_CL && fabs(Y[i] - yc) <= VQ_CL) {
          numw += d2;
          denw += a2;
        }
        if (k < 0 && Y[i] > yc && Y[i] < yc + h && fabs(X[i] - xc) <= a)
          res->max_opening = fmax(res->max_opening, v[i]);
      }
      if (k < 0) {
        res->err_all = sqrt(num / den);
        res->err_win = sqrt(numw / denw);
      } else {
        res->err_all_s[k] = sqrt(num / den);
        res->err_win_s[k] = sqrt(numw / denw);
      }
    }
  }
#undef VQ_DISP
#undef VQ_BODY
  pdk_static_destroy(&s);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  res->seconds = vq_now() - t0;
  return 0;
}

/* Least-squares slope of log e against log h (the paper's eq. (37)); h = W / np. */
static inline double vq_slope(int k, const int *np, const double *err) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int i = 0; i < k; ++i) {
    const double lx = log(1.0 / np[i]), ly = log(err[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  return (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

#endif
