/* Run output: HDF5 + XDMF + CSV (+ PNG with gnuplot) from a small 2-D PMB run.
 *   - every DataItem of the .xmf names a dataset that exists in the .h5 with the declared
 *     dimensions, number type and precision; the .xmf is well-formed XML (xmllint, when present)
 *     and ParaView's XDMF readers load every step (pvpython, when present);
 *   - field values and history columns round-trip bitwise, deflated or not; vectors are [n][3]
 *     with z = 0;
 *   - the geometry is the step's "x" when written, else /static/X; a 2-D tensor is [n][9] with
 *     zeros in the z row and column, an int32 field of 5 components [n][5] (Matrix);
 *   - the CSV has the header with units and one row per history record;
 *   - the PNG exists iff gnuplot is on the PATH (and pdk_output_will_plot says so); a gnuplot
 *     that fails is reported, naming the script, and leaves the data files complete, no PNG;
 *   - <name>_fields.csv holds the last field output and <name>_fields.png draws it (3-D: the
 *     layer nearest the mid-plane);
 *   - close(.., 0) leaves no file; a killed process leaves only .part files;
 *   - bad field names are errors that name the field.
 * Test files go to ./t070_out (the build's tests/ directory under ctest).
 * labels: unit */
#define _DEFAULT_SOURCE /* fork, setenv, opendir */
#include <dirent.h>
#include <hdf5.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "pdk/output.h"
#include "test_util.h"

#define DIR_OUT "t070_out"
#define NUM_OUT 3
#define NUM_HIST 6

/* A 2-D PMB bar [0, 20 dx] x [0, 5 dx], dx = 1 mm, sets "left" and "right" (three columns each). */
static void build(pdk_ctx *ctx, pdk_particles **p, pdk_families **fam, pdk_model **m) {
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.spacing = 1e-3;
  lo.hi[0] = 20e-3;
  lo.hi[1] = 5e-3;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, p));
  T_OK(ctx, pdk_particles_reorder_morton(*p, 3.015e-3, NULL));
  double a[3] = {-1, -1, -1}, b[3] = {2.5e-3, 1, 1}, c[3] = {17.5e-3, -1, -1}, d[3] = {1, 1, 1};
  pdk_region left = pdk_region_box(a, b), right = pdk_region_box(c, d);
  T_OK(ctx, pdk_particles_set_define(*p, "left", &left, NULL));
  T_OK(ctx, pdk_particles_set_define(*p, "right", &right, NULL));
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = 3.015e-3;
  T_OK(ctx, pdk_families_build(*p, &fo, fam));
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = PDK_MODEL_PMB;
  mo.bulk_modulus = 1e9;
  mo.density = 8000;
  T_OK(ctx, pdk_model_create(*p, *fam, &mo, m));
}

static int on_path(const char *prog) {
  const char *path = getenv("PATH");
  char buf[4096];
  while (path && *path) {
    const char *end = strchr(path, ':');
    size_t len = end ? (size_t)(end - path) : strlen(path);
    snprintf(buf, sizeof buf, "%.*s/%s", (int)len, path, prog);
    if (len && access(buf, X_OK) == 0) return 1;
    path = end ? end + 1 : NULL;
  }
  return 0;
}

static int exists(const char *name) {
  char path[512];
  struct stat sb;
  snprintf(path, sizeof path, "%s/%s", DIR_OUT, name);
  return stat(path, &sb) == 0;
}

/* Number of files in DIR_OUT whose name starts with prefix. */
static int count_files(const char *prefix) {
  DIR *d = opendir(DIR_OUT);
  int count = 0;
  if (!d) return 0;
  for (struct dirent *ent; (ent = readdir(d));)
    if (!strncmp(ent->d_name, prefix, strlen(prefix))) count++;
  closedir(d);
  return count;
}

static void clean_dir(void) {
  DIR *d = opendir(DIR_OUT);
  if (!d) return;
  char path[512];
  for (struct dirent *ent; (ent = readdir(d));) {
    if (ent->d_name[0] == '.') continue;
    snprintf(path, sizeof path, "%s/%s", DIR_OUT, ent->d_name);
    unlink(path);
  }
  closedir(d);
}

static char *read_text(const char *name) {
  char path[512];
  snprintf(path, sizeof path, "%s/%s", DIR_OUT, name);
  FILE *f = fopen(path, "rb");
  T_ASSERT(f, "cannot open %s", path);
  fseek(f, 0, SEEK_END);
  long len = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *s = malloc((size_t)len + 1);
  T_ASSERT(fread(s, 1, (size_t)len, f) == (size_t)len, "short read of %s", path);
  s[len] = '\0';
  fclose(f);
  return s;
}

/* Value of attribute `key` ("key=\"...\"") in the tag starting at tag, into out. */
static int tag_attr(const char *tag, const char *key, char *out, size_t cap) {
  const char *end = strchr(tag, '>');
  char pat[64];
  snprintf(pat, sizeof pat, " %s=\"", key);
  const char *q = strstr(tag, pat);
  if (!q || q > end) return 0;
  q += strlen(pat);
  const char *close = strchr(q, '"');
  snprintf(out, cap, "%.*s", (int)(close - q), q);
  return 1;
}

/* Checks one HDF DataItem of the XDMF against the HDF5 file; returns its dataset path in path. */
static void check_data_item(hid_t file, const char *h5name, const char *item, char *path,
                            size_t cap) {
  char dims_text[64], number_type[32] = "Float", precision[8] = "4", format[16];
  T_ASSERT(tag_attr(item, "Dimensions", dims_text, sizeof dims_text),
           "DataItem without Dimensions");
  T_ASSERT(tag_attr(item, "Format", format, sizeof format) && !strcmp(format, "HDF"),
           "DataItem not HDF");
  tag_attr(item, "NumberType", number_type, sizeof number_type);
  tag_attr(item, "Precision", precision, sizeof precision);
  const char *body = strchr(item, '>') + 1, *end = strstr(body, "</DataItem>");
  char ref[512];
  snprintf(ref, sizeof ref, "%.*s", (int)(end - body), body);
  char *colon = strchr(ref, ':');
  T_ASSERT(colon, "DataItem body '%s' has no file:path", ref);
  *colon = '\0';
  T_ASSERT(!strcmp(ref, h5name), "DataItem refers to '%s', expected the relative '%s'", ref,
           h5name);
  snprintf(path, cap, "%s", colon + 1);
  hsize_t want[2] = {0, 0};
  int rank = sscanf(dims_text, "%llu %llu", (unsigned long long *)&want[0],
                    (unsigned long long *)&want[1]);
  T_ASSERT(rank >= 1, "bad Dimensions '%s'", dims_text);
  T_ASSERT(H5Lexists(file, path, H5P_DEFAULT) > 0, "the .xmf names %s, which is not in run.h5",
           path);
  hid_t d = H5Dopen2(file, path, H5P_DEFAULT), s = H5Dget_space(d), t = H5Dget_type(d);
  hsize_t got[2] = {0, 0};
  T_ASSERT(H5Sget_simple_extent_ndims(s) == rank, "%s: rank %d, the .xmf says %d", path,
           H5Sget_simple_extent_ndims(s), rank);
  H5Sget_simple_extent_dims(s, got, NULL);
  T_ASSERT(got[0] == want[0] && got[1] == want[1], "%s: dims %llu %llu, the .xmf says %s", path,
           (unsigned long long)got[0], (unsigned long long)got[1], dims_text);
  T_ASSERT((size_t)atoi(precision) == H5Tget_size(t), "%s: %zu-byte values, the .xmf says %s", path,
           H5Tget_size(t), precision);
  H5T_class_t cls = H5Tget_class(t);
  if (!strcmp(number_type, "Float"))
    T_ASSERT(cls == H5T_FLOAT, "%s: not a float dataset", path);
  else if (!strcmp(number_type, "Int"))
    T_ASSERT(cls == H5T_INTEGER && H5Tget_sign(t) == H5T_SGN_2, "%s: not signed", path);
  else if (!strcmp(number_type, "UChar"))
    T_ASSERT(cls == H5T_INTEGER && H5Tget_sign(t) == H5T_SGN_NONE, "%s: not unsigned", path);
  else
    T_FAIL("%s: unexpected NumberType %s", path, number_type);
  H5Tclose(t);
  H5Sclose(s);
  H5Dclose(d);
}

/* Reads a whole f64 dataset. */
static double *read_f64(hid_t file, const char *path, size_t count) {
  double *buf = malloc(count * sizeof *buf);
  hid_t d = H5Dopen2(file, path, H5P_DEFAULT);
  T_ASSERT(d >= 0, "no dataset %s", path);
  hid_t s = H5Dget_space(d);
  T_ASSERT((size_t)H5Sget_simple_extent_npoints(s) == count, "%s: %lld values, expected %zu", path,
           (long long)H5Sget_simple_extent_npoints(s), count);
  T_ASSERT(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0, "reading %s",
           path);
  H5Sclose(s);
  H5Dclose(d);
  return buf;
}

/* The "unit" attribute of a dataset, or "" when it has none. */
static void read_unit(hid_t file, const char *path, char *out, size_t cap) {
  out[0] = '\0';
  hid_t d = H5Dopen2(file, path, H5P_DEFAULT);
  T_ASSERT(d >= 0, "cannot open %s", path);
  if (H5Aexists(d, "unit") > 0) {
    hid_t a = H5Aopen(d, "unit", H5P_DEFAULT), t = H5Aget_type(a);
    char *v = NULL;
    if (H5Tis_variable_str(t) > 0) {
      H5Aread(a, t, &v);
      snprintf(out, cap, "%s", v ? v : "");
      H5free_memory(v);
    } else {
      size_t len = H5Tget_size(t);
      char *buf = calloc(len + 1, 1);
      H5Aread(a, t, buf);
      snprintf(out, cap, "%s", buf);
      free(buf);
    }
    H5Tclose(t);
    H5Aclose(a);
  }
  H5Dclose(d);
}

static void check_vector(hid_t file, const char *path, const double *saved, pdk_index n) {
  double *v = read_f64(file, path, (size_t)n * 3);
  for (pdk_index i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      double want = c < 2 ? saved[c * n + i] : 0.0;
      T_ASSERT(!memcmp(&v[3 * i + c], &want, sizeof want), "%s[%d][%d] = %.17g, written %.17g",
               path, (int)i, c, v[3 * i + c], want);
    }
  free(v);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  pdk_particles *p;
  pdk_families *fam;
  pdk_model *m;
  pdk_explicit *e;
  build(ctx, &p, &fam, &m);
  const pdk_index n = pdk_particles_count(p);
  pdk_bc bcs[2] = {{0}, {0}};
  bcs[0].kind = PDK_BC_DISPLACEMENT;
  bcs[0].set = "set:left";
  bcs[0].components = 3;
  bcs[1].kind = PDK_BC_DISPLACEMENT;
  bcs[1].set = "set:right";
  bcs[1].components = 1;
  bcs[1].value[0] = (pdk_tfun){PDK_TFUN_RAMP, 1e-6, 1e-5};
  const char *rsets[2] = {"set:left", "set:right"};
  pdk_explicit_opts eo = pdk_explicit_opts_default();
  eo.bcs = bcs;
  eo.num_bcs = 2;
  eo.reaction_sets = rsets;
  eo.num_reaction_sets = 2;
  T_OK(ctx, pdk_explicit_create(m, &eo, &e));
  mkdir(DIR_OUT, 0777);
  clean_dir();

  /* 1. A complete output. Reaction set names with and without the "set:" prefix. */
  const char *rnames[2] = {"set:left", "right"};
  pdk_output_opts oo = pdk_output_opts_default();
  oo.dir = DIR_OUT;
  oo.name = "run";
  oo.scene_text = "name: t070\n";
  oo.reaction_sets = rnames;
  oo.num_reaction_sets = 2;
  oo.units = "SI";
  pdk_output *o;
  T_OK(ctx, pdk_output_open(ctx, &oo, p, &o));
  T_ASSERT(pdk_output_will_plot(o) == on_path("gnuplot"), "will_plot %d, gnuplot on PATH %d",
           pdk_output_will_plot(o), on_path("gnuplot"));
  /* Other shapes: a 2-D tensor "T" (4 components, [a][c] at 2a + c) and an int32 "odd" of 5. */
  T_OK(ctx, pdk_particles_field_add(p, "T", PDK_F64, 4));
  T_OK(ctx, pdk_particles_field_add(p, "odd", PDK_I32, 5));
  for (pdk_index i = 0; i < n; ++i) {
    for (int t = 0; t < 4; ++t)
      ((double *)pdk_particles_field_data(p, "T", t))[i] = 10.0 * i + t + 0.5;
    for (int t = 0; t < 5; ++t)
      ((int32_t *)pdk_particles_field_data(p, "odd", t))[i] = (int32_t)(7 * i - t);
  }
  const char *fields[NUM_OUT][6] = {
      {"x", "v", "f"}, {"x", "v", "f", "set:left", "T", "odd"}, {"v", "f"}};
  const int num_fields[NUM_OUT] = {3, 6, 2};
  double *saved[NUM_OUT][3]; /* x, v, f of each output, [2][n] */
  pdk_history hist[NUM_HIST];
  long steps[NUM_OUT];
  double times[NUM_OUT];
  for (int k = 0; k < NUM_OUT; ++k) {
    T_OK(ctx, pdk_explicit_run(e, 10, &hist[2 * k]));
    T_OK(ctx, pdk_output_write_history(o, &hist[2 * k]));
    T_OK(ctx, pdk_explicit_run(e, 10, &hist[2 * k + 1]));
    T_OK(ctx, pdk_output_write_history(o, &hist[2 * k + 1]));
    steps[k] = pdk_explicit_step(e);
    times[k] = pdk_explicit_time(e);
    T_OK(ctx, pdk_output_write_fields(o, p, steps[k], times[k], fields[k], num_fields[k]));
    const char *names[3] = {"x", "v", "f"};
    for (int q = 0; q < 3; ++q) {
      saved[k][q] = malloc(2 * (size_t)n * sizeof(double));
      for (int c = 0; c < 2; ++c)
        memcpy(saved[k][q] + c * n, pdk_particles_field_data(p, names[q], c),
               (size_t)n * sizeof(double));
    }
  }
  T_ASSERT(hist[NUM_HIST - 1].reaction[1][0] != 0.0, "the pulled end carries a load");
  /* Bad names: not a field, listed twice. Neither spoils the output. */
  const char *bad1[1] = {"nonesuch"}, *bad2[2] = {"v", "v"};
  T_FAILS(ctx, pdk_output_write_fields(o, p, 99, 1.0, bad1, 1), PDK_ERR_NOT_FOUND, "nonesuch");
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "volume"), "the message lists the fields: %s",
           pdk_ctx_error_message(ctx));
  T_FAILS(ctx, pdk_output_write_fields(o, p, 99, 1.0, bad2, 2), PDK_ERR_ARG, "twice");
  T_ASSERT(pdk_output_num_field_steps(o) == NUM_OUT && pdk_output_num_history_rows(o) == NUM_HIST,
           "counts %d %ld", pdk_output_num_field_steps(o), pdk_output_num_history_rows(o));
  int will_plot = pdk_output_will_plot(o);
  T_ASSERT(exists("run.h5.part") && exists("run.xmf.part") && !exists("run.h5") &&
               !exists("run.xmf"),
           "before close only .part files exist");
  T_OK(ctx, pdk_output_close(&o, 1));
  T_ASSERT(!o, "close sets the handle to NULL");
  T_ASSERT(exists("run.h5") && exists("run.xmf") && exists("run_history.csv"), "final files exist");
  /* .h5, .xmf, the two CSVs, the history plot (the last output has no scalar: no field plot) */
  T_ASSERT(count_files("run") == 4 + 2 * will_plot && !exists("run.h5.part") &&
               exists("run_fields.csv") && !exists("run_fields.png"),
           "no .part file is left (%d files)", count_files("run"));
  T_ASSERT(exists("run_history.png") == will_plot, "PNG exists iff gnuplot ran (%d)", will_plot);
  if (will_plot) {
    char *png = read_text("run_history.png");
    T_ASSERT(!memcmp(png, "\x89PNG", 4), "run_history.png is a PNG");
    free(png);
    /* time axes in the unit that fits the run's last time (SI seconds: us below 1 ms, ms below
     * 1 s), the column scaled to match; legends below the panels */
    const double tmax = times[NUM_OUT - 1];
    const char *tu = tmax < 1e-3 ? "us" : tmax < 1.0 ? "ms" : "s";
    const double ts = tmax < 1e-3 ? 1e6 : tmax < 1.0 ? 1e3 : 1.0;
    char *gp = read_text("run_history.gp"), want[64];
    snprintf(want, sizeof want, "set xlabel 'time [%s]'", tu);
    T_ASSERT(strstr(gp, want) != NULL, "the time axis is in %s (last time %g s):\n%s", tu, tmax,
             gp);
    const char *tl = strstr(gp, "tscale = ");
    T_ASSERT(tl && strtod(tl + strlen("tscale = "), NULL) == ts && strstr(gp, "($2*tscale)") &&
                 strstr(gp, "set key below"),
             "times scaled by %g, legends below:\n%s", ts, gp);
    free(gp);
  }

  /* 2. The XDMF against the HDF5 file. */
  hid_t file = H5Fopen(DIR_OUT "/run.h5", H5F_ACC_RDONLY, H5P_DEFAULT);
  T_ASSERT(file >= 0, "cannot open run.h5");
  char *xmf = read_text("run.xmf");
  int num_items = 0, num_grids = 0;
  char path[512];
  for (const char *q = xmf; (q = strstr(q, "<DataItem")); ++q, ++num_items)
    check_data_item(file, "run.h5", q, path, sizeof path);
  for (const char *q = xmf; (q = strstr(q, "<Grid Name=\"step_")); ++q, ++num_grids) {
    char want[64], value[64];
    const char *t = strstr(q, "<Time ");
    T_ASSERT(t && tag_attr(t, "Value", value, sizeof value) &&
                 strtod(value, NULL) == times[num_grids],
             "grid %d: time %s, written %.17g", num_grids, value, times[num_grids]);
    const char *g = strstr(q, "<Geometry");
    T_ASSERT(g && strstr(g, "GeometryType=\"XYZ\""), "grid %d geometry is XYZ", num_grids);
    check_data_item(file, "run.h5", strstr(g, "<DataItem"), path, sizeof path);
    if (num_grids < 2)
      snprintf(want, sizeof want, "/steps/%06d/x", num_grids);
    else
      snprintf(want, sizeof want, "/static/X");
    T_ASSERT(!strcmp(path, want), "grid %d geometry %s, expected %s", num_grids, path, want);
  }
  T_ASSERT(num_grids == NUM_OUT, "%d grids in the .xmf, expected %d", num_grids, NUM_OUT);
  /* per grid: connectivity, geometry, id, volume, 2 sets (less set:left where the output writes
   * it as a field), and the fields */
  T_ASSERT(num_items == 3 * 6 - 1 + 3 + 6 + 2, "%d DataItems in the .xmf", num_items);
  T_ASSERT(strstr(xmf, "<Attribute Name=\"T\" AttributeType=\"Tensor\"") &&
               strstr(xmf, "<Attribute Name=\"odd\" AttributeType=\"Matrix\""),
           "a 2-D tensor is a Tensor, 5 components a Matrix");
  for (const char *q = xmf; (q = strstr(q, "<Grid Name=\"step_")); ++q) {
    const char *end = strstr(q, "</Grid>");
    int count = 0;
    for (const char *a = q; (a = strstr(a, "Name=\"set:left\"")) && a < end; ++a)
      count++;
    T_ASSERT(count == 1, "a grid has %d attributes named set:left", count);
  }
  T_ASSERT(strstr(xmf, "CollectionType=\"Temporal\"") &&
               strstr(xmf, "TopologyType=\"Polyvertex\"") &&
               strstr(xmf, "AttributeType=\"Vector\"") && strstr(xmf, "Center=\"Node\""),
           "temporal collection of polyvertex grids with node vectors");
  free(xmf);
  if (on_path("xmllint")) {
    T_ASSERT(system("xmllint --noout " DIR_OUT "/run.xmf") == 0, "xmllint rejects run.xmf");
  } else {
    T_INFO("t070: xmllint not on the PATH; XML well-formedness not checked\n");
  }

  /* 2b. ParaView itself, when pvpython is on the PATH: its XDMF 2 reader and its Xdmf3 reader load
   * every step with n points, n cells, the fields, and the geometry of the first step is "x". */
  if (on_path("pvpython")) {
    FILE *py = fopen(DIR_OUT "/pv_check.py", "w");
    T_ASSERT(py, "cannot write pv_check.py");
    fprintf(
        py,
        "import sys\n"
        "from paraview.simple import *\n"
        "from vtk.numpy_interface import dataset_adapter as dsa\n"
        "import numpy as np\n"
        "fn, n, steps = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])\n"
        "for make in (lambda: XDMFReader(FileNames=[fn]), lambda: Xdmf3ReaderS(FileName=[fn])):\n"
        "    r = make()\n"
        "    r.UpdatePipelineInformation()\n"
        "    times = list(r.TimestepValues)\n"
        "    assert len(times) == steps, ('times', times)\n"
        "    for k, t in enumerate(times):\n"
        "        r.UpdatePipeline(t)\n"
        "        d = servermanager.Fetch(r)\n"
        "        if d.IsA('vtkMultiBlockDataSet'): d = d.GetBlock(0)\n"
        "        assert d.GetNumberOfPoints() == n and d.GetNumberOfCells() == n, (k, "
        "d.GetNumberOfPoints(), d.GetNumberOfCells())\n"
        "        w = dsa.WrapDataObject(d)\n"
        "        for name in ('id', 'volume', 'set:right', 'v', 'f'):\n"
        "            assert name in w.PointData.keys(), (k, name, w.PointData.keys())\n"
        "        if k == 0:\n"
        "            assert np.abs(np.array(w.Points) - np.array(w.PointData['x'])).max() == 0\n"
        "print('ok')\n");
    fclose(py);
    char abs_dir[4096], cmd[4 * 4096 + 256];
    T_ASSERT(realpath(DIR_OUT, abs_dir), "realpath");
    snprintf(cmd, sizeof cmd, "pvpython %s/pv_check.py %s/run.xmf %d %d > %s/pv_check.log 2>&1",
             abs_dir, abs_dir, (int)n, NUM_OUT, abs_dir);
    if (system(cmd) != 0) {
      char *log = read_text("pv_check.log");
      T_FAIL("ParaView could not read run.xmf:\n%s", log);
    }
  } else {
    T_INFO("t070: pvpython not on the PATH; reading the .xmf with ParaView not checked\n");
  }

  /* 3. Values round-trip bitwise. */
  for (int k = 0; k < NUM_OUT; ++k) {
    const char *names[3] = {"x", "v", "f"};
    for (int q = 0; q < 3; ++q) {
      if (k == 2 && q == 0) continue; /* x not written in the last output */
      snprintf(path, sizeof path, "/steps/%06d/%s", k, names[q]);
      check_vector(file, path, saved[k][q], n);
    }
    snprintf(path, sizeof path, "/steps/%06d", k);
    hid_t g = H5Gopen2(file, path, H5P_DEFAULT);
    hid_t a = H5Aopen(g, "step", H5P_DEFAULT);
    long long s;
    H5Aread(a, H5T_NATIVE_LLONG, &s);
    H5Aclose(a);
    H5Gclose(g);
    T_ASSERT(s == steps[k], "output %d: step %lld, written %ld", k, s, steps[k]);
  }
  T_ASSERT(H5Lexists(file, "/steps/000002/x", H5P_DEFAULT) == 0,
           "only the fields asked for are written");
  {
    /* Units: every field pdk knows carries a "unit" attribute in the output's units (SI here);
     * a caller's own fields (T, odd) and the ids carry none. */
    const char *const upath[] = {"/steps/000000/x", "/steps/000000/v", "/steps/000000/f",
                                 "/static/X",       "/static/volume",  "/steps/000001/T",
                                 "/static/id"};
    const char *const uwant[] = {"m", "m/s", "N/m^3", "m", "m^3", "", ""};
    for (int q = 0; q < 7; ++q) {
      char unit[64];
      read_unit(file, upath[q], unit, sizeof unit);
      T_ASSERT(!strcmp(unit, uwant[q]), "%s: unit '%s', expected '%s'", upath[q], unit, uwant[q]);
    }
  }
  {
    double *T = read_f64(file, "/steps/000001/T", (size_t)n * 9);
    for (pdk_index i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) {
          double want = a < 2 && c < 2 ? 10.0 * i + 2 * a + c + 0.5 : 0.0;
          T_ASSERT(T[9 * i + 3 * a + c] == want, "T[%d][%d][%d] = %g, want %g", (int)i, a, c,
                   T[9 * i + 3 * a + c], want);
        }
    free(T);
    double *odd = read_f64(file, "/steps/000001/odd", (size_t)n * 5); /* converted by HDF5 */
    for (pdk_index i = 0; i < n; ++i)
      for (int t = 0; t < 5; ++t)
        T_ASSERT(odd[5 * i + t] == 7.0 * i - t, "odd[%d][%d]", (int)i, t);
    free(odd);
  }
  {
    double *X = read_f64(file, "/static/X", (size_t)n * 3),
           *vol = read_f64(file, "/static/volume", (size_t)n);
    for (pdk_index i = 0; i < n; ++i) {
      T_ASSERT(X[3 * i] == pdk_particles_X(p, 0)[i] && X[3 * i + 1] == pdk_particles_X(p, 1)[i] &&
                   X[3 * i + 2] == 0.0,
               "/static/X[%d]", (int)i);
      T_ASSERT(vol[i] == pdk_particles_volume(p)[i], "/static/volume[%d]", (int)i);
    }
    free(X);
    free(vol);
    uint8_t *left = malloc((size_t)n);
    hid_t d = H5Dopen2(file, "/static/sets/left", H5P_DEFAULT);
    T_ASSERT(d >= 0 && H5Dread(d, H5T_NATIVE_UINT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, left) >= 0,
             "/static/sets/left");
    H5Dclose(d);
    T_ASSERT(!memcmp(left, pdk_particles_field_data(p, "set:left", 0), (size_t)n),
             "set left round-trips");
    free(left);
  }
  {
    const char *cols[6] = {"step",   "time",          "kinetic",
                           "strain", "external_work", "reaction_right_x"};
    for (int c = 0; c < 6; ++c) {
      snprintf(path, sizeof path, "/history/%s", cols[c]);
      double *v = read_f64(file, path, NUM_HIST);
      for (int r = 0; r < NUM_HIST; ++r) {
        const pdk_history *h = &hist[r];
        double want = c == 0   ? (double)h->step
                      : c == 1 ? h->time
                      : c == 2 ? h->kinetic
                      : c == 3 ? h->strain
                      : c == 4 ? h->external_work
                               : h->reaction[1][0];
        T_ASSERT(!memcmp(&v[r], &want, sizeof want), "%s[%d] = %.17g, written %.17g", path, r, v[r],
                 want);
      }
      free(v);
    }
    /* The right end's mean displacement is the prescribed ramp. */
    double *u = read_f64(file, "/history/disp_right_x", NUM_HIST);
    for (int r = 0; r < NUM_HIST; ++r)
      T_NEAR(u[r], 1e-6 * fmin(hist[r].time / 1e-5, 1.0), 1e-9, 1e-18, "disp_right_x[%d]", r);
    free(u);
  }
  H5Fclose(file);

  /* 4. CSV: header with units, one row per record. */
  {
    char *csv = read_text("run_history.csv");
    const char *header =
        "step [-],time [s],kinetic [J],strain [J],external_work [J],broken [bonds],"
        "reaction_left_x [N],reaction_left_y [N],reaction_right_x [N],reaction_right_y [N],"
        "disp_left_x [m],disp_left_y [m],disp_right_x [m],disp_right_y [m],"
        "plastic_work [J],damage_work [J],breaking_work [J],dt [s],failed [particles],"
        "damage_max [-]\n";
    T_ASSERT(!strncmp(csv, header, strlen(header)), "CSV header:\n%.300s", csv);
    int rows = 0;
    for (const char *q = strchr(csv, '\n') + 1; *q; q = strchr(q, '\n') + 1, ++rows) {
      T_ASSERT(rows < NUM_HIST, "more CSV rows than records");
      T_ASSERT(atol(q) == hist[rows].step, "CSV row %d starts with step %ld", rows, atol(q));
      T_ASSERT(strtod(strchr(q, ',') + 1, NULL) == hist[rows].time, "CSV row %d time", rows);
    }
    T_ASSERT(rows == NUM_HIST, "%d CSV rows, %d records", rows, NUM_HIST);
    free(csv);
  }

  /* 5. Without gnuplot on the PATH: no PNG, no error, and will_plot says so. */
  {
    char *old_path = strdup(getenv("PATH") ? getenv("PATH") : "");
    setenv("PATH", "/nonexistent-pdk-t070", 1);
    oo.name = "nogp";
    oo.compression = 3; /* and the deflated field datasets round-trip too */
    T_OK(ctx, pdk_output_open(ctx, &oo, p, &o));
    T_ASSERT(pdk_output_will_plot(o) == 0, "no gnuplot: will_plot is 0");
    T_OK(ctx, pdk_output_write_history(o, &hist[0]));
    T_OK(ctx, pdk_output_write_fields(o, p, steps[2], times[2], fields[2], num_fields[2]));
    T_OK(ctx, pdk_output_close(&o, 1));
    oo.compression = 0;
    setenv("PATH", old_path, 1);
    free(old_path);
    T_ASSERT(exists("nogp.h5") && exists("nogp.xmf") && !exists("nogp_history.png") &&
                 !exists("nogp_history.png.part") && exists("nogp_fields.csv") &&
                 count_files("nogp") == 4,
             "without gnuplot: .h5, .xmf and the two .csv only");
    file = H5Fopen(DIR_OUT "/nogp.h5", H5F_ACC_RDONLY, H5P_DEFAULT);
    check_vector(file, "/steps/000000/v", saved[2][1], n);
    hid_t d = H5Dopen2(file, "/steps/000000/v", H5P_DEFAULT), dcpl = H5Dget_create_plist(d);
    T_ASSERT(H5Pget_nfilters(dcpl) == 2, "compression 3: shuffle and deflate on the fields");
    H5Pclose(dcpl);
    H5Dclose(d);
    H5Fclose(file);
  }

  /* 5b. Histories only: the .xmf still holds one grid, the reference configuration. */
  {
    oo.name = "histonly";
    T_OK(ctx, pdk_output_open(ctx, &oo, p, &o));
    T_OK(ctx, pdk_output_write_history(o, &hist[0]));
    T_OK(ctx, pdk_output_close(&o, 1));
    file = H5Fopen(DIR_OUT "/histonly.h5", H5F_ACC_RDONLY, H5P_DEFAULT);
    char *text = read_text("histonly.xmf");
    int items = 0, grids = 0;
    for (const char *q = text; (q = strstr(q, "<DataItem")); ++q, ++items)
      check_data_item(file, "histonly.h5", q, path, sizeof path);
    for (const char *q = text; (q = strstr(q, "<Grid Name=\"step_")); ++q)
      grids++;
    T_ASSERT(grids == 1 && items == 6, "histories only: %d grids, %d items", grids, items);
    free(text);
    H5Fclose(file);
  }

  /* 5c. The 2-D field snapshot: <name>_fields.csv holds the last field output, read back from
   * the .h5 (not the store at close, which changed since), every component named; the plot's
   * view and colour scales leave out failed particles, and its panels draw them only in
   * "failed". */
  {
    T_OK(ctx, pdk_particles_field_add(p, "s", PDK_F64, 1));
    T_OK(ctx, pdk_particles_field_add(p, "failed", PDK_U8, 1));
    double *sv = pdk_particles_field_data(p, "s", 0);
    uint8_t *fl = pdk_particles_field_data(p, "failed", 0);
    double *xx = pdk_particles_field_data(p, "x", 0), *xy = pdk_particles_field_data(p, "x", 1);
    const double *X0 = pdk_particles_X(p, 0);
    oo.name = "snap";
    T_OK(ctx, pdk_output_open(ctx, &oo, p, &o));
    T_OK(ctx, pdk_output_write_history(o, &hist[0]));
    const char *first[2] = {"s", "v"};
    for (pdk_index i = 0; i < n; ++i)
      sv[i] = -1.0;
    T_OK(ctx, pdk_output_write_fields(o, p, 10, 0.5, first, 2));
    /* the last output: particle 0 failed and flung 1 m away, s = 1 + i / 7 (the failed one's
     * 1e6, beyond every other), T and odd as set above */
    const double x0_saved[2] = {xx[0], xy[0]};
    xx[0] = 1.0;
    xy[0] = 1.0;
    for (pdk_index i = 0; i < n; ++i) {
      sv[i] = i ? 1.0 + (double)i / 7.0 : 1e6;
      fl[i] = i == 0;
    }
    const char *last[5] = {"x", "s", "T", "odd", "failed"};
    T_OK(ctx, pdk_output_write_fields(o, p, 20, 1.5, last, 5));
    double smax = 0.0;
    for (pdk_index i = 1; i < n; ++i)
      smax = fmax(smax, sv[i]);
    for (pdk_index i = 0; i < n; ++i) /* the store moves on before close */
      sv[i] = 42.0;
    T_OK(ctx, pdk_output_close(&o, 1));
    char *csv = read_text("snap_fields.csv");
    const char *header = "id,X [m],Y [m],x_x,x_y,s,T_xx,T_xy,T_yx,T_yy,odd_0,odd_1,odd_2,odd_3,"
                         "odd_4,failed\n";
    T_ASSERT(!strncmp(csv, header, strlen(header)), "fields CSV header:\n%.200s", csv);
    const int64_t *id = pdk_particles_field_data(p, "id", 0);
    const char *q = strchr(csv, '\n') + 1;
    pdk_index rows = 0;
    for (; *q; q = strchr(q, '\n') + 1, ++rows) {
      T_ASSERT(rows < n, "more fields CSV rows than particles");
      const pdk_index i = rows;
      double v[16];
      char *endp = (char *)q;
      for (int c = 0; c < 16; ++c) {
        v[c] = strtod(endp, &endp);
        T_ASSERT(*endp == (c < 15 ? ',' : '\n'), "row %d column %d: bad separator", (int)i, c);
        ++endp;
      }
      /* expected: 10 significant digits of the values at the last output */
      double want[16] = {(double)id[i],   X0[i],           pdk_particles_X(p, 1)[i],
                         i ? xx[i] : 1.0, i ? xy[i] : 1.0, i ? 1.0 + (double)i / 7.0 : 1e6};
      for (int t = 0; t < 4; ++t)
        want[6 + t] = 10.0 * i + t + 0.5; /* T[a][c] at 2a + c: xx, xy, yx, yy */
      for (int t = 0; t < 5; ++t)
        want[10 + t] = (double)(7 * i - t);
      want[15] = i == 0;
      for (int c = 0; c < 16; ++c)
        T_ASSERT(fabs(v[c] - want[c]) <= 1e-9 * fabs(want[c]), /* 10 digits */
                 "fields CSV row %d column %d: %.17g, want %.17g", (int)i, c, v[c], want[c]);
    }
    T_ASSERT(rows == n, "%d fields CSV rows for %d particles", (int)rows, (int)n);
    free(csv);
    T_ASSERT(exists("snap_fields.png") == will_plot && exists("snap_fields.gp") == will_plot,
             "field plot made iff gnuplot ran (%d)", will_plot);
    if (will_plot) {
      char *png = read_text("snap_fields.png");
      T_ASSERT(!memcmp(png, "\x89PNG", 4), "snap_fields.png is a PNG");
      free(png);
      char *gp = read_text("snap_fields.gp");
      /* the view: the body without the flung particle 0 (x up to 20 mm, margin 3%) */
      const char *xr = strstr(gp, "set xrange [");
      T_ASSERT(xr, "the field plot sets its view:\n%s", gp);
      double xlo = strtod(xr + strlen("set xrange ["), NULL);
      double xhi = strtod(strchr(xr, ':') + 1, NULL);
      T_ASSERT(xhi < 0.05 && xlo < 0.001, "view [%g, %g] leaves the failed particle out", xlo, xhi);
      /* panels s and failed (the scalars, in order); s coloured over the unfailed particles */
      const char *ts = strstr(gp, "set title 's'"),
                 *tf = strstr(gp, "set title 'failed, reference positions'");
      T_ASSERT(ts && tf && ts < tf && !strstr(gp, "set title 'odd"), "panels s, failed:\n%s", gp);
      const char *cb = strstr(ts, "set cbrange [");
      T_ASSERT(cb && cb < tf, "panel s has a colour range");
      double clo = strtod(cb + strlen("set cbrange ["), NULL);
      double chi = strtod(strchr(cb, ':') + 1, NULL);
      T_ASSERT(fabs(clo - (1.0 + 1.0 / 7.0)) < 1e-9 && fabs(chi - smax) < 1e-9 * smax,
               "panel s range [%g, %g], want [%g, %g] (particle 0 failed)", clo, chi,
               1.0 + 1.0 / 7.0, smax);
      T_ASSERT(strstr(ts, "using ($16 != 0 ? NaN : ($4)):($5):($6)"),
               "s is drawn without the failed particles:\n%s", gp);
      /* panel failed: every particle at its reference position (columns 2, 3), the failed ones
       * drawn last, in the view of the reference positions (particle 0 at its lattice point, not
       * where it was flung); then the current view again for any later panel */
      T_ASSERT(strstr(tf, "using ($16 != 0 ? NaN : $2):($3):(0)") &&
                   strstr(tf, "using ($16 == 0 ? NaN : $2):($3):(1)") &&
                   strstr(tf, "using ($16 != 0 ? NaN : $2)") <
                       strstr(tf, "using ($16 == 0 ? NaN : $2)"),
               "failed is drawn at the reference positions, the failed particles on top:\n%s", gp);
      const char *fr = strstr(tf, "set xrange [");
      T_ASSERT(fr, "panel failed sets its view");
      double rlo = strtod(fr + strlen("set xrange ["), NULL),
             rhi = strtod(strchr(fr, ':') + 1, NULL);
      double Xlo = INFINITY, Xhi = -INFINITY;
      for (pdk_index i = 0; i < n; ++i) {
        Xlo = fmin(Xlo, X0[i]);
        Xhi = fmax(Xhi, X0[i]);
      }
      T_ASSERT(rlo < Xlo && rlo > Xlo - 0.1 * (Xhi - Xlo) && rhi > Xhi &&
                   rhi < Xhi + 0.1 * (Xhi - Xlo),
               "panel failed's view [%g, %g], reference positions [%g, %g]", rlo, rhi, Xlo, Xhi);
      const char *back = strstr(fr + 1, "set xrange [");
      T_ASSERT(back && strtod(back + strlen("set xrange ["), NULL) == xlo,
               "the current view is restored after panel failed:\n%s", tf);
      free(gp);
    }
    xx[0] = x0_saved[0];
    xy[0] = x0_saved[1];
  }

  /* 5e. 3-D: the fields CSV and plot hold the layer nearest the mid-plane, Z and _z columns. */
  {
    pdk_lattice_opts lo3 = pdk_lattice_opts_default();
    lo3.type = PDK_LATTICE_CUBIC;
    lo3.spacing = 1e-3;
    lo3.hi[0] = 5e-3;
    lo3.hi[1] = 4e-3;
    lo3.hi[2] = 5e-3; /* z layers at 0.5 ... 4.5 mm: the middle one at 2.5 mm */
    pdk_particles *p3;
    T_OK(ctx, pdk_lattice_create(ctx, &lo3, &p3));
    const pdk_index n3 = pdk_particles_count(p3);
    T_OK(ctx, pdk_particles_field_add(p3, "s", PDK_F64, 1));
    T_OK(ctx, pdk_particles_field_add(p3, "u", PDK_F64, 3));
    for (pdk_index i = 0; i < n3; ++i) {
      ((double *)pdk_particles_field_data(p3, "s", 0))[i] = 0.25 * (double)i;
      for (int c = 0; c < 3; ++c)
        ((double *)pdk_particles_field_data(p3, "u", c))[i] = 1e-6 * (double)(3 * i + c);
    }
    oo.name = "cube";
    oo.num_reaction_sets = 0;
    T_OK(ctx, pdk_output_open(ctx, &oo, p3, &o));
    T_OK(ctx, pdk_output_write_history(o, &hist[0]));
    const char *f3[2] = {"s", "u"};
    T_OK(ctx, pdk_output_write_fields(o, p3, 5, 0.25, f3, 2));
    T_OK(ctx, pdk_output_close(&o, 1));
    oo.num_reaction_sets = 2;
    char *csv = read_text("cube_fields.csv");
    const char *header = "id,X [m],Y [m],Z [m],s,u_x,u_y,u_z\n";
    T_ASSERT(!strncmp(csv, header, strlen(header)), "3-D fields CSV header:\n%.200s", csv);
    const int64_t *id3 = pdk_particles_field_data(p3, "id", 0);
    int rows = 0;
    for (const char *q = strchr(csv, '\n') + 1; *q; q = strchr(q, '\n') + 1, ++rows) {
      char *endp = (char *)q;
      double v[8];
      for (int c = 0; c < 8; ++c) {
        v[c] = strtod(endp, &endp);
        ++endp;
      }
      pdk_index i = -1;
      for (pdk_index j = 0; j < n3; ++j)
        if ((double)id3[j] == v[0]) i = j;
      T_ASSERT(i >= 0, "row %d: id %g is no particle's", rows, v[0]);
      T_ASSERT(fabs(v[3] - 2.5e-3) < 1e-12 && fabs(pdk_particles_X(p3, 2)[i] - 2.5e-3) < 1e-12,
               "row %d: Z %.17g, not the middle layer", rows, v[3]);
      T_ASSERT(fabs(v[1] - pdk_particles_X(p3, 0)[i]) < 1e-12 && v[4] == 0.25 * (double)i,
               "row %d: X %g, s %g for particle %d", rows, v[1], v[4], (int)i);
      for (int c = 0; c < 3; ++c)
        T_ASSERT(fabs(v[5 + c] - 1e-6 * (double)(3 * i + c)) <= 1e-9 * 1e-6 * (3 * i + c),
                 "row %d: u_%d %.17g", rows, c, v[5 + c]);
    }
    T_ASSERT(rows == 5 * 4, "%d rows in the 3-D fields CSV, want the 20 of one layer", rows);
    free(csv);
    T_ASSERT(exists("cube_fields.png") == will_plot, "3-D field plot made iff gnuplot ran");
    if (will_plot) {
      char *gp = read_text("cube_fields.gp");
      T_ASSERT(strstr(gp, "layer Z = 0.0025 [m]") && strstr(gp, "sqrt($6**2+$7**2+$8**2)"),
               "the plot names the layer and draws |u| of 3 components:\n%s", gp);
      free(gp);
    }
    pdk_particles_destroy(&p3);
  }

  /* 5d. A gnuplot that fails: close reports it, naming the script to rerun and gnuplot's
   * message; the data files are complete, no PNG and no .part file is left. */
  {
    const char *fake = DIR_OUT "/fakebin";
    mkdir(fake, 0755);
    FILE *g = fopen(DIR_OUT "/fakebin/gnuplot", "w");
    T_ASSERT(g, "cannot write the fake gnuplot");
    fprintf(g, "#!/bin/sh\necho 'fake gnuplot: broken' >&2\nexit 3\n");
    fclose(g);
    chmod(DIR_OUT "/fakebin/gnuplot", 0755);
    char *old_path = strdup(getenv("PATH") ? getenv("PATH") : "");
    char cwd[512], bin[700];
    T_ASSERT(getcwd(cwd, sizeof cwd), "getcwd");
    snprintf(bin, sizeof bin, "%s/%s", cwd, fake);
    setenv("PATH", bin, 1);
    oo.name = "badgp";
    T_OK(ctx, pdk_output_open(ctx, &oo, p, &o));
    T_ASSERT(pdk_output_will_plot(o), "the fake gnuplot is on the PATH");
    T_OK(ctx, pdk_output_write_history(o, &hist[0]));
    const char *sf[1] = {"s"};
    T_OK(ctx, pdk_output_write_fields(o, p, steps[0], times[0], sf, 1));
    T_FAILS(ctx, pdk_output_close(&o, 1), PDK_ERR_EXTERNAL, "badgp_history.gp");
    T_ASSERT(strstr(pdk_ctx_error_message(ctx), "fake gnuplot: broken"),
             "the message carries gnuplot's: %s", pdk_ctx_error_message(ctx));
    setenv("PATH", old_path, 1);
    free(old_path);
    T_ASSERT(exists("badgp.h5") && exists("badgp.xmf") && exists("badgp_history.csv") &&
                 exists("badgp_fields.csv") && exists("badgp_history.gp") &&
                 !exists("badgp_history.png") && !exists("badgp_fields.png") &&
                 count_files("badgp") == 5,
             "a failed plot: the data files and the script, no PNG, no .part (%d files)",
             count_files("badgp"));
  }

  /* 6. close(.., 0) removes everything. */
  oo.name = "discard";
  T_OK(ctx, pdk_output_open(ctx, &oo, p, &o));
  T_OK(ctx, pdk_output_write_fields(o, p, 1, 0.0, fields[0], 3));
  T_OK(ctx, pdk_output_write_history(o, &hist[0]));
  T_OK(ctx, pdk_output_close(&o, 0));
  T_ASSERT(count_files("discard") == 0, "close(.., 0) left %d files", count_files("discard"));

  /* 7. An interrupted run: only .part files, nothing under a final name. First in-process (open,
   * write, no close), then a child process that exits without closing. */
  oo.name = "open";
  T_OK(ctx, pdk_output_open(ctx, &oo, p, &o));
  T_OK(ctx, pdk_output_write_fields(o, p, 1, 0.0, fields[0], 3));
  T_OK(ctx, pdk_output_write_history(o, &hist[0]));
  T_ASSERT(exists("open.h5.part") && exists("open.xmf.part") && exists("open_history.csv.part") &&
               count_files("open") == 3,
           "an open output has only .part files");
  T_OK(ctx, pdk_output_close(&o, 0));
  T_ASSERT(count_files("open") == 0, "close(.., 0) left %d files", count_files("open"));
  fflush(NULL);
  pid_t pid = fork();
  T_ASSERT(pid >= 0, "fork");
  if (pid == 0) {
    oo.name = "killed";
    if (pdk_output_open(ctx, &oo, p, &o)) _exit(2);
    if (pdk_output_write_fields(o, p, 1, 0.0, fields[0], 3)) _exit(3);
    if (pdk_output_write_history(o, &hist[0])) _exit(4);
    _exit(0); /* dies without closing */
  }
  int status;
  waitpid(pid, &status, 0);
  T_ASSERT(WIFEXITED(status) && WEXITSTATUS(status) == 0, "child status %d", status);
  T_ASSERT(exists("killed.h5.part") && exists("killed.xmf.part") &&
               exists("killed_history.csv.part"),
           "the killed run left its .part files");
  T_ASSERT(!exists("killed.h5") && !exists("killed.xmf") && !exists("killed_history.csv") &&
               !exists("killed_history.png") && count_files("killed") == 3,
           "the killed run left no file under a final name");

  /* 8. Bad options. */
  oo.name = "a/b";
  T_FAILS(ctx, pdk_output_open(ctx, &oo, p, &o), PDK_ERR_ARG, "a/b");
  oo.name = "units";
  oo.units = "furlongs";
  T_FAILS(ctx, pdk_output_open(ctx, &oo, p, &o), PDK_ERR_ARG, "furlongs");
  T_ASSERT(count_files("units") == 0, "a failed open leaves no file");

  for (int k = 0; k < NUM_OUT; ++k)
    for (int q = 0; q < 3; ++q)
      free(saved[k][q]);
  pdk_explicit_destroy(&e);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  return 0;
}
