/* The static solvers' message for a residual that is no longer finite names a real particle, what
 * was not finite and the boundary condition to check. scenes/bar_tension_static.yaml with its
 * pulled end's displacement raised to absurd values:
 *   1e200  every force and position stays finite (forces ~1e207) but the squared norm overflows:
 *          the message says so and names the particle with the largest residual force;
 *   1e300  the forces themselves become NaN: the message names the first such particle.
 * Both name the prescribed displacement's condition (index 2, set 'pulled') and ask to check the
 * boundary conditions and load steps. Before, the message said "particle -1 (id -1)" for the
 * overflow (no single value was non-finite) and named no condition. ADR and Newton share it.
 * labels: unit
 */
#include "pdk/scene.h"
#include "test_util.h"

/* The particle index and id the message names: "particle <i> (id <id>)"; the first occurrence. */
static void named_particle(const char *msg, long long *index, long long *id) {
  const char *p = strstr(msg, "particle ");
  T_ASSERT(p, "message names no particle: %s", msg);
  T_ASSERT(sscanf(p, "particle %lld (id %lld)", index, id) == 2, "unparsed: %s", msg);
}

static void check(const char *method, const char *value, const char *what) {
  pdk_ctx *ctx = t_ctx(2);
  char path[1024], type[64], bc[64];
  snprintf(path, sizeof path, "%s/scenes/bar_tension_static.yaml", getenv("PDK_SOURCE_DIR"));
  snprintf(type, sizeof type, "solver.type=%s", method);
  snprintf(bc, sizeof bc, "boundary_conditions[2].x=%s", value);
  const char *ov[2] = {type, bc};
  pdk_scene *s = NULL;
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, ov, 2, &s));
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  const pdk_index n = pdk_particles_count(pdk_sim_particles(sim));
  const int64_t *ids = pdk_particles_id(pdk_sim_particles(sim));
  T_FAILS(ctx, pdk_sim_static_step(sim, NULL), PDK_ERR_NUMERIC, "non-finite");
  const char *msg = pdk_ctx_error_message(ctx);
  long long i = -1, id = -1;
  named_particle(msg, &i, &id);
  T_ASSERT(i >= 0 && i < n && id == ids[i], "%s %s: not a particle of the body: %s", method, value,
           msg);
  T_ASSERT(strstr(msg, what), "%s %s: message does not say '%s': %s", method, value, what, msg);
  T_ASSERT(strstr(msg, "boundary condition 2 on set 'pulled'"), "%s: no condition named: %s",
           method, msg);
  T_ASSERT(strstr(msg, "check the boundary conditions"), "%s: no remedy: %s", method, msg);
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  pdk_ctx_destroy(&ctx);
}

int main(void) {
  check("adr", "1e200", "residual norm overflowed");
  check("newton", "1e200", "residual norm overflowed");
  check("adr", "1e300", "the residual force on particle");
  return 0;
}
