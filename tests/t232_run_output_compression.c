/* output.compression: a scene's field outputs deflated at the level it names, losslessly.
 * The t092 bar (2-D PMB) runs 120 steps through pdk_sim_run twice, with output.compression 0 and
 * 6; in the second file every field output dataset carries the shuffle and deflate filters at
 * level 6, in the first none; the two files hold the same field outputs, static data and
 * histories, objects, attributes and values bit for bit (tests/h5_same.h; the root's scene text
 * differs by the override), so compression changes the bytes on disk only. The field output groups
 * are named with six digits (/steps/000000, ...), so a listing sorted by name is in output order.
 * The files go to $PDK_BUILD_DIR/tests/t232_run_output_compression.work.
 * labels: unit */
#include <unistd.h>

#include "test_util.h"
#include "h5_same.h"

static void run(pdk_ctx *ctx, const char *dir, const char *level) {
  char path[4096], ov[64];
  snprintf(path, sizeof path, "%s/tests/scenes/t092_bar.yaml", getenv("PDK_SOURCE_DIR"));
  snprintf(ov, sizeof ov, "output.compression=%s", level);
  const char *const ovs[] = {ov, "solver.steps=120", "output.field_interval=40"};
  pdk_scene *scene = NULL;
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, ovs, 3, &scene));
  T_ASSERT(pdk_scene_output_get(scene)->compression == atoi(level), "scene compression %d",
           pdk_scene_output_get(scene)->compression);
  T_OK(ctx, pdk_sim_create(ctx, scene, &sim));
  pdk_run_opts o = pdk_run_opts_default();
  o.dir = dir;
  o.plot = 0;
  T_OK(ctx, pdk_sim_run(sim, scene, &o, NULL));
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&scene);
}

/* The deflate level of dataset path (-1: no deflate filter); *shuffled: the shuffle filter. */
static int deflate_level(hid_t file, const char *path, int *shuffled) {
  hid_t d = H5Dopen2(file, path, H5P_DEFAULT);
  T_ASSERT(d >= 0, "cannot open %s", path);
  hid_t dcpl = H5Dget_create_plist(d);
  int level = -1;
  *shuffled = 0;
  for (int k = 0; k < H5Pget_nfilters(dcpl); ++k) {
    unsigned flags, cd[8];
    size_t ncd = 8;
    char name[64];
    unsigned config;
    const H5Z_filter_t id = H5Pget_filter2(dcpl, (unsigned)k, &flags, &ncd, cd, sizeof name, name,
                                           &config);
    if (id == H5Z_FILTER_DEFLATE) level = ncd > 0 ? (int)cd[0] : 0;
    if (id == H5Z_FILTER_SHUFFLE) *shuffled = 1;
  }
  H5Pclose(dcpl);
  H5Dclose(d);
  return level;
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  char work[512], plain[700], packed[700];
  snprintf(work, sizeof work, "%s/tests/t232_run_output_compression.work", getenv("PDK_BUILD_DIR"));
  snprintf(plain, sizeof plain, "%s/plain", work);
  snprintf(packed, sizeof packed, "%s/packed", work);
  run(ctx, plain, "0");
  run(ctx, packed, "6");

  char a[1024], b[1024], why[2048] = "";
  snprintf(a, sizeof a, "%s/bar.h5", plain);
  snprintf(b, sizeof b, "%s/bar.h5", packed);
  hid_t fa = H5Fopen(a, H5F_ACC_RDONLY, H5P_DEFAULT), fb = H5Fopen(b, H5F_ACC_RDONLY, H5P_DEFAULT);
  T_ASSERT(fa >= 0 && fb >= 0, "cannot open %s or %s", a, b);
  /* 120 steps, fields every 40: outputs at steps 0, 40, 80, 120 */
  const char *const fields[] = {"/steps/000000/u", "/steps/000003/u", "/steps/000003/v"};
  for (int k = 0; k < 3; ++k) {
    int sa, sb;
    const int la = deflate_level(fa, fields[k], &sa), lb = deflate_level(fb, fields[k], &sb);
    T_ASSERT(la == -1 && !sa, "%s without compression: deflate %d, shuffle %d", fields[k], la, sa);
    T_ASSERT(lb == 6 && sb, "%s with compression 6: deflate %d, shuffle %d", fields[k], lb, sb);
  }
  T_ASSERT(H5Lexists(fa, "/steps/000004", H5P_DEFAULT) == 0, "four field outputs, no fifth");
  /* the same data: every group but the root, whose scene text holds the override */
  T_ASSERT(h5s_same_output_data(fa, fb, why, sizeof why), "compressed and plain files differ: %s",
           why);
  H5Fclose(fa);
  H5Fclose(fb);
  pdk_ctx_destroy(&ctx);
  return 0;
}
