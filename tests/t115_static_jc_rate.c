/* Johnson-Cook rate terms under static load steps: each load step has a pseudo-time, and the
 * model's time step is the step's increment, so the rate hardening follows the load rate.
 *
 * A plane-strain block (8 x 8 mm, 1 mm spacing) of the V-JC steel with a rate term (C = 0.05,
 * reference rate 1/s, damage off) on rollers at the bottom and left, the top pulled by a linear
 * displacement to a mean strain of 2% in 10 load steps, once over 20 ms (strain rate 1/s) and once
 * over 20 us (1000/s), by ADR (and the fast one by Newton too). Checks:
 *   - the model's time step during step k is t_k - t_{k-1} (2 ms or 2 us);
 *   - the field eps_p_rate is the step's plastic strain increment over that time step, particle
 *     by particle (to 1e-9: the kernel divides the return-map increment by dt; the committed
 *     eps_p differences carry round-off only);
 *   - physics: in the last step the flow is almost all plastic, at an equivalent plastic rate of
 *     2/sqrt(3) times the applied rate (plane strain, free x face, incompressible flow): the mean
 *     over yielding particles is within 15% of it (the field is not homogeneous near the free face
 *     and the corners);
 *   - the reaction at 2% is higher at 1000/s by the Johnson-Cook factor
 *       (1 + C ln(1000 r)) / (1 + C ln r),  r = 2/sqrt(3) (rate* = max(rate/ref, 1)),
 *     = 1.343, within 3% (the local rate factor varies with the local rate, which the
 *     logarithm damps: a 15% rate spread moves the factor by 0.7%). Passing no time step leaves
 *     the commits without one (refused) or with a stale one, and fails all of these.
 * labels: physics
 */
#include "pdk/scene.h"
#include "test_util.h"

static const char *scene_fmt =
    "dimension: 2\n"
    "geometry: {spacing: 1.0e-3, box: {lo: [0, 0], hi: [0.008, 0.008]}}\n"
    "material:\n"
    "  density: 7830\n"
    "  youngs_modulus: 200.0e9\n"
    "  poisson_ratio: 0.29\n"
    "  johnson_cook: {A: 792.0e6, B: 510.0e6, n: 0.26, C: 0.05, reference_strain_rate: 1.0,\n"
    "                 damage: false}\n"
    "model: {kind: correspondence, law: jc, influence: constant, stabilization: silling}\n"
    "sets:\n"
    "  - {name: bottom, box: {lo: [-1, -1], hi: [1, 0.001]}}\n"
    "  - {name: left, box: {lo: [-1, -1], hi: [0.001, 1]}}\n"
    "  - {name: top, box: {lo: [-1, 0.007], hi: [1, 1]}}\n"
    "boundary_conditions:\n"
    "  - {set: bottom, type: displacement, y: 0}\n"
    "  - {set: left, type: displacement, x: 0}\n"
    "  - {set: top, type: displacement, y: %.17g, function: linear}\n"
    "solver: {type: %s, load_steps: 10, end_time: %.17g}\n"
    "output: {reactions: [top]}\n";

#define H 0.007 /* distance between the bottom and top rows [m] */

static double run(double rate, const char *method, double *mean_rate_ratio) {
  const double T = 0.02 / rate; /* 2% strain */
  const double v = 0.02 * H / T;
  char text[4096];
  snprintf(text, sizeof text, scene_fmt, v, method, T);
  FILE *f = fopen("t115_scene.yaml", "wb");
  T_ASSERT(f && fputs(text, f) >= 0 && !fclose(f), "writing the scene");
  pdk_ctx *ctx = t_ctx(2);
  pdk_scene *s = NULL;
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_scene_load(ctx, "t115_scene.yaml", NULL, 0, &s));
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  pdk_particles *p = pdk_sim_particles(sim);
  const pdk_index n = pdk_particles_count(p);
  double *ep_prev = calloc((size_t)n, sizeof(double));
  const double *ep = pdk_particles_field_data(p, "eps_p", 0);
  const double *ep_rate = pdk_particles_field_data(p, "eps_p_rate", 0);
  T_ASSERT(ep_prev && ep && ep_rate, "Johnson-Cook history fields");
  pdk_history h;
  for (int k = 0; k < 10; ++k) {
    T_OK(ctx, pdk_sim_static_step(sim, &h));
    const double dt = T / 10;
    T_NEAR(pdk_model_get_dt(pdk_sim_model(sim)), dt, 1e-12, 0, "time step of load step %d", k);
    T_NEAR(h.time, (k + 1) * dt, 1e-12, 0, "pseudo-time of load step %d", k);
    double sum = 0.0;
    int count = 0;
    for (pdk_index i = 0; i < n; ++i) {
      const double inc = ep[i] - ep_prev[i];
      T_NEAR(ep_rate[i] * dt, inc, 1e-9, 1e-15, "eps_p_rate x dt = increment, particle %d", (int)i);
      if (k == 9 && inc > 0) {
        sum += ep_rate[i];
        ++count;
      }
      ep_prev[i] = ep[i];
    }
    if (k == 9) {
      T_ASSERT(count > n / 2, "most particles yield (%d of %d)", count, (int)n);
      *mean_rate_ratio = sum / count / rate;
    }
  }
  const double reaction = h.reaction[0][1];
  free(ep_prev);
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  pdk_ctx_destroy(&ctx);
  remove("t115_scene.yaml");
  return reaction;
}

int main(void) {
  const double C = 0.05, r = 2.0 / sqrt(3.0);
  double ratio_slow = 0, ratio_fast = 0, ratio_newton = 0;
  const double slow = run(1.0, "adr", &ratio_slow);
  const double fast = run(1000.0, "adr", &ratio_fast);
  const double fast_newton = run(1000.0, "newton", &ratio_newton);
  const double expected = (1.0 + C * log(1000.0 * r)) / (1.0 + C * log(r));
  if (getenv("PDK_TEST_VERBOSE"))
    printf("reaction slow %.6g fast %.6g (newton %.6g), ratio %.4f expected %.4f; plastic rate / "
           "applied: %.3f %.3f %.3f (2/sqrt 3 = %.3f)\n",
           slow, fast, fast_newton, fast / slow, expected, ratio_slow, ratio_fast, ratio_newton, r);
  T_ASSERT(slow > 0 && fast > 0, "the top is pulled: positive reactions");
  T_NEAR(ratio_slow, r, 0.15, 0, "plastic rate at 1/s");
  T_NEAR(ratio_fast, r, 0.15, 0, "plastic rate at 1000/s");
  T_NEAR(fast / slow, expected, 0.03, 0, "Johnson-Cook rate factor on the reaction");
  /* Newton and ADR solve the same steps: ADR stops at 1e-6 of the load norm */
  T_NEAR(fast_newton, fast, 1e-3, 0, "Newton vs ADR at 1000/s");
  return 0;
}
