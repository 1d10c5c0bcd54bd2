/* The shipped scene scenes/galerkin_patch.yaml: the Peridynamic Galerkin model's linear patch test
 * on 1369 irregular particles (galerkin_patch.csv), uniaxial stress along x (left held in x,
 * bottom in y, right pulled 2 mm, top free), taylor basis with the vc1 correction, Newton.
 * labels: scene galerkin
 *
 * What must hold, and why these bounds.
 * - vc1 with the box's normals ("sn"): the affine field u_x = 1e-3 (X + 1),
 *   u_y = -nu/(1 - nu) 1e-3 (Y + 1) is the discrete solution (the interior area vectors vanish,
 *   the edges' are normal to them, and the uniaxial stress has P n = 0 on the free top and no
 *   tangential traction on the rollers), so the errors are those of the solve: Newton to 1e-12 of
 *   the load (two iterations) leaves 2.8e-14 (L2) and 4.8e-13 (H1) relative (measured); asserted
 *   L2 <= 1e-12, H1 <= 1e-11, and each reaction equal to E/(1 - nu^2) 1e-3 x 2 m (219.78 N,
 *   thickness 1) to 1e-10 relative (the right edge's area vectors sum to its length, 2 m, for any
 *   cloud: first-order consistency).
 * - the same with the bond correction (model.galerkin.bond=true: the V5 correction functions):
 *   the same bounds (the affine field is still reproduced, t269).
 * - vc1 without normals ("s": the override model.galerkin={..., surface: surface}): the edges'
 *   area vectors keep tangential parts and the stress puts spurious forces on the free top and the
 *   rollers' free components: measured L2 1.4e-2, H1 0.20, reaction 1 % low; asserted L2 > 1e-5
 *   (why the scene gives the normals).
 * - correction none (the override model.galerkin={basis: taylor, correction: none}): the same run
 *   misses the field by order 1e-1 (measured: L2 7.2e-2, H1 0.36, reaction 187.1 N, 15 % low;
 *   asserted: L2 > 1e-3 and > 1e4 times vc1's).
 */
#include "pdk/scene.h"
#include "test_util.h"

typedef struct result {
  double l2, h1, r_right, r_left;
} result;

static result run(pdk_ctx *ctx, const char *path, const char *const *ov, int nov) {
  pdk_scene *s = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, ov, nov, &s));
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  pdk_history h;
  T_OK(ctx, pdk_sim_static_step(sim, &h));
  pdk_particles *p = pdk_sim_particles(sim);
  const double nu = 0.3, e = 1e-3, H[2][2] = {{e, 0}, {0, -nu / (1 - nu) * e}};
  const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1), *V = pdk_particles_volume(p);
  const double *x[2] = {pdk_particles_field_data(p, "x", 0), pdk_particles_field_data(p, "x", 1)};
  const double *F[4];
  for (int t = 0; t < 4; ++t)
    F[t] = pdk_particles_field_data(p, "F", t);
  double e0 = 0, n0 = 0, e1 = 0, n1 = 0;
  for (pdk_index k = 0; k < pdk_particles_count(p); ++k) {
    const double ue[2] = {H[0][0] * (X[k] + 1), H[1][1] * (Y[k] + 1)};
    const double uh[2] = {x[0][k] - X[k], x[1][k] - Y[k]};
    for (int c = 0; c < 2; ++c) {
      e0 += V[k] * (uh[c] - ue[c]) * (uh[c] - ue[c]);
      n0 += V[k] * ue[c] * ue[c];
    }
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c) {
        const double g = F[r * 2 + c][k] - (r == c ? 1.0 : 0.0);
        e1 += V[k] * (g - H[r][c]) * (g - H[r][c]);
        n1 += V[k] * H[r][c] * H[r][c];
      }
  }
  result res = {sqrt(e0 / n0), sqrt(e1 / n1), h.reaction[0][0], h.reaction[1][0]};
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  return res;
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  const char *src = getenv("PDK_SOURCE_DIR");
  T_ASSERT(src, "PDK_SOURCE_DIR is not set (run through ctest)");
  char path[4096];
  snprintf(path, sizeof path, "%s/scenes/galerkin_patch.yaml", src);
  const double E = 1e5, nu = 0.3, reaction = E / (1 - nu * nu) * 1e-3 * 2.0;
  const result vc = run(ctx, path, NULL, 0);
  T_INFO("vc1: L2 %.3e H1 %.3e, reactions %.12g %.12g (exact %.12g)\n", vc.l2, vc.h1, vc.r_right,
         vc.r_left, reaction);
  T_ASSERT(vc.l2 <= 1e-12 && vc.h1 <= 1e-11, "vc1: L2 %.3e H1 %.3e", vc.l2, vc.h1);
  T_NEAR(vc.r_right, reaction, 1e-10, 0.0, "vc1: the right edge's reaction");
  T_NEAR(vc.r_left, -reaction, 1e-10, 0.0, "vc1: the left edge's reaction");
  const char *ovb[] = {"model.galerkin.bond=true"};
  const result bond = run(ctx, path, ovb, 1);
  T_INFO("vc1 bond: L2 %.3e H1 %.3e, reactions %.12g %.12g\n", bond.l2, bond.h1, bond.r_right,
         bond.r_left);
  T_ASSERT(bond.l2 <= 1e-12 && bond.h1 <= 1e-11, "vc1 bond: L2 %.3e H1 %.3e", bond.l2, bond.h1);
  T_NEAR(bond.r_right, reaction, 1e-10, 0.0, "vc1 bond: the right edge's reaction");
  const char *ovs[] = {"model.galerkin={basis: taylor, correction: vc1, surface: surface}"};
  const result sonly = run(ctx, path, ovs, 1);
  T_INFO("vc1 s: L2 %.3e H1 %.3e, reactions %.12g %.12g\n", sonly.l2, sonly.h1, sonly.r_right,
         sonly.r_left);
  T_ASSERT(sonly.l2 > 1e-5, "vc1 without normals: L2 %.3e (expected visible)", sonly.l2);
  const char *ov[] = {"model.galerkin={basis: taylor, correction: none}"};
  const result none = run(ctx, path, ov, 1);
  T_INFO("none: L2 %.3e H1 %.3e, reactions %.12g %.12g\n", none.l2, none.h1, none.r_right,
         none.r_left);
  T_ASSERT(none.l2 > 1e-3 && none.l2 > 1e4 * vc.l2, "correction none: L2 %.3e (vc1 %.3e)", none.l2,
           vc.l2);
  pdk_ctx_destroy(&ctx);
  return 0;
}
