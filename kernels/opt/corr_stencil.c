/* Correspondence passes on the lattice (stencil layout) for the baseline ISA (any x86-64 or other
 * CPU): 2 sites per vector; the body is kernels/opt/corr_stencil.h (layout, method, agreement with
 * the general path there). */
#include "kernels.h"

#define SC_W 2
#define SC_U 2
#define SC_NAME(base) base##_base
#include "opt/corr_stencil.h"
