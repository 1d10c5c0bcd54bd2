/* Scene loading, step 3 (src/scene/scene.c): output (intervals, fields, reaction sets, units) and
 * limits (the run's memory estimate against the memory it may use) (src/scene/scene_load.h).
 */
#include <unistd.h>

#include "models/model_registry.h"
#include "scene_load.h"
#include "pdk/ctx.h"
#include "pdk/explicit.h"
#include "pdk/geometry.h"
#include "pdk/model.h"
#include "pdk/scene.h"

int pdk_scene_resolve_output(loader *ld, const sc_scene *d) {
  pdk_scene *s = ld->s;
  const sc_output *o = &d->output;
  pdk_scene_output *out = &s->output;
  PDK_CALL(
      check_whole(ld, "output.field_interval", o->field_interval, 0, 1e15, &out->field_interval));
  const int is_static = s->solver_type != PDK_SOLVER_EXPLICIT;
  out->history_interval = is_static ? 1 : 10;
  if (has(ld, "output.history_interval"))
    PDK_CALL(check_whole(ld, "output.history_interval", o->history_interval, 1, 1e15,
                         &out->history_interval));
  PDK_CALL(check_whole(ld, "output.checkpoint_interval", o->checkpoint_interval, 0, 1e15,
                       &out->checkpoint_interval));
  out->units = o->units == UNITS_SI ? "SI" : o->units == UNITS_MM ? "mm-N-s-tonne" : NULL;
  {
    long level = 0;
    PDK_CALL(check_whole(ld, "output.compression", o->compression, 0, 9, &level));
    out->compression = (int)level;
  }

  const char *default_fields[] = {"u", "v"};
  const int hf = has(ld, "output.fields");
  const int nf = hf ? (int)o->fields_count : is_static ? 1 : 2; /* static: no velocities */
  s->fields = calloc((size_t)nf + 1, sizeof *s->fields);
  if (!s->fields) return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory");
  for (int k = 0; k < nf; ++k) {
    const char *f = hf ? o->fields[k] : default_fields[k];
    const char *key = K(ld, "output.fields[%d]", k);
    REQUIRE(ld, valid_name(f) || !strncmp(f, "set:", 4), key,
            "'%s' is not a field name; fields are names such as u, v, f, x", f);
    for (int j = 0; j < k; ++j)
      REQUIRE(ld, strcmp(s->fields[j], f), key, "'%s' is listed twice; list each field once", f);
    s->fields[k] = strdup(f);
    out->num_fields = k + 1;
    if (!s->fields[k]) return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory");
  }
  out->fields = (const char *const *)s->fields;

  /* Reaction sets: given, or by default the sets of the displacement and velocity conditions. */
  int nr = 0;
  const char *names[MAX_REACTION_SETS];
  if (has(ld, "output.reactions")) {
    for (int k = 0; k < (int)o->reactions_count; ++k) {
      const char *key = K(ld, "output.reactions[%d]", k);
      char sets[512];
      list_sets(s, sets, sizeof sets);
      REQUIRE(ld, find_set(s, o->reactions[k]) >= 0, key,
              "names the set '%s', which is not defined; defined sets: %s", o->reactions[k], sets);
      for (int j = 0; j < nr; ++j)
        REQUIRE(ld, strcmp(names[j], o->reactions[k]), key, "'%s' is listed twice",
                o->reactions[k]);
      REQUIRE(ld, nr < MAX_REACTION_SETS, key, "at most %d reaction sets are recorded; list fewer",
              MAX_REACTION_SETS);
      names[nr++] = o->reactions[k];
    }
  } else {
    for (int k = 0; k < s->num_bcs && nr < MAX_REACTION_SETS; ++k) {
      const char *set = d->boundary_conditions[k].set;
      if (s->bcs[k].kind == PDK_BC_BODY_FORCE || s->bcs[k].kind == PDK_BC_WALL ||
          !strcmp(set, "all"))
        continue;
      int dup = 0;
      for (int j = 0; j < nr; ++j)
        dup |= !strcmp(names[j], set);
      if (!dup) names[nr++] = set;
    }
  }
  s->reaction_names = calloc((size_t)nr + 1, sizeof(char *));
  s->reaction_fields = calloc((size_t)nr + 1, sizeof(char *));
  if (!s->reaction_names || !s->reaction_fields)
    return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory");
  for (int k = 0; k < nr; ++k) {
    size_t len = strlen(names[k]) + 5;
    s->reaction_names[k] = strdup(names[k]);
    s->reaction_fields[k] = malloc(len);
    out->num_reaction_sets = k + 1;
    if (!s->reaction_names[k] || !s->reaction_fields[k])
      return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory");
    snprintf(s->reaction_fields[k], len, "set:%s", names[k]);
  }
  out->reaction_sets = (const char *const *)s->reaction_names;
  for (int k = 0; k < nr && k < 8; ++k) /* a condition along a direction on the set: its n */
    for (int b = 0; b < s->num_bcs; ++b) {
      const pdk_bc *bc = &s->bcs[b];
      const double *dn = bc->direction;
      const double len = sqrt(dn[0] * dn[0] + dn[1] * dn[1] + dn[2] * dn[2]);
      if (len > 0 && s->bc_fields[b] && !strcmp(s->bc_fields[b], s->reaction_fields[k]))
        for (int a = 0; a < 3; ++a)
          out->reaction_normal[k][a] = dn[a] / len;
    }
  s->solver.reaction_sets = (const char *const *)s->reaction_fields;
  s->solver.num_reaction_sets = nr;
  s->static_opts.reaction_sets = (const char *const *)s->reaction_fields;
  s->static_opts.num_reaction_sets = nr;
  return PDK_SUCCESS;
}

/* Memory available to this process now, in bytes: MemAvailable of /proc/meminfo (what the kernel
 * can hand out without swapping), else the free pages; 0 when neither is known. */
static double memory_available(const char **source) {
  FILE *f = fopen("/proc/meminfo", "r");
  if (f) {
    char line[256];
    double kb = -1;
    while (fgets(line, sizeof line, f))
      if (sscanf(line, "MemAvailable: %lf kB", &kb) == 1) break;
    fclose(f);
    if (kb > 0) {
      *source = "available (MemAvailable in /proc/meminfo)";
      return kb * 1024.0;
    }
  }
#if defined(_SC_AVPHYS_PAGES) && defined(_SC_PAGESIZE)
  long pages = sysconf(_SC_AVPHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages > 0 && page > 0) {
    *source = "free (sysconf _SC_AVPHYS_PAGES)";
    return (double)pages * (double)page;
  }
#endif
  return 0;
}

/* The memory a run of the scene needs, estimated before anything is allocated: a base, bytes per
 * lattice point (positions, velocities, forces, model state, cells) and bytes per bond (neighbour
 * lists, bond state; a Newton solve also its tangent and factor), the bonds per point from the
 * horizon's area or volume over a lattice cell. Measured with pdk check and pdk run (peak resident
 * set) on the shipped scenes refined to 1e5 to 5e5 points: PMB and LPS 380 to 540 B per point and
 * 4 B per bond (float: 8), correspondence 640 to 730 B and 12 to 14 B, Newton about 700 B per bond
 * (correspondence, 2-D) and 270 B (PMB); the figures below are those rounded up. */
static double memory_estimate(const pdk_scene *s, double *per_point, double *per_bond,
                              double *bonds) {
  const double m = s->horizon_factor, pi = 3.14159265358979323846;
  double nb = s->dim == 3 ? 4.0 / 3.0 * pi * m * m * m : pi * m * m;
  if (s->lattice.type == PDK_LATTICE_HEX) nb *= 2.0 / sqrt(3.0);
  const double n = (double)s->num_points;
  if (nb > n - 1) nb = n - 1;
  const pdk_model_kind_info *k = pdk_model_kind_info_of(s->model.kind);
  const int single = s->model.precision == PDK_PRECISION_FLOAT;
  *per_point = k->mem_point;
  *per_bond = single ? k->mem_bond_float : k->mem_bond;
  /* stored bond lengths (counted even where the stencil path will make them unnecessary: the
   * estimate errs high) */
  if (!single && s->model.bond_lengths == PDK_BOND_LENGTHS_STORED &&
      s->model.layout == PDK_LAYOUT_CSR)
    *per_bond += k->mem_bond_lengths;
  if (s->solver_type == PDK_SOLVER_NEWTON) *per_bond += k->mem_newton_bond * s->dim * s->dim;
  *bonds = n * nb;
  return 32.0 * 1024 * 1024 + n * *per_point + *bonds * *per_bond;
}

static void fmt_bytes(char *buf, size_t len, double bytes) {
  if (bytes >= 1e12)
    snprintf(buf, len, "%.3g TB", bytes / 1e12);
  else if (bytes >= 1e9)
    snprintf(buf, len, "%.3g GB", bytes / 1e9);
  else
    snprintf(buf, len, "%.3g MB", bytes / 1e6);
}

/* limits.memory: the estimate against the memory the run may use, before pdk_sim_create
 * allocates anything. */
int pdk_scene_resolve_limits(loader *ld, const sc_scene *d) {
  const pdk_scene *s = ld->s;
  const char *source = NULL;
  double limit;
  if (has(ld, "limits.memory")) {
    limit = d->limits.memory;
    REQUIRE(ld, isfinite(limit) && limit > 0, "limits.memory",
            "must be > 0, got %g (bytes the run may use, for example 64e9)", limit);
    source = "that limits.memory allows";
  } else {
    limit = memory_available(&source);
    if (limit <= 0) return PDK_SUCCESS; /* unknown: nothing to compare with */
  }
  double per_point, per_bond, bonds;
  const double need = memory_estimate(s, &per_point, &per_bond, &bonds);
  const int given = has(ld, "limits.memory");
  char need_s[32], limit_s[32];
  fmt_bytes(need_s, sizeof need_s, need);
  fmt_bytes(limit_s, sizeof limit_s, limit);
  REQUIRE(ld, need <= limit, given ? "limits.memory" : "geometry.spacing",
          "the run needs about %s by pdk's estimate (%.4g particles x %.0f B + %.4g bonds x "
          "%.0f B), more than the %s of memory %s; increase geometry.spacing or shrink "
          "geometry.box, or %s limits.memory (bytes, for example limits.memory: %.0fe9) to run "
          "it anyway",
          need_s, (double)s->num_points, per_point, bonds, per_bond, limit_s, source,
          given ? "raise" : "set", ceil(need / 1e9));
  return PDK_SUCCESS;
}
