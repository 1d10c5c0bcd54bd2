/* Dilatation laws in plane strain with any influence function (Queiruga & Moridis 2017, sections
 * 2.2 and 2.3): Silling's LPS law (kind lps with lps_use_influence = 1)
 * and Oterkus' law (kind oterkus). 2-D only, no bond breaking (bonds cut by pre-cracks do not exist
 * and so carry weight 0 in every sum, as the paper's alpha = 0).
 *
 * Per bond b of particle i (neighbour j): xi = X_j - X_i, r0 = |xi|, Y = x_j - x_i, r = |Y|,
 * e = r - r0, n = Y / r, w = omega(r0) (opts.influence over the families' horizon),
 * Lambda = (Y . xi) / (r r0). Both laws have the form
 *   theta_i = kappa_i sum_b w g_b e V_j,        W_i (below),
 *   f_i     = -(1/V_i) dE/dx_i, E = sum_i V_i W_i; for Silling f_i = sum_b (t_ij + t_ji) n V_j,
 *   t_ij    = w (A_i theta_i r0 + B_i e) (t_ji: the bond seen from j, with j's constants)
 * with
 *   Silling (LPS, 2-D, eqs. (5)-(7); lambda = K - 2G/3, mu = G):
 *     g = r0, m_i = sum w r0^2 V_j, kappa = 2/m, A = 2 (lambda - mu)/m, B = 8 mu/m,
 *     W_i = (lambda + mu) theta^2 / 2 + (4 mu / m) sum w (e - theta r0 / 2)^2 V_j
 *     (the notes' canonical form; the paper's code writes 2(K - G/3) theta r0 + 8G (e - theta r0/3),
 *     the same numbers; with omega = 1/r0 it is pdk's LAMMPS-style LPS in plane strain);
 *   Oterkus (eqs. (8)-(10), (12), (16)):
 *     g = Lambda, d_i = 2 / sum w r0 V_j, D_i = sum w (xi_1 xi_2)^2 / r0^2 V_j, b_i = G / (2 D_i),
 *     kappa = d, A = 2 a_i d_i, B = 2 b_i, W_i = a_i theta^2 + b_i sum w e^2 V_j, and a_i
 *       PDK_OTERKUS_A_PUBLISHED  a = (K - 2G)/2 with the 3-D K: what the published results used
 *                                (notes 2.3, the authors' code, commit "results of Oterkus for
 *                                a = K-2G"); the isotropic response is then wrong,
 *       PDK_OTERKUS_A_CALIBRATED a_i = (lambda + mu)/2 - G m_i / (8 D_i), m_i = sum w r0^2 V_j:
 *                                eq. (13) with the plane-strain bulk modulus lambda + mu, so an
 *                                isotropic stretch has the continuum energy at every particle.
 *     The force is the gradient of the energy (10): the paper's (9), t = w (A theta Lambda +
 *     B e) along n, plus the term A theta w e (xi/r0 - Lambda n)/r from dLambda/dY, which (9)
 *     omits. That term vanishes at the reference state (e = 0), so the linearised problem, and
 *     every result of the paper, is the same; with it the model is hyperelastic (symmetric
 *     tangent, energy conserved in explicit runs).
 * A particle with an empty family has zero constants. Calibration (b_i, d_i, a_i) and m_i use the
 * particle's own (discrete) sums, as the paper's code.
 *
 * Passes: (1) theta_i; (2) forces, gathering theta_j and the constants of the neighbours. One
 * parallel region over fixed blocks of particles; the energy is summed per block and the blocks
 * in order: results are bitwise the same for any thread count.
 * Fields: "theta" (f64 x1, dilatation of the last pass).
 */
#include <math.h>
#include <string.h>

#include "model_bond.h"
#include "model_impl.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"

#define PDK_DIL2_BLOCK 1024

typedef struct dil2_impl {
  int oterkus;
  pdk_index n;
  int64_t num_blocks;
  double *w;     /* [num_bonds] omega(r0) V_j */
  double *kappa; /* [n] */
  double *A, *B; /* [n] */
  double *wdev;  /* [n] Silling: 4 mu / m (energy), Oterkus: b_i */
  double *ebulk; /* [n] Silling: (lambda + mu)/2, Oterkus: a_i */
  double *block_energy;
  /* analytic tangent, allocated on first use: theta and S_i = sum_b w_b grad phi_b (below) at the
   * x of the last tangent_prepare */
  double *tan_theta, *tan_s[2]; /* [n] */
} dil2_impl;

static void dil2_destroy(pdk_model *m) {
  dil2_impl *im = m->impl;
  if (!im) return;
  free(im->w);
  free(im->kappa);
  free(im->A);
  free(im->B);
  free(im->wdev);
  free(im->ebulk);
  free(im->block_energy);
  free(im->tan_theta);
  free(im->tan_s[0]);
  free(im->tan_s[1]);
  free(im);
  m->impl = NULL;
}

static int dil2_setup(pdk_model *m) {
  pdk_ctx *ctx = m->ctx;
  const pdk_model_opts *o = &m->opts;
  pdk_particles *p = m->p;
  const char *name = o->kind == PDK_MODEL_OTERKUS ? "oterkus" : "lps (influence)";
  PDK_CHECK(pdk_particles_dim(p) == 2, ctx, PDK_ERR_UNSUPPORTED,
            "%s model: implemented in 2-D (plane strain) only; this store is %d-D%s", name,
            pdk_particles_dim(p),
            o->kind == PDK_MODEL_LPS ? " (3-D LPS: set lps_use_influence = 0, omega = 1/r)" : "");
  PDK_CHECK(o->critical_stretch == 0, ctx, PDK_ERR_UNSUPPORTED,
            "%s model: bond breaking is not implemented; set critical_stretch = 0 (bonds cut by "
            "pre-cracks are supported)",
            name);
  PDK_CHECK(o->lattice_constant == 0, ctx, PDK_ERR_UNSUPPORTED,
            "%s model: partial volumes are not implemented; set lattice_constant = 0", name);
  PDK_CHECK(o->kind == PDK_MODEL_LPS || (unsigned)o->oterkus_a <= PDK_OTERKUS_A_CALIBRATED, ctx,
            PDK_ERR_ARG, "oterkus model: oterkus_a %d unknown; use published (0) or calibrated (1)",
            (int)o->oterkus_a);
  dil2_impl *im = calloc(1, sizeof *im);
  PDK_CHECK(im, ctx, PDK_ERR_MEMORY, "out of memory creating the %s model", name);
  m->impl = im;
  im->oterkus = o->kind == PDK_MODEL_OTERKUS;
  const pdk_index n = im->n = pdk_particles_count(p);
  im->num_blocks = ((int64_t)n + PDK_DIL2_BLOCK - 1) / PDK_DIL2_BLOCK;
  const pdk_bond_index nb = pdk_families_num_bonds(m->fam);
  const size_t nn = (size_t)(n > 0 ? n : 1);
  im->w = malloc((size_t)(nb > 0 ? nb : 1) * sizeof(double));
  im->kappa = malloc(nn * sizeof(double));
  im->A = malloc(nn * sizeof(double));
  im->B = malloc(nn * sizeof(double));
  im->wdev = malloc(nn * sizeof(double));
  im->ebulk = malloc(nn * sizeof(double));
  im->block_energy = calloc((size_t)(im->num_blocks > 0 ? im->num_blocks : 1), sizeof(double));
  PDK_CHECK(im->w && im->kappa && im->A && im->B && im->wdev && im->ebulk && im->block_energy, ctx,
            PDK_ERR_MEMORY, "%s model: out of memory for %lld bonds", name, (long long)nb);
  PDK_CALL(pdk_particles_field_add(p, "theta", PDK_F64, 1));

  const double K = o->bulk_modulus, G = o->shear_modulus;
  const double lambda = K - 2.0 * G / 3.0, mu = G;
  const double delta = pdk_families_horizon(m->fam);
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index *bj = pdk_families_bond_j(m->fam);
  const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1);
  const double *V = pdk_particles_volume(p);
  const int oterkus = im->oterkus, calibrated = o->oterkus_a == PDK_OTERKUS_A_CALIBRATED;
  const pdk_influence kind = o->influence;
  const double width = o->gaussian_width;
#pragma omp parallel for schedule(static) num_threads(ctx->num_threads)
  for (pdk_index i = 0; i < n; ++i) {
    double m2 = 0.0, s1 = 0.0, ds = 0.0;
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      const pdk_index j = bj[b];
      const double dx = X[j] - X[i], dy = Y[j] - Y[i];
      const double r0 = sqrt(dx * dx + dy * dy);
      const double wv = (r0 > 0.0 ? pdk_influence_eval(kind, r0, delta, width) : 0.0) * V[j];
      im->w[b] = wv;
      m2 += wv * r0 * r0;
      s1 += wv * r0;
      ds += r0 > 0.0 ? wv * (dx * dy) * (dx * dy) / (r0 * r0) : 0.0;
    }
    double kappa = 0, A = 0, B = 0, wdev = 0, ebulk = 0;
    if (!oterkus && m2 > 0) {
      kappa = 2.0 / m2;
      A = 2.0 * (lambda - mu) / m2;
      B = 8.0 * mu / m2;
      wdev = 4.0 * mu / m2;
      ebulk = 0.5 * (lambda + mu);
    } else if (oterkus && s1 > 0 && ds > 0) {
      const double d = 2.0 / s1, bb = G / (2.0 * ds);
      const double a = calibrated ? 0.5 * (lambda + mu) - G * m2 / (8.0 * ds) : 0.5 * (K - 2.0 * G);
      kappa = d;
      A = 2.0 * a * d;
      B = 2.0 * bb;
      wdev = bb;
      ebulk = a;
    }
    im->kappa[i] = kappa;
    im->A[i] = A;
    im->B[i] = B;
    im->wdev[i] = wdev;
    im->ebulk[i] = ebulk;
  }
  return PDK_SUCCESS;
}

static int dil2_force(pdk_model *m, int commit, double *energy) {
  (void)commit; /* no history */
  pdk_ctx *ctx = m->ctx;
  dil2_impl *im = m->impl;
  pdk_particles *p = m->p;
  const pdk_index n = im->n;
  const int64_t num_blocks = im->num_blocks;
  const int oterkus = im->oterkus;
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index *bj = pdk_families_bond_j(m->fam);
  const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1);
  const double *x = pdk_particles_field_data(p, "x", 0), *y = pdk_particles_field_data(p, "x", 1);
  double *fx = pdk_particles_field_data(p, "f", 0), *fy = pdk_particles_field_data(p, "f", 1);
  double *theta = pdk_particles_field_data(p, "theta", 0);
  const double *V = pdk_particles_volume(p);
  PDK_CHECK(x && y && fx && fy && theta, ctx, PDK_ERR_NOT_FOUND,
            "%s model: fields \"x\", \"f\" or \"theta\" are missing from the particle store",
            m->info->name);
  const double *w = im->w, *kappa = im->kappa, *A = im->A, *B = im->B;
  const double *wdev = im->wdev, *ebulk = im->ebulk;
  double *block_energy = im->block_energy;
#pragma omp parallel num_threads(ctx->num_threads)
  {
#pragma omp for schedule(static)
    for (int64_t blk = 0; blk < num_blocks; ++blk) {
      const pdk_index i0 = (pdk_index)(blk * PDK_DIL2_BLOCK);
      const pdk_index i1 = i0 + PDK_DIL2_BLOCK < n ? i0 + PDK_DIL2_BLOCK : n;
      for (pdk_index i = i0; i < i1; ++i) {
        double s = 0.0;
        for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
          const pdk_index j = bj[b];
          const double dX = X[j] - X[i], dY = Y[j] - Y[i], dx = x[j] - x[i], dy = y[j] - y[i];
          const double r0 = sqrt(dX * dX + dY * dY), r = sqrt(dx * dx + dy * dy);
          const double g = oterkus ? (r > 0 ? (dx * dX + dy * dY) / (r * r0) : 0.0) : r0;
          s += w[b] * g * (r - r0);
        }
        theta[i] = kappa[i] * s;
      }
    } /* barrier: every theta is complete */
#pragma omp for schedule(static)
    for (int64_t blk = 0; blk < num_blocks; ++blk) {
      const pdk_index i0 = (pdk_index)(blk * PDK_DIL2_BLOCK);
      const pdk_index i1 = i0 + PDK_DIL2_BLOCK < n ? i0 + PDK_DIL2_BLOCK : n;
      double eblk = 0.0;
      for (pdk_index i = i0; i < i1; ++i) {
        double sx = 0.0, sy = 0.0, wsum = 0.0;
        for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
          const pdk_index j = bj[b];
          const double dX = X[j] - X[i], dY = Y[j] - Y[i], dx = x[j] - x[i], dy = y[j] - y[i];
          const double r0 = sqrt(dX * dX + dY * dY), r = sqrt(dx * dx + dy * dy);
          if (!(r > 0.0)) continue;
          const double e = r - r0;
          /* w[b] = omega V_j; the bond from j's side has the same omega (it depends on r0 only) */
          const double at = A[i] * theta[i] + A[j] * theta[j], bt = B[i] + B[j];
          if (oterkus) { /* c1 n + c2 xi/r0: d(e Lambda)/dY = Lambda n + e (xi/r0 - Lambda n)/r */
            const double lam = (dx * dX + dy * dY) / (r * r0);
            const double c1 = w[b] * (at * lam * (1.0 - e / r) + bt * e), c2 = w[b] * at * e / r;
            sx += c1 * dx / r + c2 * dX / r0;
            sy += c1 * dy / r + c2 * dY / r0;
          } else {
            const double t = w[b] * (at * r0 + bt * e);
            sx += t * dx / r;
            sy += t * dy / r;
          }
          if (energy) {
            const double dev = oterkus ? e : e - 0.5 * theta[i] * r0;
            wsum += w[b] * dev * dev;
          }
        }
        fx[i] = sx;
        fy[i] = sy;
        if (energy)
          eblk += V[i] * (ebulk[i] * theta[i] * theta[i] + wdev[i] * wsum);
      }
      block_energy[blk] = eblk;
    }
  }
  if (energy) {
    double e = 0.0;
    for (int64_t blk = 0; blk < num_blocks; ++blk) e += block_energy[blk];
    *energy = e;
  }
  return PDK_SUCCESS;
}

/* ---- analytic tangent (the Newton solver's, see pdk_model_ops) --------------------------------
 *
 * Both laws share one form. Per bond b of particle a (neighbour j), with the bond function
 *   phi_b(Y) = r0 e             (Silling)      grad phi = r0 n,
 *                                               Hess phi = r0 (I - n n^T) / r
 *   phi_b(Y) = e Lambda = Y.xi / r0 - Y.xi / r  (Oterkus)  grad phi = xi e / (r r0) + Lambda r0 n / r,
 *                    Hess phi = (xi Y^T + Y xi^T) / r^3 + (Y.xi) (I / r^3 - 3 Y Y^T / r^5),
 * the pass computes theta_a = kappa_a sum_b w_b phi_b and
 *   f_a = sum_b w_b [(A_a theta_a + A_j theta_j) grad phi_b + (B_a + B_j) e n]
 * (for Oterkus this is the c1 n + c2 xi / r0 of dil2_force: grad phi is the d(e Lambda)/dY there).
 * Differentiating with theta fixed gives the bond block
 *   M_b = w_b [at Hess phi + bt (n n^T + e (I - n n^T) / r)],  at = A_a theta_a + A_j theta_j,
 *   bt = B_a + B_j,
 * and through theta: df_a/dtheta_p = A_p S_p for a = p (S_p = sum_b w_b grad phi_b) and
 * w_ap A_p grad phi_ap for every a whose family holds p. theta_p depends on x_i with gradient
 * g_i = -kappa_i S_i (p = i) and g_j = kappa_j w_ji grad phi_ji (p = j, bond j -> i). phi and the
 * Hessian are even and grad phi odd under reversing a bond (Y, xi -> -Y, -xi), so the column of i
 * (K = -d(V f)/dx) is, per bond b of i to j (w' the weight of the bond j -> i, omega V_i):
 *   K[i,i] += V_i M_b,  K[j,i] -= V_j (w'/w) M_b,  and the rows of p = j with g_j = -kappa_j w'
 *   grad phi_b;
 * then the rows of p = i; for each p: K[p,i] -= V_p A_p S_p g_p^T and, per bond p -> a,
 *   K[a,i] += V_a w_ap A_p grad phi_pa g_p^T.
 * The symmetric form makes the tangent symmetric for these hyperelastic laws. Bonds with r = 0
 * are skipped (no force). */
typedef struct dil2_bond {
  double n[2], grad[2], hess[2][2], e, r, r0;
} dil2_bond;

static void dil2_bond_eval(int oterkus, const double *X, const double *Y, const double *x,
                           const double *y, pdk_index a, pdk_index j, dil2_bond *g) {
  const double dX = X[j] - X[a], dY = Y[j] - Y[a], dx = x[j] - x[a], dy = y[j] - y[a];
  g->r0 = sqrt(dX * dX + dY * dY);
  g->r = sqrt(dx * dx + dy * dy);
  if (!(g->r > 0.0)) return;
  const double r = g->r, r0 = g->r0, e = g->e = r - r0;
  g->n[0] = dx / r;
  g->n[1] = dy / r;
  const double xi[2] = {dX, dY}, Yv[2] = {dx, dy};
  if (!oterkus) {
    for (int c = 0; c < 2; ++c) {
      g->grad[c] = r0 * g->n[c];
      for (int d = 0; d < 2; ++d)
        g->hess[c][d] = r0 * ((c == d ? 1.0 : 0.0) - g->n[c] * g->n[d]) / r;
    }
  } else {
    const double yx = dx * dX + dy * dY, lam = yx / (r * r0), r3 = r * r * r, r5 = r3 * r * r;
    for (int c = 0; c < 2; ++c) {
      g->grad[c] = xi[c] * e / (r * r0) + lam * r0 * g->n[c] / r;
      for (int d = 0; d < 2; ++d)
        g->hess[c][d] = (xi[c] * Yv[d] + Yv[c] * xi[d]) / r3 +
                        yx * ((c == d ? 1.0 : 0.0) / r3 - 3.0 * Yv[c] * Yv[d] / r5);
    }
  }
}

static int dil2_tangent_prepare(pdk_model *m) {
  pdk_ctx *ctx = m->ctx;
  dil2_impl *im = m->impl;
  const pdk_index n = im->n;
  if (!im->tan_theta) {
    const size_t nn = (size_t)(n > 0 ? n : 1);
    im->tan_theta = malloc(nn * sizeof(double));
    im->tan_s[0] = malloc(nn * sizeof(double));
    im->tan_s[1] = malloc(nn * sizeof(double));
    PDK_CHECK(im->tan_theta && im->tan_s[0] && im->tan_s[1], ctx, PDK_ERR_MEMORY,
              "%s model: out of memory for the tangent of %d particles",
              m->info->name, (int)n);
  }
  const int oterkus = im->oterkus;
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index *bj = pdk_families_bond_j(m->fam);
  const double *X = pdk_particles_X(m->p, 0), *Y = pdk_particles_X(m->p, 1);
  const double *x = pdk_particles_field_data(m->p, "x", 0);
  const double *y = pdk_particles_field_data(m->p, "x", 1);
  const double *w = im->w, *kappa = im->kappa;
  double *th = im->tan_theta, *s0 = im->tan_s[0], *s1 = im->tan_s[1];
#pragma omp parallel for default(none) schedule(static) num_threads(ctx->num_threads)              \
    shared(n, oterkus, bs, bj, X, Y, x, y, w, kappa, th, s0, s1)
  for (pdk_index i = 0; i < n; ++i) {
    double sum = 0.0, sx = 0.0, sy = 0.0;
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      dil2_bond g;
      dil2_bond_eval(oterkus, X, Y, x, y, i, bj[b], &g);
      if (!(g.r > 0.0)) { /* phi as the pass has it: Silling r0 e = -r0^2, Oterkus 0 */
        if (!oterkus) sum -= w[b] * g.r0 * g.r0;
        continue;
      }
      sum += w[b] * (oterkus ? g.e * ((x[bj[b]] - x[i]) * (X[bj[b]] - X[i]) +
                                      (y[bj[b]] - y[i]) * (Y[bj[b]] - Y[i])) /
                                   (g.r * g.r0)
                             : g.r0 * g.e);
      sx += w[b] * g.grad[0];
      sy += w[b] * g.grad[1];
    }
    th[i] = kappa[i] * sum;
    s0[i] = sx;
    s1[i] = sy;
  }
  return PDK_SUCCESS;
}

/* Rows of the dilatation of p, whose gradient with respect to x_i is g (see above). */
static void dil2_dilatation_rows(const dil2_impl *im, const pdk_model *m, pdk_index p,
                                 const double *g, const pdk_index *loc, double *block) {
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index *bj = pdk_families_bond_j(m->fam);
  const double *X = pdk_particles_X(m->p, 0), *Y = pdk_particles_X(m->p, 1);
  const double *x = pdk_particles_field_data(m->p, "x", 0);
  const double *y = pdk_particles_field_data(m->p, "x", 1);
  const double *V = pdk_particles_volume(m->p);
  const double Ap = im->A[p];
  const double sp[2] = {im->tan_s[0][p], im->tan_s[1][p]};
  double *Kp = block + (size_t)loc[p] * 4;
  for (int e = 0; e < 2; ++e)
    for (int c = 0; c < 2; ++c)
      Kp[e * 2 + c] -= V[p] * Ap * sp[e] * g[c];
  for (pdk_bond_index b = bs[p]; b < bs[p + 1]; ++b) {
    const pdk_index a = bj[b];
    dil2_bond gb;
    dil2_bond_eval(im->oterkus, X, Y, x, y, p, a, &gb);
    if (!(gb.r > 0.0)) continue;
    const pdk_bond_index rb = pdk_bond_reverse(bs, bj, p, a);
    if (rb < 0) continue;
    const double wa = V[a] * im->w[rb] * Ap;
    double *Ka = block + (size_t)loc[a] * 4;
    for (int e = 0; e < 2; ++e)
      for (int c = 0; c < 2; ++c)
        Ka[e * 2 + c] += wa * gb.grad[e] * g[c];
  }
}

static void dil2_tangent_column(const pdk_model *m, pdk_index i, const pdk_index *loc,
                                double *block) {
  const dil2_impl *im = m->impl;
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index *bj = pdk_families_bond_j(m->fam);
  const double *X = pdk_particles_X(m->p, 0), *Y = pdk_particles_X(m->p, 1);
  const double *x = pdk_particles_field_data(m->p, "x", 0);
  const double *y = pdk_particles_field_data(m->p, "x", 1);
  const double *V = pdk_particles_volume(m->p);
  const double *th = im->tan_theta, *A = im->A, *B = im->B, *kappa = im->kappa;
  double *Kii = block + (size_t)loc[i] * 4;
  for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
    const pdk_index j = bj[b];
    dil2_bond gb;
    dil2_bond_eval(im->oterkus, X, Y, x, y, i, j, &gb);
    if (!(gb.r > 0.0)) continue;
    const pdk_bond_index rb = pdk_bond_reverse(bs, bj, i, j);
    const double w_i = im->w[b], w_j = rb >= 0 ? im->w[rb] : 0.0;
    const double at = A[i] * th[i] + A[j] * th[j], bt = B[i] + B[j];
    double M[2][2];
    for (int e = 0; e < 2; ++e)
      for (int c = 0; c < 2; ++c) {
        const double nn = gb.n[e] * gb.n[c];
        M[e][c] = at * gb.hess[e][c] + bt * (nn + gb.e * ((e == c ? 1.0 : 0.0) - nn) / gb.r);
      }
    double *Kji = block + (size_t)loc[j] * 4;
    for (int e = 0; e < 2; ++e)
      for (int c = 0; c < 2; ++c) {
        Kii[e * 2 + c] += V[i] * w_i * M[e][c];
        Kji[e * 2 + c] -= V[j] * w_j * M[e][c];
      }
    if (w_j != 0.0 && A[j] != 0.0) {
      const double g[2] = {-kappa[j] * w_j * gb.grad[0], -kappa[j] * w_j * gb.grad[1]};
      dil2_dilatation_rows(im, m, j, g, loc, block);
    }
  }
  if (A[i] != 0.0) {
    const double g[2] = {-kappa[i] * im->tan_s[0][i], -kappa[i] * im->tan_s[1][i]};
    dil2_dilatation_rows(im, m, i, g, loc, block);
  }
}

const pdk_model_ops pdk_model_ops_dil2 = {.setup = dil2_setup,
                                          .force = dil2_force,
                                          .destroy = dil2_destroy,
                                          .tangent_prepare = dil2_tangent_prepare,
                                          .tangent_column = dil2_tangent_column};

static const pdk_model_ops *oterkus_ops_for(const pdk_model_opts *o) {
  (void)o;
  return &pdk_model_ops_dil2;
}

static const char *const oterkus_scene_keys[] = {"model.influence", "model.gaussian_width",
                                                 "model.oterkus_a", NULL};

const pdk_model_kind_info pdk_model_kind_oterkus = {
    .kind = PDK_MODEL_OTERKUS,
    .name = "oterkus",
    .caps = PDK_KIND_SCENE | PDK_KIND_SHEAR | PDK_KIND_MATERIALS | PDK_KIND_TANGENT,
    .scene_keys = oterkus_scene_keys,
    .hops = 2,
    .scene_stabilization = PDK_STAB_NONE,
    .mem_point = 640,
    .mem_bond = 8,
    .mem_bond_float = 12,
    .mem_newton_bond = 100,
    .ops_for = oterkus_ops_for};
