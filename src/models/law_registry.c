/* The registry of correspondence laws (src/models/model_registry.h): one line each. Below the kinds:
 * the kinds that take laws look them up here. */
#include "model_registry.h"
#include "pdk/model.h"

/* The correspondence laws, each defining pdk_law_<name> in src/law_<name>.c. */
#define PDK_LAWS(X) X(linear_elastic) X(svk) X(neo_hooke) X(jc)

#define PDK_DECLARE_LAW(l) extern const pdk_law_info pdk_law_##l;
#define PDK_LIST_LAW(l) &pdk_law_##l,
PDK_LAWS(PDK_DECLARE_LAW)
static const pdk_law_info *const laws[] = {PDK_LAWS(PDK_LIST_LAW)};
#define NUM_LAWS ((int)(sizeof laws / sizeof laws[0]))

const pdk_law_info *pdk_law_at(int i) { return i >= 0 && i < NUM_LAWS ? laws[i] : NULL; }

const pdk_law_info *pdk_law_info_of(pdk_law law) {
  for (int i = 0; i < NUM_LAWS; ++i)
    if (laws[i]->law == law) return laws[i];
  return NULL;
}

const char *pdk_law_name(pdk_law law) {
  const pdk_law_info *l = pdk_law_info_of(law);
  return l ? l->name : "?";
}
