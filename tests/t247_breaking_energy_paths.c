/* The breaking energy of PMB and LPS ("w_broken", src/models/model_bond_book.c) on every path and
 * across a restart, on the pre-cracked plate of crack_plate_util.h (200 us, the crack grows):
 *   - a run stopped right after a pass that broke bonds (half of their energy still pending),
 *     checkpointed, and restored into a freshly built simulation ends with bitwise the same
 *     "w_broken", strain energy and breaking work as the run that never stopped;
 *   - the stencil path (the scene's default on this lattice), the general path (model.stencil
 *     off) and layout sell break the same bonds (the stencil's stretches are the general path's
 *     bits) and book the same breaking work to round-off (1e-8 relative: the paths sum the
 *     families in other orders, so positions drift apart by round-off, which the growing crack
 *     amplifies; measured 3e-11 (stencil off) and 1e-10 (sell) for PMB; a path that did not book
 *     would miss all of it);
 *   - 2 threads give the 1-thread bits (breaking work and "w_broken").
 * labels: unit threads */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pdk/output.h"
#include "test_util.h"
#include "crack_plate_util.h"

typedef struct end {
  pdk_history h;
  pdk_index n;
  double *w;
} end;

static end finish(pdk_ctx *ctx, pdk_sim *sim, long steps) {
  end r;
  T_OK(ctx, pdk_explicit_run(pdk_sim_explicit(sim), steps, &r.h));
  pdk_particles *p = pdk_sim_particles(sim);
  r.n = pdk_particles_count(p);
  r.w = malloc((size_t)r.n * sizeof(double));
  memcpy(r.w, pdk_particles_field_data(p, "w_broken", 0), (size_t)r.n * sizeof(double));
  return r;
}

static end run_path(const char *kind, const char *path_override, int threads) {
  pdk_ctx *ctx = t_ctx(threads);
  const char *ov[] = {kind, path_override};
  pdk_sim *sim = cp_build(ctx, "t247.yaml", ov, path_override ? 2 : 1, NULL);
  end r = finish(ctx, sim, pdk_sim_num_steps(sim));
  pdk_sim_destroy(&sim);
  pdk_ctx_destroy(&ctx);
  return r;
}

static void same(const end *a, const end *b, const char *what) {
  T_ASSERT(a->h.breaking_work == b->h.breaking_work && a->h.strain == b->h.strain &&
               !memcmp(a->w, b->w, (size_t)a->n * sizeof(double)),
           "%s: breaking %.17g vs %.17g, strain %.17g vs %.17g, or w_broken differ", what,
           a->h.breaking_work, b->h.breaking_work, a->h.strain, b->h.strain);
}

static void check_restart(const char *kind, const end *whole) {
  pdk_ctx *ctx = t_ctx(2);
  const char *ov[] = {kind};
  pdk_sim *sim = cp_build(ctx, "t247.yaml", ov, 1, NULL);
  const long steps = pdk_sim_num_steps(sim);
  pdk_explicit *e = pdk_sim_explicit(sim);
  pdk_history h;
  long s = 0;
  pdk_bond_index before = 0;
  int found = 0;
  /* the first step past a third of the run whose pass broke bonds */
  while (s < steps - 1 && !found) {
    T_OK(ctx, pdk_explicit_run(e, 1, &h));
    ++s;
    found = s > steps / 3 && h.broken > before;
    before = h.broken;
  }
  T_ASSERT(found, "%s: no step broke bonds", kind);
  T_OK(ctx, pdk_checkpoint_write(ctx, "t247.h5", e, NULL));
  pdk_sim_destroy(&sim);
  sim = cp_build(ctx, "t247.yaml", ov, 1, NULL);
  T_OK(ctx, pdk_checkpoint_read(ctx, "t247.h5", pdk_sim_explicit(sim)));
  end r = finish(ctx, sim, steps - s);
  T_INFO("%s: restarted at step %ld of %ld (%lld bonds broken then)\n", kind, s, steps,
         (long long)before);
  same(&r, whole, "restart");
  free(r.w);
  pdk_sim_destroy(&sim);
  pdk_ctx_destroy(&ctx);
  remove("t247.h5");
}

int main(void) {
  const char *kinds[] = {"model.kind=pmb", "model.kind=lps"};
  for (int k = 0; k < 2; ++k) {
    end a = run_path(kinds[k], NULL, 2), a1 = run_path(kinds[k], NULL, 1);
    same(&a, &a1, "1 and 2 threads");
    check_restart(kinds[k], &a);
    const char *paths[] = {"model.stencil=off", "model.layout=sell"};
    for (int q = 0; q < 2; ++q) {
      end b = run_path(kinds[k], paths[q], 2);
      T_INFO("%s %s: breaking %.17g (stencil %.17g), %lld bonds broken\n", kinds[k], paths[q],
             b.h.breaking_work, a.h.breaking_work, (long long)b.h.broken);
      T_ASSERT(b.h.broken == a.h.broken, "%s %s: %lld bonds broken, stencil path %lld", kinds[k],
               paths[q], (long long)b.h.broken, (long long)a.h.broken);
      T_NEAR(b.h.breaking_work, a.h.breaking_work, 1e-8, 0.0, "%s %s: breaking work", kinds[k],
             paths[q]);
      free(b.w);
    }
    free(a.w), free(a1.w);
  }
  remove("t247.yaml");
  return 0;
}
