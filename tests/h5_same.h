/* Test helper: two HDF5 files hold the same objects, attributes and dataset bytes (what h5diff
 * compares; object-header times are not compared). Include after test_util.h. */
#ifndef PDK_TEST_H5_SAME_H
#define PDK_TEST_H5_SAME_H

#include <hdf5.h>

typedef struct h5s_names {
  char **name;
  int n;
} h5s_names;

static inline herr_t h5s_collect(hid_t loc, const char *name, const H5A_info_t *info, void *data) {
  (void)loc;
  (void)info;
  h5s_names *nm = data;
  nm->name = realloc(nm->name, (size_t)(nm->n + 1) * sizeof *nm->name);
  nm->name[nm->n++] = strdup(name);
  return 0;
}

static inline void h5s_free(h5s_names *nm) {
  for (int k = 0; k < nm->n; ++k)
    free(nm->name[k]);
  free(nm->name);
}

/* Same type, extent and bytes of two attributes (is_attr) or datasets. */
static inline int h5s_same_data(hid_t a, hid_t b, int is_attr, const char *what, char *why,
                                size_t cap) {
  hid_t ta = is_attr ? H5Aget_type(a) : H5Dget_type(a),
        tb = is_attr ? H5Aget_type(b) : H5Dget_type(b);
  hid_t sa = is_attr ? H5Aget_space(a) : H5Dget_space(a),
        sb = is_attr ? H5Aget_space(b) : H5Dget_space(b);
  int same = H5Tequal(ta, tb) > 0 && H5Sextent_equal(sa, sb) > 0;
  if (!same) snprintf(why, cap, "%s: another type or shape", what);
  if (same) {
    const size_t bytes = (size_t)H5Sget_simple_extent_npoints(sa) * H5Tget_size(ta);
    unsigned char *x = malloc(bytes + 1), *y = malloc(bytes + 1);
    T_ASSERT(x && y, "out of memory");
    if (bytes)
      T_ASSERT(
          (is_attr ? H5Aread(a, ta, x) : H5Dread(a, ta, H5S_ALL, H5S_ALL, H5P_DEFAULT, x)) >= 0 &&
              (is_attr ? H5Aread(b, tb, y) : H5Dread(b, tb, H5S_ALL, H5S_ALL, H5P_DEFAULT, y)) >= 0,
          "%s: cannot read", what);
    same = !memcmp(x, y, bytes);
    if (!same) {
      size_t k = 0;
      while (x[k] == y[k])
        ++k;
      snprintf(why, cap, "%s: bytes differ from byte %zu of %zu", what, k, bytes);
    }
    free(x);
    free(y);
  }
  H5Tclose(ta);
  H5Tclose(tb);
  H5Sclose(sa);
  H5Sclose(sb);
  return same;
}

static inline int h5s_same_attrs(hid_t a, hid_t b, const char *path, char *why, size_t cap) {
  h5s_names na = {0}, nb = {0};
  hsize_t i = 0, j = 0;
  H5Aiterate2(a, H5_INDEX_NAME, H5_ITER_INC, &i, h5s_collect, &na);
  H5Aiterate2(b, H5_INDEX_NAME, H5_ITER_INC, &j, h5s_collect, &nb);
  int same = na.n == nb.n;
  if (!same) snprintf(why, cap, "%s: %d attributes against %d", path, na.n, nb.n);
  for (int k = 0; same && k < na.n; ++k) {
    char what[1024];
    snprintf(what, sizeof what, "%s attribute '%s'", path, na.name[k]);
    same = !strcmp(na.name[k], nb.name[k]);
    if (!same) {
      snprintf(why, cap, "%s: attribute '%s' against '%s'", path, na.name[k], nb.name[k]);
      break;
    }
    hid_t x = H5Aopen(a, na.name[k], H5P_DEFAULT), y = H5Aopen(b, nb.name[k], H5P_DEFAULT);
    same = h5s_same_data(x, y, 1, what, why, cap);
    H5Aclose(x);
    H5Aclose(y);
  }
  h5s_free(&na);
  h5s_free(&nb);
  return same;
}

static inline int h5s_same_group(hid_t a, hid_t b, const char *path, char *why, size_t cap) {
  if (!h5s_same_attrs(a, b, path, why, cap)) return 0;
  H5G_info_t ia, ib;
  H5Gget_info(a, &ia);
  H5Gget_info(b, &ib);
  if (ia.nlinks != ib.nlinks) {
    snprintf(why, cap, "%s: %llu members against %llu", path, (unsigned long long)ia.nlinks,
             (unsigned long long)ib.nlinks);
    return 0;
  }
  for (hsize_t k = 0; k < ia.nlinks; ++k) {
    char na[256], nb[256], child[1024];
    H5Lget_name_by_idx(a, ".", H5_INDEX_NAME, H5_ITER_INC, k, na, sizeof na, H5P_DEFAULT);
    H5Lget_name_by_idx(b, ".", H5_INDEX_NAME, H5_ITER_INC, k, nb, sizeof nb, H5P_DEFAULT);
    snprintf(child, sizeof child, "%s/%s", path, na);
    if (strcmp(na, nb)) {
      snprintf(why, cap, "%s: member '%s' against '%s'", path, na, nb);
      return 0;
    }
    hid_t x = H5Oopen(a, na, H5P_DEFAULT), y = H5Oopen(b, nb, H5P_DEFAULT);
    int same = H5Iget_type(x) == H5Iget_type(y);
    if (!same) snprintf(why, cap, "%s: another kind of object", child);
    if (same && H5Iget_type(x) == H5I_GROUP)
      same = h5s_same_group(x, y, child, why, cap);
    else if (same)
      same = h5s_same_attrs(x, y, child, why, cap) && h5s_same_data(x, y, 0, child, why, cap);
    H5Oclose(x);
    H5Oclose(y);
    if (!same) return 0;
  }
  return 1;
}

/* 1 when the files at a and b hold the same contents; else 0 with the first difference in why. */
static inline int h5s_same_file(const char *a, const char *b, char *why, size_t cap) {
  hid_t fa = H5Fopen(a, H5F_ACC_RDONLY, H5P_DEFAULT), fb = H5Fopen(b, H5F_ACC_RDONLY, H5P_DEFAULT);
  T_ASSERT(fa >= 0 && fb >= 0, "cannot open %s or %s", a, b);
  const int same = h5s_same_group(fa, fb, "", why, cap);
  H5Fclose(fa);
  H5Fclose(fb);
  return same;
}

/* 1 when the output groups /steps, /static and /history of the open files fa and fb hold the same
 * contents (everything but the root, whose attributes name the run's scene text); else 0 with the
 * first difference in why. */
static inline int h5s_same_output_data(hid_t fa, hid_t fb, char *why, size_t cap) {
  const char *const groups[] = {"/steps", "/static", "/history"};
  int same = 1;
  for (int k = 0; k < 3 && same; ++k) {
    hid_t ga = H5Gopen2(fa, groups[k], H5P_DEFAULT), gb = H5Gopen2(fb, groups[k], H5P_DEFAULT);
    T_ASSERT(ga >= 0 && gb >= 0, "cannot open %s in both files", groups[k]);
    same = h5s_same_group(ga, gb, groups[k], why, cap);
    H5Gclose(ga);
    H5Gclose(gb);
  }
  return same;
}

#endif
