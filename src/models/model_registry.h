/* Private: the registry of model kinds and correspondence laws (src/models/model_registry.c).
 *
 * A model kind is one plug-in: its file(s) (src/model_<kind>.c) define its operations
 * (pdk_model_ops, src/models/model_impl.h) and one pdk_model_kind_info, which says what the rest of pdk
 * may ask about the kind: its name, capabilities, coupling hops, the scene keys it accepts, the
 * derived output fields it provides. A correspondence law is one plug-in too: its file
 * (src/law_<law>.c) defines one pdk_law_info (name, flags, its out-of-plane stress and derived
 * quantities) and its kernel header (kernels/ref/law_<law>.h). The registry lists both, one line
 * each; the scene layer, the solvers, checkpoints and output ask it (or the model's ops) and never
 * name a kind or a law. docs/architecture.md has the recipe for a new kind or law.
 */
#ifndef PDK_MODEL_REGISTRY_H
#define PDK_MODEL_REGISTRY_H

#include <stddef.h>

#include "pdk/model.h"

struct pdk_model_ops;

/* Capabilities of a kind (pdk_model_kind_info.caps). */
enum {
  PDK_KIND_SCENE = 1u << 0,     /* scenes may name it (model.kind) */
  PDK_KIND_SHEAR = 1u << 1,     /* needs a shear modulus (else the bulk modulus alone) */
  PDK_KIND_STENCIL = 1u << 2,   /* has a stencil path (model.stencil: on; see no_stencil) */
  PDK_KIND_MATERIALS = 1u << 3, /* supports several materials */
  PDK_KIND_LAWS = 1u << 4,      /* takes a correspondence law (opts.law) and its options */
  PDK_KIND_FLOAT = 1u << 5,     /* implements float storage (opts.precision) */
  PDK_KIND_SPAN_FLAG = 1u << 6, /* field "flag" marks particles whose family does not span */
  PDK_KIND_TANGENT = 1u << 7    /* has an analytic Newton tangent (pdk_model_ops.tangent_column) */
};

/* A derived output field a kind provides (pdk_model_ops.derived computes it). */
typedef struct pdk_model_derived_info {
  const char *name; /* the field's name, as in output.fields */
  const char *what; /* what it is, for messages: "stress" */
} pdk_model_derived_info;

typedef struct pdk_model_kind_info {
  pdk_model_kind kind;
  const char *name; /* as in scenes, checkpoints and messages */
  unsigned caps;    /* PDK_KIND_* */
  int hops;         /* coupling hops: f_i depends on particles within `hops` family hops of i */
  pdk_stabilization scene_stabilization; /* model.stabilization when a scene gives none */
  /* The scene keys only some kinds accept (model.influence, ...): those this kind does,
   * NULL-terminated (or NULL). */
  const char *const *scene_keys;
  /* Derived output fields (NULL-terminated by name, or NULL). */
  const pdk_model_derived_info *derived;
  /* Memory estimate of a scene before it is built (bytes per point, per bond in double and float
   * storage, and the Newton solver's per bond per dim^2), measured on the shipped scenes. */
  double mem_point, mem_bond, mem_bond_float, mem_newton_bond;
  /* bytes per bond more with bond_lengths stored and precision double (0: the kind stores none) */
  double mem_bond_lengths;
  /* The operations that implement these options. */
  const struct pdk_model_ops *(*ops_for)(const pdk_model_opts *o);
  /* 1 when the force passes walk the particles' arrays in lattice-row order (stencil path), so
   * the particles are best ordered by rows rather than Morton cells; NULL: never. */
  int (*stencil_rows)(const pdk_model_opts *o);
  /* 1 when a Newton solve may rely on a symmetric tangent (the force derives from an energy);
   * NULL: always. */
  int (*hyperelastic)(const pdk_model_opts *o);
  /* 1 when the options leave zero-energy modes uncontrolled (for a solver's diagnosis); NULL:
   * never. */
  int (*unstabilized)(const pdk_model_opts *o);
  /* PDK_KIND_STENCIL kinds: 1 when these options take a path without a stencil (NULL: never),
   * and why stencil on is refused with these options (the message; NULL: it is not). */
  int (*no_stencil)(const pdk_model_opts *o);
  const char *(*stencil_refusal)(const pdk_model_opts *o);
} pdk_model_kind_info;

/* Flags of a correspondence law (pdk_law_info.flags). */
enum {
  PDK_LAWF_HYPERELASTIC = 1u << 0, /* stress from a strain energy: a symmetric Newton tangent */
  PDK_LAWF_HISTORY = 1u << 1,      /* plastic history (eps_p, ...): softening, break_stress,
                                     damage_triaxiality apply */
  PDK_LAWF_ONE_MATERIAL = 1u << 2, /* takes one material (its own parameters) */
  PDK_LAWF_PLASTICITY = 1u << 3    /* takes opts.jc (scene: material.johnson_cook) */
};

typedef struct pdk_law_info {
  pdk_law law;
  const char *name; /* as in scenes (model.law) */
  unsigned flags;   /* PDK_LAWF_* */
  /* PDK_LAWF_ONE_MATERIAL: why a scene's materials are refused */
  const char *one_material_why;
  /* Output fields only this law declares (NULL-terminated, or NULL), and the hint a scene's
   * output.fields gets when it asks for one under another law. */
  const char *const *history_fields;
  const char *history_hint;
  /* Elastic laws: the Cauchy stress S (3 x 3, S[2][2] the plane-strain out-of-plane component in
   * 2-D) of a particle with first Piola-Kirchhoff stress P (d x d) at F (F[2][2] = 1 in 2-D), the
   * particle's lambda; returns 0 when the law has no value there (S is then not used). */
  int (*cauchy)(int d, double lambda, const double F[3][3], const double P[3][3], double S[3][3]);
  /* Laws with history: von Mises of every particle ([n]) from the model's history fields at the
   * stored F (a trial update with time step dt: nothing changes). */
  int (*von_mises)(const pdk_model *m, double dt, double *vm);
  /* Rate-dependent laws: nonzero when these options need strain rates, with what needs them in
   * buf ("the Johnson-Cook rate terms (C = .., D4 = ..)"); NULL: never. */
  int (*rate_terms)(const pdk_model_opts *o, char *buf, size_t len);
  /* 1 when the law's failed particles break their bonds with these options; NULL: never. */
  int (*breaks_bonds)(const pdk_model_opts *o);
} pdk_law_info;

/* The registered kinds and laws, in registry order (i = 0, 1, ...; NULL past the end). */
const pdk_model_kind_info *pdk_model_kind_at(int i);
const pdk_law_info *pdk_law_at(int i);
/* The entry of a kind or law, or NULL when none is registered under that value. */
const pdk_model_kind_info *pdk_model_kind_info_of(pdk_model_kind kind);
const pdk_law_info *pdk_law_info_of(pdk_law law);
/* A law's name ("?" when unknown). */
const char *pdk_law_name(pdk_law law);
/* The names of the kinds whose caps & mask == want (include PDK_KIND_SCENE in both for the kinds
 * scenes may name), joined by ", " and `last` before the last one ("pmb, lps or correspondence"),
 * into buf; returns buf. */
const char *pdk_model_kinds_list(unsigned mask, unsigned want, const char *last, char *buf,
                                 size_t len);
/* The scene kind that provides derived field `name` (NULL when none does), and the entry. */
const pdk_model_kind_info *pdk_model_derived_owner(const char *name,
                                                   const pdk_model_derived_info **out);
/* The derived field `name` of kind `kind`, or NULL. */
const pdk_model_derived_info *pdk_model_kind_derived(pdk_model_kind kind, const char *name);

/* Queries on options (the kind's and the law's entries). */
int pdk_model_opts_hops(const pdk_model_opts *o);
int pdk_model_opts_has(const pdk_model_opts *o, unsigned cap);
int pdk_model_opts_hyperelastic(const pdk_model_opts *o);
int pdk_model_opts_unstabilized(const pdk_model_opts *o);
int pdk_model_opts_stencil_rows(const pdk_model_opts *o);
/* The kind takes laws and the law has all of `flags` (PDK_LAWF_*). */
int pdk_model_opts_law_has(const pdk_model_opts *o, unsigned flags);
/* The law needs strain rates (what in buf), or 0. */
int pdk_model_opts_rate_terms(const pdk_model_opts *o, char *buf, size_t len);
/* The law's failed particles break their bonds. */
int pdk_model_opts_law_breaks(const pdk_model_opts *o);
/* The scene keys (model.*) only some kinds accept, each once, in registry order (NULL past the
 * end), and whether the kind of o accepts `key` (1 too for a key no kind restricts). */
const char *pdk_model_scene_key_at(int i);
int pdk_model_opts_scene_key(const pdk_model_opts *o, const char *key);
/* The scene kinds that accept `key`, joined as pdk_model_kinds_list (count in *count). */
const char *pdk_model_key_kinds(const char *key, const char *last, char *buf, size_t len,
                                int *count);

/* Queries on a model (src/models/model.c). */
/* Derived output field `name` of every particle into out [n] (the kind's pdk_model_ops.derived;
 * dt: the step of the last force pass). */
int pdk_model_derived(const pdk_model *m, const char *name, double dt, double *out);
/* The derived fields of this model (NULL past the end): its kind's, then "bond_damage" (every
 * model, pdk_model_bond_damage) and "damage" (the same, when the law declares no "damage" of its
 * own); and the one named `name`, or NULL. */
const pdk_model_derived_info *pdk_model_derived_at(const pdk_model *m, int i);
const pdk_model_derived_info *pdk_model_derived_of(const pdk_model *m, const char *name);
/* 1 when the model has an analytic Newton tangent (pdk_model_ops.tangent_column). */
int pdk_model_has_tangent(const pdk_model *m);
#endif
