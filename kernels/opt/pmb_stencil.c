/* PMB force and LPS dilation / force passes on the lattice (stencil layout) for the baseline ISA
 * (any x86-64 or other CPU): 2 sites per vector; the bodies are kernels/opt/pmb_stencil.h and
 * lps_stencil.h (layout, method, equality with the general path there). */
#include <math.h>

#include "kernels.h"

PDK_KERNEL_FP_EXACT

#define SC_W 2
#define SC_U 4
#if defined(__SSE2__)
#include <emmintrin.h>
#define SC_SQRT(v) ((sc_vd)_mm_sqrt_pd((__m128d)(v)))
#define SC_MIN(a, b) ((sc_vd)_mm_min_pd((__m128d)(a), (__m128d)(b)))
#else
#define SC_SQRT(v)                                                                                 \
  ({                                                                                               \
    sc_vd r_ = (v);                                                                                \
    for (int l_ = 0; l_ < SC_W; ++l_) r_[l_] = sqrt(r_[l_]);                                       \
    r_;                                                                                            \
  })
#endif
#define SC_NAME(base) base##_base
#include "opt/pmb_stencil.h"
#include "opt/lps_stencil.h"
