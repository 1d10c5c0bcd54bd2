/* Helpers shared by the correspondence tests (t04x): lattices, families, models, fields. */
#ifndef PDK_CORR_UTIL_H
#define PDK_CORR_UTIL_H

#include "pdk/explicit.h"
#include "pdk/geometry.h"
#include "pdk/model.h"
#include "test_util.h"

/* Material of every correspondence test: K = 2, G = 1 (lambda = 4/3, mu = 1), rho = 1. */
#define CU_BULK 2.0
#define CU_SHEAR 1.0

static const char *const cu_law_name[] = {"linear_elastic", "svk", "neo_hooke"};
static const char *const cu_infl_name[] = {"constant", "inv_r", "inv_r2",
                                           "linear",   "cubic", "gaussian"};
static const char *const cu_stab_name[] = {"none", "silling", "hourglass"};

typedef struct cu_body {
  pdk_ctx *ctx;
  pdk_particles *p;
  pdk_families *fam;
  pdk_model *m;
  int dim;
  pdk_index n;
} cu_body;

/* Deterministic uniform numbers in [-1, 1). */
static inline double cu_rand(uint64_t *s) {
  *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(*s >> 11) * 0x1p-52 - 1.0;
}

/* A lattice of N^dim points with unit spacing in [0, N)^dim (square or simple cubic), points at
 * i + 1/2, optional jitter; volume 1 (2-D: unit thickness). */
static inline pdk_particles *cu_lattice(pdk_ctx *ctx, int dim, int N, double jitter,
                                        uint64_t seed) {
  pdk_lattice_opts o = pdk_lattice_opts_default();
  o.type = dim == 2 ? PDK_LATTICE_SQUARE : PDK_LATTICE_CUBIC;
  for (int a = 0; a < 3; ++a) {
    o.lo[a] = 0.0;
    o.hi[a] = a < dim ? (double)N : 1.0;
  }
  o.spacing = 1.0;
  o.jitter = jitter;
  o.seed = seed;
  pdk_particles *p = NULL;
  T_OK(ctx, pdk_lattice_create(ctx, &o, &p));
  return p;
}

static inline pdk_families *cu_families(pdk_ctx *ctx, pdk_particles *p, double horizon) {
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = horizon;
  pdk_families *fam = NULL;
  T_OK(ctx, pdk_families_build(p, &fo, &fam));
  return fam;
}

static inline pdk_model_opts cu_opts(int law, int infl, int stab, double cs) {
  pdk_model_opts o = pdk_model_opts_default();
  o.kind = PDK_MODEL_CORRESPONDENCE;
  o.bulk_modulus = CU_BULK;
  o.shear_modulus = CU_SHEAR;
  o.density = 1.0;
  o.law = (pdk_law)law;
  o.influence = (pdk_influence)infl;
  o.stabilization = (pdk_stabilization)stab;
  o.stab_coefficient = cs;
  return o;
}

static inline pdk_model *cu_model(pdk_ctx *ctx, pdk_particles *p, pdk_families *fam,
                                  const pdk_model_opts *o) {
  pdk_model *m = NULL;
  T_OK(ctx, pdk_model_create(p, fam, o, &m));
  return m;
}

static inline double *cu_field(pdk_particles *p, const char *name, int comp) {
  double *v = pdk_particles_field_data(p, name, comp);
  if (!v) T_FAIL("field %s[%d] missing", name, comp);
  return v;
}

/* x = X */
static inline void cu_reset_x(pdk_particles *p) {
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  for (int a = 0; a < dim; ++a)
    memcpy(cu_field(p, "x", a), pdk_particles_X(p, a), (size_t)n * sizeof(double));
}

/* x = F0 X + c (F0 row-major dim x dim) */
static inline void cu_affine(pdk_particles *p, const double *F0, const double *c) {
  const int d = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  const double *X[3] = {pdk_particles_X(p, 0), pdk_particles_X(p, 1),
                        d == 3 ? pdk_particles_X(p, 2) : NULL};
  double *x[3] = {cu_field(p, "x", 0), cu_field(p, "x", 1), d == 3 ? cu_field(p, "x", 2) : NULL};
  for (pdk_index i = 0; i < n; ++i)
    for (int a = 0; a < d; ++a) {
      double s = c[a];
      for (int b = 0; b < d; ++b)
        s += F0[a * d + b] * X[b][i];
      x[a][i] = s;
    }
}

/* x = X + amp * random */
static inline void cu_random_x(pdk_particles *p, double amp, uint64_t seed) {
  const int d = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  uint64_t s = seed;
  for (int a = 0; a < d; ++a) {
    const double *X = pdk_particles_X(p, a);
    double *x = cu_field(p, "x", a);
    for (pdk_index i = 0; i < n; ++i)
      x[i] = X[i] + amp * cu_rand(&s);
  }
}

/* Rotation matrix (row-major): 2-D by angle t; 3-D by angle t about the unit axis (1, 2,
 * 3)/sqrt(14). */
static inline void cu_rotation(int d, double t, double *R) {
  if (d == 2) {
    R[0] = cos(t), R[1] = -sin(t), R[2] = sin(t), R[3] = cos(t);
    return;
  }
  double u[3] = {1.0, 2.0, 3.0}, nu = sqrt(14.0);
  for (int a = 0; a < 3; ++a)
    u[a] /= nu;
  const double c = cos(t), s = sin(t);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      double v = (a == b ? c : 0.0) + (1.0 - c) * u[a] * u[b];
      if (a != b) {
        const int k = 3 - a - b; /* the third axis */
        const double sign = ((a + 1) % 3 == b) ? -1.0 : 1.0;
        v += sign * s * u[k];
      }
      R[a * 3 + b] = v;
    }
}

/* Lattice index of particle i along axis a (regular lattice, points at k + 1/2). */
static inline int cu_index(pdk_particles *p, int a, pdk_index i) {
  return (int)floor(pdk_particles_X(p, a)[i]);
}

/* 1 when every axis index lies in [lo, N-1-lo]. */
static inline int cu_inside(pdk_particles *p, pdk_index i, int N, int lo) {
  for (int a = 0; a < pdk_particles_dim(p); ++a) {
    const int k = cu_index(p, a, i);
    if (k < lo || k > N - 1 - lo) return 0;
  }
  return 1;
}

/* Influence functions, written here independently of the library (pdk_influence): omega(r) for
 * r <= delta, clamped at 0 (the library clamps too), gaussian width 0.5 delta. */
static inline double cu_omega(int infl, double r, double delta) {
  const double q = r / delta;
  double w = 0.0;
  switch (infl) {
  case PDK_INFLUENCE_CONSTANT: w = 1.0; break;
  case PDK_INFLUENCE_INV_R: w = 1.0 / q; break;
  case PDK_INFLUENCE_INV_R2: w = 1.0 / (q * q); break;
  case PDK_INFLUENCE_LINEAR: w = 1.0 - q; break;
  case PDK_INFLUENCE_CUBIC: w = (1.0 - q) * (1.0 - q) * (1.0 - q); break;
  case PDK_INFLUENCE_GAUSSIAN: w = exp(-(q / 0.5) * (q / 0.5)); break;
  }
  return w > 0.0 ? w : 0.0;
}

/* Largest lattice offset within the horizon m (unit spacing). */
static inline int cu_reach(double m) { return (int)floor(m * (1.0 + 1e-12)); }

/* The biaxially pulled 2-D block of t052, t133 and t134 on [0, L]^2: grips two spacings deep on
 * the four sides (sets "left", "right", "bottom", "top") and velocity conditions moving each grip
 * outwards along its normal at V, reached by a smooth ramp over `ramp`. */
static inline void cu_biaxial_grips(pdk_ctx *ctx, pdk_particles *p, double L, double V, double ramp,
                                    pdk_bc bcs[4]) {
  const double e = 2.0;
  const double l0[3] = {-1, -1, -1}, l1[3] = {e, L + 1, 1};
  const double r0[3] = {L - e, -1, -1}, r1[3] = {L + 1, L + 1, 1};
  const double b0[3] = {-1, -1, -1}, b1[3] = {L + 1, e, 1};
  const double t0[3] = {-1, L - e, -1}, t1[3] = {L + 1, L + 1, 1};
  const pdk_region grips[4] = {pdk_region_box(l0, l1), pdk_region_box(r0, r1),
                               pdk_region_box(b0, b1), pdk_region_box(t0, t1)};
  static const char *const set[4] = {"left", "right", "bottom", "top"};
  static const char *const field[4] = {"set:left", "set:right", "set:bottom", "set:top"};
  for (int k = 0; k < 4; ++k)
    T_OK(ctx, pdk_particles_set_define(p, set[k], &grips[k], NULL));
  const double sign[4] = {-1, 1, -1, 1};
  memset(bcs, 0, 4 * sizeof *bcs);
  for (int k = 0; k < 4; ++k) {
    const int c = k < 2 ? 0 : 1;
    bcs[k].kind = PDK_BC_VELOCITY;
    bcs[k].set = field[k];
    bcs[k].components = 1u << c;
    bcs[k].value[c].kind = PDK_TFUN_SMOOTH;
    bcs[k].value[c].a = sign[k] * V;
    bcs[k].value[c].b = ramp;
  }
}

/* The block of t134, also run by t052: N x N points jittered by 0.02 (seed 5), gripped and pulled
 * as cu_biaxial_grips at the homogeneous stretch rate 0.001 (ramp 50), horizon 3.015, Neo-Hooke,
 * cubic influence, Silling 0.1, `mode` connectivity (UL skin 0.1). Returns the model; *p and *fam
 * are what it was built on. */
static inline pdk_model *cu_pulled_block(pdk_ctx *ctx, int N, pdk_connectivity mode, pdk_bc bcs[4],
                                         pdk_particles **p, pdk_families **fam) {
  const double L = N;
  *p = cu_lattice(ctx, 2, N, 0.02, 5);
  cu_biaxial_grips(ctx, *p, L, 0.001 * (0.5 * L - 1.0), 50.0, bcs);
  *fam = cu_families(ctx, *p, 3.015);
  pdk_model_opts mo = cu_opts(PDK_LAW_NEO_HOOKE, PDK_INFLUENCE_CUBIC, PDK_STAB_SILLING, 0.1);
  mo.connectivity = mode;
  mo.ul_skin = 0.1;
  return cu_model(ctx, *p, *fam, &mo);
}

#endif
