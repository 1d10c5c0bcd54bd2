/* Checkpoint and restart of a tearing Johnson-Cook bar: bitwise the same as a continuous run.
 *
 * The notched bar of t101 (JC damage with a short failure strain, Silling stabilization, left end
 * fixed, right end pulled at 10 m/s), in TL and semi-TL with compaction in every breaking pass:
 * 400 steps in one go against 300 steps, a checkpoint, everything destroyed and rebuilt, a
 * restore and 100 steps. Bonds start breaking near step 270 and the bar separates near step 340,
 * so the checkpoint falls in the middle of the tear: the restored semi-TL model starts without
 * its compacted bond list (it walks the families with the restored bond state until its next
 * compaction) and recomputes K of every particle with broken bonds, and must still give the same
 * bits. Compared: x, v, f, every history field (cp_inv, eps_p, damage, failed, eps_p_rate,
 * w_plastic, w_damage, w_broken), the bond state and the last history record (energies included).
 * On 1 and 2 threads. A third run in TL with softened stabilization, the family-averaged
 * triaxiality and the continuous stress at breaks also compares their fields (stab_factor,
 * w_stab, w_silling, sigma_m, sigma_m_avg; the checkpoint stores every field, and the factors'
 * scratch is rewritten by every commit; the remapped C_p^-1, whose det is no longer 1, is
 * restored as it was).
 * (D2 = 0 here, so the damage does not depend on the triaxiality; t105 tests that it is used.)
 * labels: unit threads */
#include "jc_corr_util.h"
#include "pdk/output.h"

#define N_STEPS 400
#define N_FIRST 300

typedef jcu_sim sim;


static void build(pdk_ctx *ctx, pdk_connectivity mode, int options, sim *s) {
  jcu_bar(ctx, 1, &s->p, &s->fam);
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = PDK_MODEL_CORRESPONDENCE;
  mo.law = PDK_LAW_JC;
  mo.jc.D1 = 0.02;
  mo.jc.D2 = 0.0;
  mo.stabilization = PDK_STAB_SILLING;
  mo.connectivity = mode;
  mo.compact_fraction = 0.0;
  mo.stab_softening = options;
  mo.damage_triaxiality = options ? PDK_TRIAX_FAMILY : PDK_TRIAX_LOCAL;
  mo.break_stress = options ? PDK_BREAK_STRESS_CONTINUOUS : PDK_BREAK_STRESS_REFIT;
  T_OK(ctx, pdk_model_create(s->p, s->fam, &mo, &s->m));
  jcu_bar_pull(s->bcs, 0, 10.0);
  pdk_explicit_opts eo = pdk_explicit_opts_default();
  eo.bcs = s->bcs;
  eo.num_bcs = 2;
  eo.dt = 1.5e-7;
  T_OK(ctx, pdk_explicit_create(s->m, &eo, &s->e));
}

/* x, v, f, history fields and bond state as bytes. */
static unsigned char *state_bytes(sim *s, size_t *bytes) {
  const pdk_index n = pdk_particles_count(s->p);
  const char *names[3] = {"x", "v", "f"};
  const size_t len = (size_t)n * sizeof(double);
  jcu_snapshot h = jcu_snapshot_take(s->m);
  unsigned char *out = malloc(6 * len + h.bytes);
  T_ASSERT(out, "out of memory");
  for (int q = 0; q < 3; ++q)
    for (int c = 0; c < 2; ++c)
      memcpy(out + (2 * q + c) * len, pdk_particles_field_data(s->p, names[q], c), len);
  memcpy(out + 6 * len, h.data, h.bytes);
  free(h.data);
  *bytes = 6 * len + h.bytes;
  return out;
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  const char *path = "t104_jc.ckpt.h5";
  for (int mode = 0; mode < 3; ++mode) {
    const pdk_connectivity conn = mode == 1 ? PDK_CONNECTIVITY_SEMI_TL : PDK_CONNECTIVITY_TL;
    const int opt = mode == 2; /* softened, family triaxiality, continuous at breaks */
    for (int threads = 1; threads <= 2; ++threads) {
      T_OK(ctx, pdk_ctx_set_num_threads(ctx, threads));
      const char *what = mode == 2 ? "TL, softened + family + continuous" : mode ? "semi-TL" : "TL";
      sim s;
      pdk_history h1, h2;
      build(ctx, conn, opt, &s);
      T_OK(ctx, pdk_explicit_run(s.e, N_STEPS, &h1));
      T_ASSERT(h1.broken > 0 && pdk_model_num_failed(s.m) > 0, "%s: nothing broke", what);
      size_t b1, b2;
      unsigned char *one = state_bytes(&s, &b1);
      jcu_sim_destroy(&s);

      build(ctx, conn, opt, &s);
      T_OK(ctx, pdk_explicit_run(s.e, N_FIRST, NULL));
      T_ASSERT(pdk_model_num_broken(s.m) > 0, "%s: no bond broken before the checkpoint", what);
      T_OK(ctx, pdk_checkpoint_write(ctx, path, s.e, NULL));
      jcu_sim_destroy(&s);
      build(ctx, conn, opt, &s);
      T_OK(ctx, pdk_checkpoint_read(ctx, path, s.e));
      T_OK(ctx, pdk_explicit_run(s.e, N_STEPS - N_FIRST, &h2));
      unsigned char *two = state_bytes(&s, &b2);
      T_ASSERT(b1 == b2 && !memcmp(one, two, b1), "%s, %d threads: restarted state differs", what,
               threads);
      T_ASSERT(!memcmp(&h1, &h2, sizeof h1),
               "%s, %d threads: history differs: strain %.17g vs %.17g, plastic %.17g vs %.17g, "
               "breaking %.17g vs %.17g",
               what, threads, h1.strain, h2.strain, h1.plastic_work, h2.plastic_work,
               h1.breaking_work, h2.breaking_work);
      free(one);
      free(two);
      jcu_sim_destroy(&s);
      remove(path);
    }
  }
  pdk_ctx_destroy(&ctx);
  return 0;
}
