/* Vector types and helpers of the stencil-layout kernels (kernels/opt/pmb_stencil.h,
 * lps_stencil.h, corr_stencil.h): lanes are consecutive sites. The including file defines SC_W
 * (lanes per vector) and SC_U (vectors per block) first. */
#ifndef PDK_STENCIL_SIMD_H
#define PDK_STENCIL_SIMD_H
#include <string.h>

typedef double sc_vd __attribute__((vector_size(SC_W * 8)));
typedef long long sc_vl __attribute__((vector_size(SC_W * 8)));
typedef uint8_t sc_vb __attribute__((vector_size(SC_W)));

#define SC_INLINE static inline __attribute__((always_inline))
#define SC_B (SC_U * SC_W) /* sites per block */
_Static_assert(SC_B <= PDK_STENCIL_SLACK, "a block reads past the row into the slack");

SC_INLINE sc_vd sc_set1(double a) {
  sc_vd v;
  for (int l = 0; l < SC_W; ++l)
    v[l] = a;
  return v;
}
SC_INLINE sc_vd sc_ld(const double *p) { /* unaligned load */
  sc_vd v;
  memcpy(&v, p, sizeof v);
  return v;
}
SC_INLINE sc_vd sc_sel(sc_vl m, sc_vd a, sc_vd b) { /* m ? a : b per lane */
  return (sc_vd)(((sc_vl)a & m) | ((sc_vl)b & ~m));
}
/* t < 1 ? t : 1 per lane (NaN gives 1): the partial-volume factor's min(1, t). SC_MIN(a, b), when
 * the including file defines it, is the ISA's minimum instruction (vminpd: a < b ? a : b, the same
 * result for every input, NaN and signed zeros included), one instruction where the comparison
 * and selection take three or four. */
SC_INLINE sc_vd sc_min1(sc_vd t) {
  const sc_vd one = sc_set1(1.0);
#ifdef SC_MIN
  return SC_MIN(t, one);
#else
  return sc_sel(t < one, t, one);
#endif
}
/* Mask bytes of one vector as 0.0 / 1.0, only the first nv lanes read (0 beyond): the sites past
 * a row may belong to another thread's rows, whose mask a committing pass is writing. */
SC_INLINE sc_vd sc_mask_lanes(const uint8_t *mk, int nv) {
  sc_vb mb = {0};
  if (nv >= SC_W)
    memcpy(&mb, mk, sizeof mb);
  else
    for (int l = 0; l < nv; ++l)
      mb[l] = mk[l];
  return __builtin_convertvector(mb, sc_vd);
}

#endif
