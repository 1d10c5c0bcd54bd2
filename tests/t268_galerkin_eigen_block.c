/* Peridynamic Galerkin, eigenvalues of the global stiffness of a free block (Bode et al. 2022
 * section 7.1, Table 1; Bode 2021 section 7.2.1, Fig. 7.6): 20 x 10 mm, E = 100 N/mm^2,
 * nu = 0.4, plane strain, the linear law, no boundary conditions; 20 x 10 bilinear elements, the
 * particles collocated with their 21 x 11 nodes (spacing 1 mm), volumes the nodes' shares of the
 * element areas (1, 1/2 on the edges, 1/4 at the corners), families the mesh connectivity (the
 * nodes of the adjacent elements: horizon 1.5 mm on this lattice) or the horizon 3.01 mm; the
 * eigenvalues of K u = lambda u (no mass), thickness 1 mm.
 * labels: galerkin physics
 *
 * Stiffnesses: Q1 assembled here (2 x 2 Gauss points, exact for the bilinear rectangle); pdk's
 * models by central differences of the force (K = -d(V f)/du, exact to round-off for the linear
 * law); eigenvalues of the dense symmetric matrices by Householder reduction and implicit QL.
 *
 * What must hold, and why these bounds (numbers: docs/validation/galerkin.md, "Eigenvalues of a
 * free block").
 * - Q1: 3 zero eigenvalues (the rigid motions; below 1e-8 of the largest), the next ones against
 *   the paper's Q1 column. They do not agree to 3 digits: this standard Q1 gives 0.8928, 2.2005,
 *   2.3417, 4.8278, 5.0087, 5.1702 against the paper's 0.8848, 2.1907, 2.3415, 4.8071, 4.9879,
 *   5.1117 (0.01 to 1.2 %), and plane stress, selective reduced integration, another Poisson ratio
 *   (best fit nu = 0.395 with a free scale: still 0.5 % off) or a lumped mass do not reproduce it
 *   (the document lists them). Asserted: the first six within 1.5 % of the paper's (the measured
 *   spread) and to 1e-5 of the values this assembly gives (a check of assembly and solver).
 * - The paper's PGM (the thesis' VCPBG Unl): taylor (MTE1), the bond-mapping correction, VC1 with
 *   the V5 projector in its printed componentwise form, "sn" with the corners' normals the mean of
 *   their edges', the mesh connectivity. Modes 4-11 equal the paper's to 3e-13 relative (asserted
 *   1e-9), which fixes every choice above (each alternative moves them by 1e-4 to 1e-1: the
 *   other rows). Modes 1-3 are 0.08, 0.18 and 0.30 % below the paper's, for a reason not found
 *   (asserted 0.5 %).
 * - Every galerkin form: the tangent is symmetric (to 1e-9 of its largest entry: differences of
 *   a linear force), exactly 3 eigenvalues at round-off (no spurious zero-energy mode: the PG
 *   claim) and the first three within 25 % of Q1's (measured: 21 % at worst, taylor without the
 *   bond correction at horizon 3.01).
 * - Classical correspondence without stabilization on the same families: its first non-zero
 *   eigenvalue is below half of Q1's (soft spurious modes; measured 0.007 to 0.095 against 0.89).
 *   The paper's PDC column (0.2368, 0.2888, ...) is not reproduced by any of influence 1, 1/r,
 *   1/r^2, connectivity or horizon 3.01, nor by WLS with VC1 (the document lists them).
 */
#include "test_util.h"

#define NX 20
#define NY 10
#define NN ((NX + 1) * (NY + 1))
#define NDOF (2 * NN)
#define E_MOD 100.0
#define NU 0.4

static const double paper_q1[11] = {0.8847792246124383, 2.1907158017383337, 2.3414565538196377,
                                    4.80714133198664,   4.987857418616576,  5.11165437573685,
                                    5.191467277052113,  6.08921036444145,   8.555409502176447,
                                    8.797959773335593,  9.96545665970472};
static const double paper_pgm[11] = {0.8369763872245309, 2.1983497321413943, 2.2561792668569387,
                                     4.476948975015391,  4.5285770761519215, 4.593032112209565,
                                     4.7843232595800185, 5.919080469545088,  7.7249329399069095,
                                     8.04100514007736,   9.120985625864364};
static const double paper_pdc[11] = {0.23682170004911376, 0.28884910033074,   0.3392560177723449,
                                     0.5143214151790636,  0.5345370015188999, 0.5703166361181341,
                                     0.7519366670698632,  0.7760065129353704, 0.8034404224436078,
                                     0.8225423531522853,  0.8496526583286905};

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Eigenvalues (ascending) of the symmetric n x n matrix a (row-major, destroyed): Householder
 * reduction to tridiagonal form, then the implicit QL iteration with Wilkinson shifts. */
static void sym_eigvals(int n, double *a, double *d) {
  double *e = calloc((size_t)n, sizeof(double));
#define A(i, j) a[(size_t)(i) * (size_t)n + (size_t)(j)]
  for (int i = n - 1; i > 0; --i) {
    const int l = i - 1;
    double h = 0.0, scale = 0.0;
    if (l > 0) {
      for (int k = 0; k <= l; ++k)
        scale += fabs(A(i, k));
      if (scale == 0.0) {
        e[i] = A(i, l);
      } else {
        for (int k = 0; k <= l; ++k) {
          A(i, k) /= scale;
          h += A(i, k) * A(i, k);
        }
        double f = A(i, l), g = f >= 0.0 ? -sqrt(h) : sqrt(h);
        e[i] = scale * g;
        h -= f * g;
        A(i, l) = f - g;
        f = 0.0;
        for (int j = 0; j <= l; ++j) {
          g = 0.0;
          for (int k = 0; k <= j; ++k)
            g += A(j, k) * A(i, k);
          for (int k = j + 1; k <= l; ++k)
            g += A(k, j) * A(i, k);
          e[j] = g / h;
          f += e[j] * A(i, j);
        }
        const double hh = f / (h + h);
        for (int j = 0; j <= l; ++j) {
          f = A(i, j);
          e[j] = g = e[j] - hh * f;
          for (int k = 0; k <= j; ++k)
            A(j, k) -= f * e[k] + g * A(i, k);
        }
      }
    } else {
      e[i] = A(i, l);
    }
  }
  for (int i = 0; i < n; ++i)
    d[i] = A(i, i);
#undef A
  for (int i = 1; i < n; ++i)
    e[i - 1] = e[i];
  e[n - 1] = 0.0;
  for (int l = 0; l < n; ++l) {
    int iter = 0, m;
    do {
      for (m = l; m < n - 1; ++m) {
        const double dd = fabs(d[m]) + fabs(d[m + 1]);
        if (fabs(e[m]) <= 1e-16 * dd) break;
      }
      if (m != l) {
        T_ASSERT(++iter <= 60, "QL iteration does not converge at %d", l);
        double g = (d[l + 1] - d[l]) / (2.0 * e[l]), r = hypot(g, 1.0);
        g = d[m] - d[l] + e[l] / (g + copysign(r, g));
        double s = 1.0, c = 1.0, p = 0.0;
        int i;
        for (i = m - 1; i >= l; --i) {
          const double f = s * e[i], b = c * e[i];
          e[i + 1] = (r = hypot(f, g));
          if (r == 0.0) {
            d[i + 1] -= p;
            e[m] = 0.0;
            break;
          }
          s = f / r;
          c = g / r;
          g = d[i + 1] - p;
          r = (d[i] - g) * s + 2.0 * c * b;
          d[i + 1] = g + (p = s * r);
          g = c * r - b;
        }
        if (r == 0.0 && i >= l) continue;
        d[l] -= p;
        e[l] = g;
        e[m] = 0.0;
      }
    } while (m != l);
  }
  free(e);
  qsort(d, (size_t)n, sizeof(double), cmp_double);
}

/* Plane-strain Q1 stiffness of the block (2 x 2 Gauss points), thickness 1. */
static void q1_stiffness(double *K) {
  memset(K, 0, sizeof(double) * NDOF * NDOF);
  const double c = E_MOD / ((1 + NU) * (1 - 2 * NU));
  const double D[3][3] = {{c * (1 - NU), c * NU, 0}, {c * NU, c * (1 - NU), 0},
                          {0, 0, c * (1 - 2 * NU) / 2}};
  const double xi[4] = {-1, 1, 1, -1}, eta[4] = {-1, -1, 1, 1}, g = 1 / sqrt(3.0);
  for (int ey = 0; ey < NY; ++ey)
    for (int ex = 0; ex < NX; ++ex) {
      const int nodes[4] = {ey * (NX + 1) + ex, ey * (NX + 1) + ex + 1,
                            (ey + 1) * (NX + 1) + ex + 1, (ey + 1) * (NX + 1) + ex};
      for (int q = 0; q < 4; ++q) {
        const double gx = (q % 2 ? g : -g), gy = (q / 2 ? g : -g);
        double B[4][3][2]; /* strain (xx, yy, 2xy) of node a, displacement component */
        for (int a = 0; a < 4; ++a) {
          /* unit element: dN/dx = 2 dN/dxi, Jacobian determinant 1/4, Gauss weight 1 */
          const double nx = xi[a] * (1 + eta[a] * gy) / 2, ny = eta[a] * (1 + xi[a] * gx) / 2;
          B[a][0][0] = nx, B[a][0][1] = 0;
          B[a][1][0] = 0, B[a][1][1] = ny;
          B[a][2][0] = ny, B[a][2][1] = nx;
        }
        for (int a = 0; a < 4; ++a)
          for (int b = 0; b < 4; ++b)
            for (int p = 0; p < 2; ++p)
              for (int r = 0; r < 2; ++r) {
                double v = 0;
                for (int i = 0; i < 3; ++i)
                  for (int j = 0; j < 3; ++j)
                    v += B[a][i][p] * D[i][j] * B[b][j][r];
                K[(size_t)(2 * nodes[a] + p) * NDOF + 2 * nodes[b] + r] += 0.25 * v;
              }
      }
    }
}

/* The particles of the block: lattice of spacing 1, FE nodal volumes, set "surface" and the
 * outward normals of the edges (0 at the corners: the "s" condition there). */
static pdk_particles *block(pdk_ctx *ctx, int unit_volumes, int corner_normals) {
  pdk_particles *p;
  T_OK(ctx, pdk_particles_create(ctx, 2, NN, &p));
  double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1), *V = pdk_particles_volume(p);
  T_OK(ctx, pdk_particles_field_add(p, "set:surface", PDK_U8, 1));
  T_OK(ctx, pdk_particles_field_add(p, "normal", PDK_F64, 2));
  uint8_t *surf = pdk_particles_field_data(p, "set:surface", 0);
  double *nx = pdk_particles_field_data(p, "normal", 0), *ny = pdk_particles_field_data(p, "normal", 1);
  for (int j = 0; j <= NY; ++j)
    for (int i = 0; i <= NX; ++i) {
      const int k = j * (NX + 1) + i, ex = i == 0 || i == NX, ey = j == 0 || j == NY;
      X[k] = i;
      Y[k] = j;
      V[k] = unit_volumes ? 1.0 : (ex ? 0.5 : 1.0) * (ey ? 0.5 : 1.0);
      surf[k] = (uint8_t)(ex || ey);
      nx[k] = ex && !ey ? (i == 0 ? -1.0 : 1.0) : 0.0;
      ny[k] = ey && !ex ? (j == 0 ? -1.0 : 1.0) : 0.0;
      if (ex && ey && corner_normals) { /* the mean of the two edges' normals */
        nx[k] = (i == 0 ? -1.0 : 1.0) / sqrt(2.0);
        ny[k] = (j == 0 ? -1.0 : 1.0) / sqrt(2.0);
      }
    }
  return p;
}

/* K = -d(V f)/du by central differences at rest; returns the largest asymmetry relative to the
 * largest entry, K symmetrized. */
static double tangent(pdk_ctx *ctx, pdk_model *m, pdk_particles *p, double *K) {
  const double eps = 1e-3;
  const double *V = pdk_particles_volume(p);
  double *x[2] = {pdk_particles_field_data(p, "x", 0), pdk_particles_field_data(p, "x", 1)};
  const double *f[2] = {pdk_particles_field_data(p, "f", 0), pdk_particles_field_data(p, "f", 1)};
  double *fp = malloc(sizeof(double) * NDOF);
  for (int col = 0; col < NDOF; ++col) {
    const int jn = col / 2, jc = col % 2;
    const double x0 = x[jc][jn];
    for (int s = 0; s < 2; ++s) {
      x[jc][jn] = x0 + (s ? -eps : eps);
      T_OK(ctx, pdk_model_force_trial(m, NULL));
      for (int i = 0; i < NN; ++i)
        for (int c = 0; c < 2; ++c) {
          const double vf = V[i] * f[c][i];
          if (s == 0) fp[2 * i + c] = vf;
          else K[(size_t)(2 * i + c) * NDOF + col] = -(fp[2 * i + c] - vf) / (2 * eps);
        }
    }
    x[jc][jn] = x0;
  }
  free(fp);
  double kmax = 0, amax = 0;
  for (int i = 0; i < NDOF; ++i)
    for (int j = 0; j < NDOF; ++j) {
      kmax = fmax(kmax, fabs(K[(size_t)i * NDOF + j]));
      amax = fmax(amax, fabs(K[(size_t)i * NDOF + j] - K[(size_t)j * NDOF + i]));
    }
  for (int i = 0; i < NDOF; ++i)
    for (int j = 0; j < i; ++j) {
      const double a = 0.5 * (K[(size_t)i * NDOF + j] + K[(size_t)j * NDOF + i]);
      K[(size_t)i * NDOF + j] = K[(size_t)j * NDOF + i] = a;
    }
  return amax / kmax;
}

typedef struct spectrum {
  int zeros;         /* eigenvalues below 1e-8 of the largest */
  double first[11];  /* the first 11 above that */
  double largest;
} spectrum;

static spectrum spectrum_of(double *K) {
  double *d = malloc(sizeof(double) * NDOF);
  sym_eigvals(NDOF, K, d);
  spectrum s;
  memset(&s, 0, sizeof s);
  s.largest = fmax(fabs(d[0]), fabs(d[NDOF - 1]));
  int k = 0;
  for (int i = 0; i < NDOF; ++i) {
    if (fabs(d[i]) <= 1e-8 * s.largest) ++s.zeros;
    else if (k < 11) s.first[k++] = d[i];
  }
  free(d);
  return s;
}

static void print_spectrum(const char *name, const spectrum *s, const double *paper) {
  T_INFO("%-34s zeros %3d:", name, s->zeros);
  for (int i = 0; i < 11; ++i)
    T_INFO(" %.7g", s->first[i]);
  T_INFO("\n");
  if (paper) {
    T_INFO("%-34s  rel. to paper:", "");
    for (int i = 0; i < 11; ++i)
      T_INFO(" %+.1e", s->first[i] / paper[i] - 1);
    T_INFO("\n");
  }
}

typedef struct variant {
  const char *name;
  pdk_model_kind kind;
  pdk_galerkin_basis basis;
  pdk_galerkin_correction corr;
  int sn;
  pdk_influence influence;
  double horizon;
  int unit_volumes;
  int bond;
  int corner_normals;
} variant;

static spectrum run_model(pdk_ctx *ctx, const variant *v, double *K) {
  pdk_particles *p = block(ctx, v->unit_volumes, v->corner_normals);
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = v->horizon;
  pdk_families *fam;
  T_OK(ctx, pdk_families_build(p, &fo, &fam));
  const double mu = E_MOD / (2 * (1 + NU)), lam = E_MOD * NU / ((1 + NU) * (1 - 2 * NU));
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = v->kind;
  mo.shear_modulus = mu;
  mo.bulk_modulus = lam + 2.0 * mu / 3.0;
  mo.density = 1.0;
  mo.law = PDK_LAW_LINEAR_ELASTIC;
  if (v->kind == PDK_MODEL_GALERKIN) {
    mo.galerkin.basis = v->basis;
    mo.galerkin.correction = v->corr;
    mo.galerkin.surface = "surface";
    mo.galerkin.bond = v->bond;
    if (v->sn) mo.galerkin.normals = "normal";
  } else {
    mo.influence = v->influence;
    mo.stabilization = PDK_STAB_NONE;
  }
  pdk_model *m;
  T_OK(ctx, pdk_model_create(p, fam, &mo, &m));
  const double asym = tangent(ctx, m, p, K);
  T_ASSERT(asym <= 1e-9, "%s: tangent asymmetric by %.3e of its largest entry", v->name, asym);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  return spectrum_of(K);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  double *K = malloc(sizeof(double) * NDOF * NDOF);

  /* Q1 */
  q1_stiffness(K);
  const spectrum q1 = spectrum_of(K);
  print_spectrum("Q1 (2x2 Gauss)", &q1, paper_q1);
  T_ASSERT(q1.zeros == 3, "Q1: %d zero eigenvalues, expected the 3 rigid motions", q1.zeros);
  /* this assembly's own values (see the header) */
  static const double own_q1[6] = {0.892756, 2.20052, 2.3417, 4.82782, 5.00869, 5.17021};
  for (int i = 0; i < 6; ++i) {
    T_NEAR(q1.first[i], own_q1[i], 1e-5, 0.0, "Q1 eigenvalue %d against its recorded value", i + 1);
    T_NEAR(q1.first[i], paper_q1[i], 0.015, 0.0, "Q1 eigenvalue %d against the paper's", i + 1);
  }

  /* The paper's PGM: taylor (MTE1), the bond correction, VC1 with the V5 projector, "sn" with the
   * corners' normals the mean of their edges', the mesh connectivity (first); then pdk's other
   * forms on the same block, and classical correspondence. */
#define GAL(nm, b, cr, sn_, hor, bnd, cn)                                                         \
  {.name = nm, .kind = PDK_MODEL_GALERKIN, .basis = b, .corr = cr, .sn = sn_, .horizon = hor,     \
   .bond = bnd, .corner_normals = cn}
#define COR(nm, infl, hor)                                                                          \
  {.name = nm, .kind = PDK_MODEL_CORRESPONDENCE, .influence = infl, .horizon = hor}
  const variant variants[] = {
      GAL("PGM: taylor bond VC1 sn, conn.", PDK_GALERKIN_TAYLOR, PDK_GALERKIN_VC1, 1, 1.5, 1, 1),
      GAL("taylor bond VC1 sn (corner s)", PDK_GALERKIN_TAYLOR, PDK_GALERKIN_VC1, 1, 1.5, 1, 0),
      GAL("taylor bond VC1 s, conn.", PDK_GALERKIN_TAYLOR, PDK_GALERKIN_VC1, 0, 1.5, 1, 0),
      GAL("taylor bond, conn.", PDK_GALERKIN_TAYLOR, PDK_GALERKIN_NONE, 0, 1.5, 1, 0),
      GAL("taylor VC1 sn, conn.", PDK_GALERKIN_TAYLOR, PDK_GALERKIN_VC1, 1, 1.5, 0, 1),
      GAL("taylor, conn.", PDK_GALERKIN_TAYLOR, PDK_GALERKIN_NONE, 0, 1.5, 0, 0),
      GAL("taylor bond VC1 sn, 3.01", PDK_GALERKIN_TAYLOR, PDK_GALERKIN_VC1, 1, 3.01, 1, 1),
      GAL("taylor VC1 sn, 3.01", PDK_GALERKIN_TAYLOR, PDK_GALERKIN_VC1, 1, 3.01, 0, 1),
      COR("correspondence 1/r^2, conn.", PDK_INFLUENCE_INV_R2, 1.5),
      COR("correspondence 1/r, conn.", PDK_INFLUENCE_INV_R, 1.5),
      COR("correspondence 1, conn.", PDK_INFLUENCE_CONSTANT, 1.5),
      COR("correspondence 1/r^2, 3.01", PDK_INFLUENCE_INV_R2, 3.01),
  };
  const int nv = (int)(sizeof variants / sizeof variants[0]);
  for (int v = 0; v < nv; ++v) {
    const spectrum s = run_model(ctx, &variants[v], K);
    const int gal = variants[v].kind == PDK_MODEL_GALERKIN;
    print_spectrum(variants[v].name, &s, gal ? paper_pgm : paper_pdc);
    if (v == 0) {
      /* the paper's PGM column: modes 4-11 to 1e-9 (measured 3e-13: the paper prints 16 digits),
       * modes 1-3 to 0.5 % (measured 0.08, 0.18, 0.30 %: unexplained, see the header) */
      for (int i = 0; i < 11; ++i)
        T_NEAR(s.first[i], paper_pgm[i], i < 3 ? 5e-3 : 1e-9, 0.0,
               "PGM eigenvalue %d against the paper's", i + 1);
    }
    if (gal) {
      T_ASSERT(s.zeros == 3, "%s: %d zero eigenvalues, expected the 3 rigid motions",
               variants[v].name, s.zeros);
      /* no spurious soft mode: the first ones near Q1's (all forms within 25 %) */
      for (int i = 0; i < 3; ++i)
        T_NEAR(s.first[i], q1.first[i], 0.25, 0.0, "%s: eigenvalue %d against Q1's",
               variants[v].name, i + 1);
    } else {
      /* classical correspondence: soft (hourglass-like) modes far below Q1's first */
      T_ASSERT(s.first[0] < 0.5 * q1.first[0],
               "%s: first non-zero eigenvalue %.4g, expected soft spurious modes (Q1: %.4g)",
               variants[v].name, s.first[0], q1.first[0]);
    }
  }
  free(K);
  pdk_ctx_destroy(&ctx);
  return 0;
}
