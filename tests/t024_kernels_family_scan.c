/* Family candidate-scan kernels: every variant this CPU can run (AVX2, AVX-512) returns exactly the
 * reference's ids in the reference's order, on awkward sizes (0, 1, width-1, width, width+1, ...,
 * up to 100 candidates), with self present or absent, with candidates exactly at r2max and one ulp
 * either side of it, and never writes beyond n_cand + PDK_SCAN_OUT_PAD entries of out.
 * labels: unit */
#include <stdint.h>

#include "kernels.h"
#include "core/pdk_impl.h"
#include "test_util.h"

typedef pdk_index (*scan2_fn)(pdk_index, const double *restrict, const double *restrict, double,
                              double, double, pdk_index, const pdk_index *restrict,
                              pdk_index *restrict);
typedef pdk_index (*scan3_fn)(pdk_index, const double *restrict, const double *restrict,
                              const double *restrict, double, double, double, double, pdk_index,
                              const pdk_index *restrict, pdk_index *restrict);

static uint64_t rng_next(uint64_t *s) {
  uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}
static double rng_unit(uint64_t *s) { return (double)(rng_next(s) >> 11) * 0x1p-53; }

enum { MAXC = 100, GUARD = -777 };

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  const unsigned isa = t_isa(ctx);
  struct {
    const char *name;
    unsigned need;
    scan2_fn s2;
    scan3_fn s3;
  } variants[] = {
      {"avx2", PDK_ISA_AVX2, pdk_kernel_family_scan2_avx2, pdk_kernel_family_scan3_avx2},
      {"avx512", PDK_ISA_AVX512, pdk_kernel_family_scan2_avx512, pdk_kernel_family_scan3_avx512},
  };
  /* The table's simd entries are among the variants this CPU runs. */
  pdk_kernel_table t;
  T_ASSERT(pdk_kernels_select("simd", isa, &t) == 0, "select simd");
  if (isa & PDK_ISA_AVX512)
    T_ASSERT(t.family_scan3 == pdk_kernel_family_scan3_avx512, "AVX-512 scan installed");
  else if (isa & PDK_ISA_AVX2)
    T_ASSERT(t.family_scan3 == pdk_kernel_family_scan3_avx2, "AVX2 scan installed");
  T_ASSERT(pdk_kernels_select("ref", isa, &t) == 0 && t.family_scan2 == pdk_kernel_family_scan2_ref,
           "ref table");

  uint64_t seed = 7;
  double cx[MAXC], cy[MAXC], cz[MAXC];
  pdk_index id[MAXC], ref[MAXC + PDK_SCAN_OUT_PAD], got[MAXC + PDK_SCAN_OUT_PAD + 8];
  const double xi = 0.3, yi = -0.2, zi = 0.1, r2max = 0.25;
  int tested = 0;
  for (size_t v = 0; v < sizeof variants / sizeof variants[0]; ++v) {
    if (!(isa & variants[v].need)) continue;
    for (int n = 0; n <= MAXC; ++n) {
      for (int trial = 0; trial < 6; ++trial) {
        for (int k = 0; k < n; ++k) {
          cx[k] = xi + (rng_unit(&seed) - 0.5) * 1.2;
          cy[k] = yi + (rng_unit(&seed) - 0.5) * 1.2;
          cz[k] = zi + (rng_unit(&seed) - 0.5) * 1.2;
          id[k] = 1000 + 3 * k;
          const uint64_t r = rng_next(&seed) % 8;
          if (r < 3) { /* a candidate on or one ulp around the sphere, along x */
            cy[k] = yi;
            cz[k] = zi;
            cx[k] = xi + sqrt(r2max);
            if (r == 1) cx[k] = nextafter(cx[k], 1e9);
            if (r == 2) cx[k] = nextafter(cx[k], -1e9);
          }
        }
        /* self: absent, first, last, or in the middle (at distance 0) */
        pdk_index self = -5;
        if (n > 0 && trial > 0) {
          int at = trial == 1 ? 0 : (trial == 2 ? n - 1 : (int)(rng_next(&seed) % (uint64_t)n));
          self = id[at];
          cx[at] = xi, cy[at] = yi, cz[at] = zi;
        }
        for (int dim = 2; dim <= 3; ++dim) {
          pdk_index nref, ngot;
          for (int k = 0; k < MAXC + PDK_SCAN_OUT_PAD + 8; ++k)
            got[k] = GUARD;
          if (dim == 2) {
            nref = pdk_kernel_family_scan2_ref(n, cx, cy, xi, yi, r2max, self, id, ref);
            ngot = variants[v].s2(n, cx, cy, xi, yi, r2max, self, id, got);
          } else {
            nref = pdk_kernel_family_scan3_ref(n, cx, cy, cz, xi, yi, zi, r2max, self, id, ref);
            ngot = variants[v].s3(n, cx, cy, cz, xi, yi, zi, r2max, self, id, got);
          }
          T_ASSERT(ngot == nref, "%s %d-D n = %d trial %d: %d ids, ref %d", variants[v].name, dim,
                   n, trial, (int)ngot, (int)nref);
          for (int k = 0; k < nref; ++k)
            T_ASSERT(got[k] == ref[k], "%s %d-D n = %d: id %d is %d, ref %d", variants[v].name, dim,
                     n, k, (int)got[k], (int)ref[k]);
          for (int k = n + PDK_SCAN_OUT_PAD; k < MAXC + PDK_SCAN_OUT_PAD + 8; ++k)
            T_ASSERT(got[k] == GUARD, "%s %d-D n = %d: wrote out[%d], beyond the allowed room",
                     variants[v].name, dim, n, k);
          ++tested;
        }
      }
    }
  }
  pdk_ctx_destroy(&ctx);
  if (!tested) T_SKIP("t024: no AVX2 or AVX-512 on this CPU: no variant to test (the table was)");
  return 0;
}
