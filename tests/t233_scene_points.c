/* geometry.points: a body read from a point-cloud CSV file.
 * 1. The t092 bar (2-D PMB, bonds break) written out as a cloud (its lattice's positions and
 *    volumes with 17 digits, in id order, and its sets left and right as set: columns), and the
 *    scene that reads it (no sets list: the columns define them; no box): both runs give the same
 *    field outputs, histories and static data bit for bit (tests/h5_same.h) and the same history
 *    CSV byte for byte, so the cloud path builds the very body the lattice path builds.
 *    The same cloud as an HDF5 file (datasets X [n][2], volume [n], sets/left, sets/right at the
 *    root) runs bit for bit the same too; the output file of the lattice run (its /static group)
 *    loads as a cloud with the run's particles and sets.
 * 2. 2-D `area` columns are multiplied by geometry.thickness.
 * 3. Bad clouds fail at load with a message naming the scene key, the CSV file and line, and what
 *    to do: no header, an unknown column, a missing volume, a cell that is no number, a row with
 *    too few or too many values, a negative volume, a set column with a 2, a set column with no
 *    member, a set named by both a column and the sets list, geometry.box beside geometry.points,
 *    a missing file, no geometry.box nor points.
 * The files go to $PDK_BUILD_DIR/tests/t233_scene_points.work.
 * labels: unit */
#include <sys/stat.h>

#include "work_util.h"
#include "h5_same.h"

static void run_scene(pdk_ctx *ctx, const char *scene_path, const char *dir) {
  pdk_scene *scene = NULL;
  pdk_sim *sim = NULL;
  const char *const ov[] = {"solver.steps=200"};
  T_OK(ctx, pdk_scene_load(ctx, scene_path, ov, 1, &scene));
  T_OK(ctx, pdk_sim_create(ctx, scene, &sim));
  pdk_run_opts o = pdk_run_opts_default();
  o.dir = dir;
  o.plot = 0;
  pdk_run_report rep;
  T_OK(ctx, pdk_sim_run(sim, scene, &o, &rep));
  T_ASSERT(rep.last.broken > 0, "the bar breaks bonds in 200 steps (%ld broken)",
           (long)rep.last.broken);
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&scene);
}

/* The lattice body of the t092 bar as CSV: x, y, volume, set:left, set:right in id order. */
static void write_cloud(pdk_ctx *ctx, const char *lattice_scene) {
  pdk_scene *scene = NULL;
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_scene_load(ctx, lattice_scene, NULL, 0, &scene));
  T_OK(ctx, pdk_sim_create(ctx, scene, &sim));
  pdk_particles *p = pdk_sim_particles(sim);
  const pdk_index n = pdk_particles_count(p);
  const int64_t *id = pdk_particles_id(p);
  pdk_index *at = malloc((size_t)n * sizeof *at);
  for (pdk_index i = 0; i < n; ++i)
    at[id[i]] = i;
  const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1);
  const double *V = pdk_particles_volume(p);
  const uint8_t *left = pdk_particles_field_data(p, "set:left", 0);
  const uint8_t *right = pdk_particles_field_data(p, "set:right", 0);
  char path[1024];
  snprintf(path, sizeof path, "%s/bar.csv", work);
  FILE *f = fopen(path, "w");
  T_ASSERT(f != NULL, "cannot write %s", path);
  fprintf(f, "# the t092 bar's lattice\nx, y, volume, set:left, set:right\n");
  double *xy = malloc(2 * (size_t)n * sizeof(double)), *vol = malloc((size_t)n * sizeof(double));
  uint8_t *sl = malloc((size_t)n), *sr = malloc((size_t)n);
  for (pdk_index k = 0; k < n; ++k) {
    const pdk_index i = at[k];
    fprintf(f, "%.17g,%.17g,%.17g,%d,%d\n", X[i], Y[i], V[i], left[i], right[i]);
    xy[2 * k] = X[i], xy[2 * k + 1] = Y[i], vol[k] = V[i], sl[k] = left[i], sr[k] = right[i];
  }
  T_ASSERT(fclose(f) == 0, "cannot write %s", path);
  /* the same as HDF5 */
  snprintf(path, sizeof path, "%s/bar.h5", work);
  hid_t h = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hsize_t d2[2] = {(hsize_t)n, 2}, d1[1] = {(hsize_t)n};
  hid_t s2 = H5Screate_simple(2, d2, NULL), s1 = H5Screate_simple(1, d1, NULL);
  hid_t ds = H5Dcreate2(h, "X", H5T_IEEE_F64LE, s2, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  T_ASSERT(H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, xy) >= 0, "write X");
  H5Dclose(ds);
  ds = H5Dcreate2(h, "volume", H5T_IEEE_F64LE, s1, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  T_ASSERT(H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, vol) >= 0, "write V");
  H5Dclose(ds);
  hid_t gs = H5Gcreate2(h, "sets", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  ds = H5Dcreate2(gs, "left", H5T_STD_U8LE, s1, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  T_ASSERT(H5Dwrite(ds, H5T_NATIVE_UINT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, sl) >= 0, "write left");
  H5Dclose(ds);
  ds = H5Dcreate2(gs, "right", H5T_STD_U8LE, s1, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  T_ASSERT(H5Dwrite(ds, H5T_NATIVE_UINT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, sr) >= 0, "write right");
  H5Dclose(ds);
  H5Gclose(gs);
  H5Sclose(s1);
  H5Sclose(s2);
  H5Fclose(h);
  free(xy);
  free(vol);
  free(sl);
  free(sr);
  free(at);
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&scene);
}

static const char cloud_scene[] =
    "name: bar\ndimension: 2\n"
    "geometry:\n  points: %s\n  spacing: 1.0e-3\n  horizon_factor: 3.015\n%s"
    "material: {density: 8000, bulk_modulus: 1.0e9}\n"
    "model: {kind: pmb, critical_stretch: 0.002}\n%s"
    "boundary_conditions:\n"
    "  - {set: left, type: displacement, x: 0, y: 0}\n"
    "  - {set: right, type: velocity, x: 0.5, function: ramp, duration: 1.0e-5}\n"
    "solver: {steps: 400}\n"
    "output: {field_interval: 100, fields: [u, v], history_interval: 10, reactions: [left, "
    "right]}\n";

/* A scene over the cloud file `csv` (extra geometry lines, extra top-level lines) must fail to
 * load with a message holding every one of want[] (NULL-terminated). */
static void bad(pdk_ctx *ctx, const char *label, const char *csv, const char *geom_extra,
                const char *top_extra, const char *const *want) {
  char text[4096], scene_path[1024];
  if (csv) write_file("bad.csv", csv);
  snprintf(text, sizeof text, cloud_scene, "bad.csv", geom_extra, top_extra);
  write_file("bad.yaml", text);
  snprintf(scene_path, sizeof scene_path, "%s/bad.yaml", work);
  pdk_scene *scene = NULL;
  const int err = pdk_scene_load(ctx, scene_path, NULL, 0, &scene);
  T_ASSERT(err != 0 && scene == NULL, "%s: the scene loaded", label);
  const char *msg = pdk_ctx_error_message(ctx);
  for (int k = 0; want[k]; ++k)
    T_ASSERT(strstr(msg, want[k]) != NULL, "%s: the message lacks '%s': %s", label, want[k], msg);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  work_init("t233_scene_points");
  char lattice_scene[1024], cloud_path[1024], text[4096];
  snprintf(lattice_scene, sizeof lattice_scene, "%s/tests/scenes/t092_bar.yaml",
           getenv("PDK_SOURCE_DIR"));

  /* 1. the lattice and its cloud */
  write_cloud(ctx, lattice_scene);
  snprintf(text, sizeof text, cloud_scene, "bar.csv", "", "");
  write_file("cloud.yaml", text);
  snprintf(cloud_path, sizeof cloud_path, "%s/cloud.yaml", work);
  char dir_l[1024], dir_c[1024];
  snprintf(dir_l, sizeof dir_l, "%s/lattice", work);
  snprintf(dir_c, sizeof dir_c, "%s/cloud", work);
  run_scene(ctx, lattice_scene, dir_l);
  run_scene(ctx, cloud_path, dir_c);
  {
    char a[1200], b[1200], why[2048] = "";
    snprintf(a, sizeof a, "%s/bar_history.csv", dir_l);
    snprintf(b, sizeof b, "%s/bar_history.csv", dir_c);
    char *ta = slurp(a), *tb = slurp(b);
    T_ASSERT(!strcmp(ta, tb), "the cloud's history CSV differs from the lattice's");
    free(ta);
    free(tb);
    snprintf(a, sizeof a, "%s/bar.h5", dir_l);
    snprintf(b, sizeof b, "%s/bar.h5", dir_c);
    hid_t fa = H5Fopen(a, H5F_ACC_RDONLY, H5P_DEFAULT),
          fb = H5Fopen(b, H5F_ACC_RDONLY, H5P_DEFAULT);
    T_ASSERT(fa >= 0 && fb >= 0, "cannot open %s or %s", a, b);
    T_ASSERT(h5s_same_output_data(fa, fb, why, sizeof why),
             "the cloud's output differs from the lattice's: %s", why);
    H5Fclose(fa);
    H5Fclose(fb);
  }
  /* the cloud as HDF5: the same run, bit for bit */
  {
    snprintf(text, sizeof text, cloud_scene, "bar.h5", "", "");
    write_file("cloud_h5.yaml", text);
    char path[1024], dir_h[1024], a[1200], b[1200];
    snprintf(path, sizeof path, "%s/cloud_h5.yaml", work);
    snprintf(dir_h, sizeof dir_h, "%s/cloud_h5", work);
    run_scene(ctx, path, dir_h);
    snprintf(a, sizeof a, "%s/bar_history.csv", dir_l);
    snprintf(b, sizeof b, "%s/bar_history.csv", dir_h);
    char *ta = slurp(a), *tb = slurp(b);
    T_ASSERT(!strcmp(ta, tb), "the HDF5 cloud's history CSV differs from the lattice's");
    free(ta);
    free(tb);
  }
  /* the lattice run's output file as a cloud: its /static group */
  {
    char rel[1200], path[1024];
    snprintf(rel, sizeof rel, "lattice/bar.h5");
    snprintf(text, sizeof text, cloud_scene, rel, "", "");
    write_file("from_output.yaml", text);
    snprintf(path, sizeof path, "%s/from_output.yaml", work);
    pdk_scene *scene = NULL;
    pdk_sim *sim = NULL;
    T_OK(ctx, pdk_scene_load(ctx, path, NULL, 0, &scene));
    T_OK(ctx, pdk_sim_create(ctx, scene, &sim));
    pdk_particles *p = pdk_sim_particles(sim);
    T_ASSERT(pdk_particles_count(p) == 240 && pdk_particles_field_exists(p, "set:left") &&
                 pdk_particles_field_exists(p, "set:right"),
             "the output file as a cloud: %d particles (240), sets left and right",
             (int)pdk_particles_count(p));
    pdk_sim_destroy(&sim);
    pdk_scene_destroy(&scene);
  }

  /* 2. area x thickness */
  {
    write_file("area.csv", "x,y,area,set:left,set:right\n0,0,2e-6,1,0\n1e-3,0,2e-6,0,1\n"
                           "0,1e-3,2e-6,1,0\n1e-3,1e-3,2e-6,0,1\n");
    snprintf(text, sizeof text, cloud_scene, "area.csv", "  thickness: 0.5\n", "");
    write_file("area.yaml", text);
    char path[1024];
    snprintf(path, sizeof path, "%s/area.yaml", work);
    pdk_scene *scene = NULL;
    pdk_sim *sim = NULL;
    T_OK(ctx, pdk_scene_load(ctx, path, NULL, 0, &scene));
    T_OK(ctx, pdk_sim_create(ctx, scene, &sim));
    const double *V = pdk_particles_volume(pdk_sim_particles(sim));
    for (pdk_index i = 0; i < 4; ++i)
      T_ASSERT(V[i] == 2e-6 * 0.5, "volume %g, want area x thickness = 1e-6", V[i]);
    pdk_sim_destroy(&sim);
    pdk_scene_destroy(&scene);
  }

  /* 3. bad clouds */
  const char *const k1[] = {"geometry.points", "bad.csv", "no header line", NULL};
  bad(ctx, "empty file", "", "", "", k1);
  const char *const k2[] = {"bad.csv:1", "unknown column 'w'", "volume or area", NULL};
  bad(ctx, "unknown column", "x,y,w\n0,0,1\n", "", "", k2);
  const char *const k3[] = {"bad.csv:1", "one of volume", NULL};
  bad(ctx, "no volume", "x,y\n0,0\n", "", "", k3);
  const char *const k4[] = {"bad.csv:3", "column 2 is '0.0.1', not a finite number", NULL};
  bad(ctx, "not a number", "x,y,volume,set:left,set:right\n0,0,1,1,0\n1,0.0.1,1,0,1\n", "", "", k4);
  const char *const k5[] = {"bad.csv:2", "3 values, the header (line 1) names 5 columns", NULL};
  bad(ctx, "short row", "x,y,volume,set:left,set:right\n0,0,1\n", "", "", k5);
  const char *const k6[] = {"bad.csv:2", "more values than the 5 columns", NULL};
  bad(ctx, "long row", "x,y,volume,set:left,set:right\n0,0,1,1,0,7\n", "", "", k6);
  const char *const k7[] = {"bad.csv:2", "the volume is -1", "must be > 0", NULL};
  bad(ctx, "negative volume", "x,y,volume,set:left,set:right\n0,0,-1,1,0\n", "", "", k7);
  const char *const k8[] = {"bad.csv:2", "set:left is 2", "0 or 1", NULL};
  bad(ctx, "set value 2", "x,y,volume,set:left,set:right\n0,0,1,2,0\n", "", "", k8);
  const char *const k9[] = {"geometry.points", "set:right selects no particle", NULL};
  bad(ctx, "empty set", "x,y,volume,set:left,set:right\n0,0,1,1,0\n", "", "", k9);
  const char *const k10[] = {"geometry.points", "set:left", "sets[0] defines too", NULL};
  bad(ctx, "set twice", "x,y,volume,set:left,set:right\n0,0,1,1,0\n1,0,1,0,1\n", "",
      "sets:\n  - {name: left, box: {lo: [-1, -1], hi: [0.5, 1]}}\n", k10);
  const char *const k11[] = {"geometry.box", "remove one of them", NULL};
  bad(ctx, "box and points", "x,y,volume,set:left,set:right\n0,0,1,1,0\n1,0,1,0,1\n",
      "  box: {lo: [0, 0], hi: [1, 1]}\n", "", k11);
  {
    /* an HDF5 cloud without volumes */
    char path[1024];
    snprintf(path, sizeof path, "%s/novol.h5", work);
    hid_t h = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    hsize_t d2[2] = {2, 2};
    const double xy[4] = {0, 0, 1, 0};
    hid_t s2 = H5Screate_simple(2, d2, NULL);
    hid_t ds = H5Dcreate2(h, "X", H5T_IEEE_F64LE, s2, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, xy);
    H5Dclose(ds);
    H5Sclose(s2);
    H5Fclose(h);
    snprintf(text, sizeof text, cloud_scene, "novol.h5", "", "");
    write_file("novol.yaml", text);
    snprintf(path, sizeof path, "%s/novol.yaml", work);
    pdk_scene *scene = NULL;
    T_ASSERT(pdk_scene_load(ctx, path, NULL, 0, &scene) != 0,
             "an HDF5 cloud without volumes loads");
    const char *msg = pdk_ctx_error_message(ctx);
    T_ASSERT(strstr(msg, "geometry.points") && strstr(msg, "novol.h5") &&
                 strstr(msg, "needs a dataset /volume of shape [2]"),
             "no volumes: %s", msg);
  }
  const char *const k12[] = {"geometry.points", "cannot open the point cloud", "nowhere.csv", NULL};
  {
    snprintf(text, sizeof text, cloud_scene, "nowhere.csv", "", "");
    write_file("missing.yaml", text);
    char path[1024];
    snprintf(path, sizeof path, "%s/missing.yaml", work);
    pdk_scene *scene = NULL;
    T_ASSERT(pdk_scene_load(ctx, path, NULL, 0, &scene) != 0, "a missing cloud file loads");
    for (int k = 0; k12[k]; ++k)
      T_ASSERT(strstr(pdk_ctx_error_message(ctx), k12[k]), "missing file: no '%s' in: %s", k12[k],
               pdk_ctx_error_message(ctx));
  }
  {
    write_file("nobody.yaml", "dimension: 2\ngeometry: {spacing: 1.0e-3}\n"
                              "material: {density: 1, bulk_modulus: 1}\nsolver: {steps: 1}\n");
    char path[1024];
    snprintf(path, sizeof path, "%s/nobody.yaml", work);
    pdk_scene *scene = NULL;
    T_ASSERT(pdk_scene_load(ctx, path, NULL, 0, &scene) != 0, "a scene without a body loads");
    T_ASSERT(strstr(pdk_ctx_error_message(ctx), "give geometry.box") != NULL, "no body: %s",
             pdk_ctx_error_message(ctx));
  }
  pdk_ctx_destroy(&ctx);
  return 0;
}
