/* What the kernels take from the rest of pdk, and nothing more: the index types and status codes
 * (pdk/ctx.h), the Johnson-Cook material point's parameters, state and result (pdk/plasticity.h),
 * and the values of the correspondence law and stabilization below. Kernels include this header
 * (through kernels.h) and no other pdk header: they know no model, family or particle store.
 *
 * The law and stabilization values are those of the public enums pdk_law and pdk_stabilization
 * (pdk/model.h), which the drivers copy into pdk_corr_consts.law and .stab; src/core/kernels.c checks
 * at compile time that the two agree. */
#ifndef PDK_KERNEL_TYPES_H
#define PDK_KERNEL_TYPES_H

#include "pdk/ctx.h"
#include "pdk/plasticity.h"

/* pdk_corr_consts.law: pdk_law */
enum {
  PDK_KERNEL_LAW_LINEAR_ELASTIC = 0,
  PDK_KERNEL_LAW_SVK = 1,
  PDK_KERNEL_LAW_NEO_HOOKE = 2,
  PDK_KERNEL_LAW_JC = 3
};

/* pdk_corr_consts.stab: pdk_stabilization */
enum { PDK_KERNEL_STAB_NONE = 0, PDK_KERNEL_STAB_SILLING = 1, PDK_KERNEL_STAB_HOURGLASS = 2 };

#endif
