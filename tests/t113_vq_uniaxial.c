/* V-Q3 / V-Q4 smoke test (Queiruga & Moridis 2017 section 4.1): uniaxial
 * compression of a 10 mm square, correspondence (F-based) law, cubic influence, RF = 1.5, solved
 * by Newton at two resolutions; the top-displacement error falls with order about 1.
 * labels: physics
 *
 * Setup as the paper (Table 1, Fig. 5): H = W = 10 mm, E = 1000 GPa, nu = 0, plane strain, T = 1e-3
 * GPa (N-mm-GPa units: forces in kN); node-type grid (particles on the boundary lines); bottom row
 * clamped, side columns on vertical rollers (u_x = 0), traction on the top row as a body force
 * b = T W / (N_top V) (notes 2.6); the small-strain linear law without stabilization (the paper
 * has none). Exact top displacement u_y = -T H / E = -1e-5 mm (compression: negative). Probe: mean
 * u_y over the top particles with 0.4 W <= x <= 0.6 W.
 *
 * Expected: the paper's order for this case is 0.9999 (Table 3/4, a fit over NP > 99); V-Q3 allows
 * 0.92-1.04 over the influence functions and problems. Between NP = 40 and 80 we measure 0.985; the
 * test accepts [0.9, 1.1] (pre-asymptotic at these sizes, where the 1/NP boundary-layer error still
 * carries a few per cent of higher-order terms). Errors: 3.7% and 1.9%; the test requires them
 * below 5% and 2.5% (first order with a constant of ~1.5 h / H, as the paper's Fig. 8 shows for
 * RF 1.5).
 */
#include "test_util.h"
#include "vq_util.h"

/* The block and probe of tests/vq_util.h (the setup described above). */
static double probe(pdk_ctx *ctx, int np) {
  vq_case c = {VQ_UNIAXIAL, VQ_F, PDK_INFLUENCE_CUBIC, 1.5, np, PDK_OTERKUS_A_PUBLISHED, 2, 0.0, 0};
  vq_result r;
  T_ASSERT(vq_run(ctx, &c, &r) == 0, "NP = %d: the solve failed", np);
  T_ASSERT(r.exact == -1e-5, "exact top displacement %g", r.exact);
  T_ASSERT(r.probe_count == np / 5 + 1, "probe holds %d particles at NP = %d", r.probe_count, np);
  return r.probe;
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  const double exact = -1e-5;
  const int np[2] = {40, 80};
  double err[2];
  for (int k = 0; k < 2; ++k) {
    const double u = probe(ctx, np[k]);
    T_ASSERT(u < 0, "NP = %d: the top moved up (u_y = %g) under compression", np[k], u);
    err[k] = fabs(u - exact) / fabs(exact);
    if (getenv("PDK_TEST_VERBOSE"))
      printf("NP %d: u_y %.10e, relative error %.4e\n", np[k], u, err[k]);
  }
  const double order = log(err[0] / err[1]) / log(2.0);
  if (getenv("PDK_TEST_VERBOSE")) printf("order %.4f\n", order);
  T_ASSERT(err[0] < 0.05 && err[1] < 0.025, "errors %.3e (NP 40), %.3e (NP 80)", err[0], err[1]);
  T_ASSERT(order >= 0.9 && order <= 1.1, "convergence order %.4f, expected about 1 (V-Q3)", order);
  pdk_ctx_destroy(&ctx);
  return 0;
}
