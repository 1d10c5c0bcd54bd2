/* The Taylor anvil's measures from the .h5 of a pdk run of scenes/taylor_anvil.yaml (its last field
 * output, which holds u and eps_p): final length, mushroom radius, largest plastic strain
 * (docs/validation/taylor_anvil.md). Not built with pdk; compile it against HDF5:
 *   cc -O2 -o taylor_measure docs/validation/taylor_anvil_measure.c \
 *      $(pkg-config --cflags --libs hdf5) -lm
 *   ./taylor_measure out/taylor_anvil/taylor_anvil.h5 0.4e-3      (the run's spacing)
 * final length: the extent of the current positions along z plus one spacing (each particle
 * stands for a cell); mushroom radius: the largest distance from the axis of a particle of the
 * impact-end layer (reference Z < spacing) plus half a spacing; largest eps_p over all particles. */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static double *read_f64(hid_t f, const char *path, hsize_t *n) {
  hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
  if (d < 0) {
    fprintf(stderr, "no dataset %s\n", path);
    exit(1);
  }
  hid_t s = H5Dget_space(d);
  hsize_t dims[2] = {0, 1};
  int nd = H5Sget_simple_extent_dims(s, dims, NULL);
  double *v = malloc(dims[0] * (nd > 1 ? dims[1] : 1) * sizeof *v);
  if (!v || H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0) exit(1);
  *n = dims[0];
  H5Sclose(s);
  H5Dclose(d);
  return v;
}

int main(int argc, char **argv) {
  if (argc != 3) {
    fprintf(stderr, "usage: %s <run>.h5 <spacing>\n", argv[0]);
    return 2;
  }
  const double h = atof(argv[2]);
  hid_t f = H5Fopen(argv[1], H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return 1;
  hid_t g = H5Gopen2(f, "/steps", H5P_DEFAULT);
  H5G_info_t info;
  H5Gget_info(g, &info);
  char last[64], path[128];
  H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, info.nlinks - 1, last, sizeof last,
                     H5P_DEFAULT);
  hsize_t n = 0;
  double *X = read_f64(f, "/static/X", &n);
  snprintf(path, sizeof path, "/steps/%s/u", last);
  double *u = read_f64(f, path, &n);
  snprintf(path, sizeof path, "/steps/%s/eps_p", last);
  double *ep = read_f64(f, path, &n);
  double zmin = INFINITY, zmax = -INFINITY, r = 0, epmax = 0;
  for (hsize_t i = 0; i < n; ++i) {
    const double x = X[3 * i] + u[3 * i], y = X[3 * i + 1] + u[3 * i + 1];
    const double z = X[3 * i + 2] + u[3 * i + 2];
    zmin = fmin(zmin, z);
    zmax = fmax(zmax, z);
    epmax = fmax(epmax, ep[i]);
    if (X[3 * i + 2] < h) r = fmax(r, hypot(x, y));
  }
  printf("%llu particles, output %s: final length %.2f mm, mushroom radius %.2f mm, largest eps_p "
         "%.2f, lowest z %.4f mm\n",
         (unsigned long long)n, last, (zmax - zmin + h) * 1e3, (r + h / 2) * 1e3, epmax,
         zmin * 1e3);
  free(X);
  free(u);
  free(ep);
  H5Gclose(g);
  H5Fclose(f);
  return 0;
}
