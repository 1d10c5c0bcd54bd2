/* pdk: peridynamics solid mechanics with ductile fracture. This header includes every public one. */
#ifndef PDK_PDK_H
#define PDK_PDK_H

#include "pdk/version.h"
#include "pdk/export.h"
#include "pdk/ctx.h"
#include "pdk/particles.h"
#include "pdk/geometry.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/explicit.h"
#include "pdk/scene.h"
#include "pdk/output.h"
#include "pdk/plasticity.h"
#include "pdk/static.h"
#include "pdk/run.h"
#include "pdk/comm.h"

#endif
