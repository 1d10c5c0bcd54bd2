/* Peridynamic Galerkin in 3-D: the linear patch test on an irregular cloud (the 2-D test t241 in
 * one more dimension, same code path): [-1, 1]^3, 7 x 7 x 7 nodes, interior nodes jittered by
 * 0.3 h in each direction, face nodes in their face, volumes h^3 halved per face the node lies on;
 * horizon 2.01 h; u affine with a full gradient H, Dirichlet on every face but the top (z = 1,
 * its edges excepted), the traction of the affine field on the top as the nodal force P A_k;
 * Newton to the round-off floor.
 * VC1: relative L2 and H1 errors <= 1e-12 (round-off; measured 4e-16, 1e-15). Uncorrected PBG:
 * errors of order 1e-1 (measured 0.26, 0.34), asserted > 1e-4 and > 1e6 times VC1's.
 * labels: unit galerkin */
#include "galerkin_util.h"

enum { N1 = 7 };

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  const double h = 2.0 / (N1 - 1);
  const pdk_index n = N1 * N1 * N1;
  pdk_particles *p;
  T_OK(ctx, pdk_particles_create(ctx, 3, n, &p));
  T_OK(ctx, pdk_particles_field_add(p, "set:surface", PDK_U8, 1));
  T_OK(ctx, pdk_particles_field_add(p, "set:dirichlet", PDK_U8, 1));
  T_OK(ctx, pdk_particles_field_add(p, "set:top", PDK_U8, 1));
  T_OK(ctx, pdk_particles_field_add(p, "u_exact", PDK_F64, 3));
  T_OK(ctx, pdk_particles_field_add(p, "t_load", PDK_F64, 3));
  uint8_t *surf = pdk_particles_field_data(p, "set:surface", 0);
  uint8_t *dir = pdk_particles_field_data(p, "set:dirichlet", 0);
  uint8_t *top = pdk_particles_field_data(p, "set:top", 0);
  double *X[3], *ue[3], *tl[3];
  for (int c = 0; c < 3; ++c) {
    X[c] = pdk_particles_X(p, c);
    ue[c] = pdk_particles_field_data(p, "u_exact", c);
    tl[c] = pdk_particles_field_data(p, "t_load", c);
  }
  double *V = pdk_particles_volume(p);
  uint64_t s = 3;
  for (int k = 0; k < N1; ++k)
    for (int j = 0; j < N1; ++j)
      for (int i = 0; i < N1; ++i) {
        const int id[3] = {i, j, k};
        const pdk_index q = ((pdk_index)k * N1 + j) * N1 + i;
        int faces = 0;
        V[q] = h * h * h;
        for (int c = 0; c < 3; ++c) {
          const int e = id[c] == 0 || id[c] == N1 - 1;
          const double jit = (2 * pg_rand(&s) - 1) * 0.3 * h;
          X[c][q] = -1.0 + id[c] * h + (e ? 0.0 : jit);
          faces += e;
          if (e) V[q] *= 0.5;
        }
        surf[q] = (uint8_t)(faces > 0);
        top[q] = (uint8_t)(k == N1 - 1 && faces == 1);
        dir[q] = (uint8_t)(faces > 0 && !top[q]);
      }
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = 2.01 * h;
  pdk_families *fam;
  T_OK(ctx, pdk_families_build(p, &fo, &fam));
  const double lam = pg_lambda(), mu = pg_mu();
  const double H[3][3] = {{0.1, 0.3, 0.05}, {0.2, 0.4, -0.1}, {0.07, 0.02, 0.15}};
  const double tr = H[0][0] + H[1][1] + H[2][2];
  double P[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      P[r][c] = mu * (H[r][c] + H[c][r]) + (r == c ? lam * tr : 0.0);
  double err[2][2];
  for (int corr = 0; corr < 2; ++corr) {
    pdk_model_opts mo = pg_model_opts(PDK_GALERKIN_TAYLOR, (pdk_galerkin_correction)corr);
    pdk_model *m;
    T_OK(ctx, pdk_model_create(p, fam, &mo, &m));
    const double *A[3];
    for (int c = 0; c < 3; ++c) {
      A[c] = pdk_particles_field_data(p, "area", c);
      memcpy(pdk_particles_field_data(p, "x", c), X[c], (size_t)n * sizeof(double));
    }
    for (pdk_index q = 0; q < n; ++q)
      for (int c = 0; c < 3; ++c) {
        ue[c][q] = H[c][0] * X[0][q] + H[c][1] * X[1][q] + H[c][2] * X[2][q];
        tl[c][q] = (P[c][0] * A[0][q] + P[c][1] * A[1][q] + P[c][2] * A[2][q]) / V[q];
      }
    pdk_bc bc[2];
    memset(bc, 0, sizeof bc);
    bc[0].kind = PDK_BC_DISPLACEMENT;
    bc[0].set = "set:dirichlet";
    bc[0].scale_field = "u_exact";
    bc[1].kind = PDK_BC_BODY_FORCE;
    bc[1].set = "set:top";
    bc[1].scale_field = "t_load";
    for (int b = 0; b < 2; ++b) {
      bc[b].components = 7;
      for (int c = 0; c < 3; ++c)
        bc[b].value[c] = pdk_tfun_constant(1.0);
    }
    pdk_static_opts so = pdk_static_opts_default(PDK_STATIC_NEWTON);
    so.bcs = bc;
    so.num_bcs = 2;
    so.rtol = 1e-15;
    pdk_static *st;
    T_OK(ctx, pdk_static_create(m, &so, &st));
    T_OK(ctx, pdk_static_solve(st));
    pdk_static_destroy(&st);
    T_OK(ctx, pdk_model_force_trial(m, NULL));
    double e0 = 0, n0 = 0, e1 = 0, n1 = 0;
    for (int c = 0; c < 3; ++c) {
      const double *x = pdk_particles_field_data(p, "x", c);
      for (pdk_index q = 0; q < n; ++q) {
        const double du = x[q] - X[c][q] - ue[c][q];
        e0 += V[q] * du * du;
        n0 += V[q] * ue[c][q] * ue[c][q];
        for (int d = 0; d < 3; ++d) {
          const double *F = pdk_particles_field_data(p, "F", c * 3 + d);
          const double g = F[q] - (c == d ? 1.0 : 0.0) - H[c][d];
          e1 += V[q] * g * g;
          n1 += V[q] * H[c][d] * H[c][d];
        }
      }
    }
    err[corr][0] = sqrt(e0 / n0);
    err[corr][1] = sqrt(e1 / n1);
    T_INFO("3-D correction %d: L2 %.3e H1 %.3e\n", corr, err[corr][0], err[corr][1]);
    pdk_model_destroy(&m);
  }
  T_ASSERT(err[1][0] <= 1e-12 && err[1][1] <= 1e-12, "VC1: L2 %.3e H1 %.3e", err[1][0], err[1][1]);
  T_ASSERT(err[0][0] > 1e-4 && err[0][1] > 1e-4 && err[0][0] > 1e6 * err[1][0] &&
               err[0][1] > 1e6 * err[1][1],
           "uncorrected L2 %.3e H1 %.3e not clearly above VC1's", err[0][0], err[0][1]);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  return 0;
}
