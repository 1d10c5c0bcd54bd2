/* scenes/plate_two_holes_close.yaml at 0.5 and 0.25 mm, TL, each run past its first failures in
 * the band between the holes and in the outer ligaments (to 0.85 and 0.75 ms): pdk's first
 * failures converge to the finite-element reference of the same geometry in place, order and grip
 * displacement (reference and shared checks: plate_two_holes_close.h; the band at 1.200 mm, the
 * outer ligaments at 1.350 mm, force at 1.2 mm 40.06 kN).
 * Checked:
 *   - at both spacings: the first failing particles all in the band, the outer ligaments at least
 *     3% later (measured 7% and 8%);
 *   - at 0.25 mm both first failures within 8% of the reference's grip displacement (measured
 *     1.247 and 1.348 mm: +3.9%, -0.1%), each closer to it than at 0.5 mm (1.451, 1.552 mm), and
 *     the force at 1.2 mm within 2% (measured 40.45 kN, +1.0%) and closer than at 0.5 mm
 *     (41.66 kN). 8% and 2% are about twice the measured errors: a finer reference or spacing
 *     would move them by that much (the reference's own outer value moves by 0.7% between its
 *     meshes).
 * Numbers and the 1 mm run: docs/validation/plate_two_holes.md, item 11. Run time: about 6
 * minutes on 2 cores (measured 340 s).
 *   PDK_TEST_VERBOSE=1 ctest --test-dir build -R t128 -V
 * labels: physics slow */
#include "plate_two_holes_close.h"

int main(void) {
  pdk_ctx *ctx = t_ctx(0);
  phc_result c, f;
  phc_run(ctx, "0.5e-3", 0.85e-3, &c);
  phc_run(ctx, "0.25e-3", 0.75e-3, &f);
  const double ei = fabs(f.u_inner - PHC_FE_INNER), eo = fabs(f.u_outer - PHC_FE_OUTER);
  T_ASSERT(ei < 0.08 * PHC_FE_INNER && ei < fabs(c.u_inner - PHC_FE_INNER),
           "0.25 mm: first failure in the band at grip u %g m (0.5 mm: %g m), reference %g m",
           f.u_inner, c.u_inner, PHC_FE_INNER);
  T_ASSERT(eo < 0.08 * PHC_FE_OUTER && eo < fabs(c.u_outer - PHC_FE_OUTER),
           "0.25 mm: first failure outside the band at grip u %g m (0.5 mm: %g m), reference %g m",
           f.u_outer, c.u_outer, PHC_FE_OUTER);
  const double ef = fabs(f.r.force_at_ref - PHC_FE_FORCE);
  T_ASSERT(ef < 0.02 * PHC_FE_FORCE && ef < fabs(c.r.force_at_ref - PHC_FE_FORCE),
           "0.25 mm: force at 1.2 mm %g N (0.5 mm: %g N), reference %g N", f.r.force_at_ref,
           c.r.force_at_ref, PHC_FE_FORCE);
  pdk_ctx_destroy(&ctx);
  return 0;
}
