/* pelt — a desc's parameters as data: for every field its name, where it
 * lives, its default and the range the library accepts. The library checks
 * a desc against these rows; the scene file's keys and the command line
 * read their ranges and defaults from them, so a value has one home. */
#ifndef PELT_PARAMS_H
#define PELT_PARAMS_H

#include "pelt/base.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum pelt_param_type {
    PELT_PARAM_UINT,  /* unsigned */
    PELT_PARAM_SEED,  /* uint32_t */
    PELT_PARAM_FLOAT, /* `count` floats (1, or 3 for a colour) */
    PELT_PARAM_ENUM,  /* an enum stored as an int, one of `names` */
    PELT_PARAM_BOOL   /* bool */
} pelt_param_type;

enum {
    PELT_PARAM_MIN_OPEN = 1u << 0, /* min itself is not accepted */
    PELT_PARAM_MAX_OPEN = 1u << 1  /* max itself is not accepted */
};

typedef struct pelt_param {
    const char *name;          /* the field's path in the desc: "look.density" */
    pelt_param_type type;
    size_t offset;             /* offsetof the field in the desc */
    unsigned count;            /* floats of a PELT_PARAM_FLOAT: 1 or 3 */
    double min, max;           /* the accepted range (after defaults), per float */
    unsigned flags;            /* PELT_PARAM_MIN_OPEN, PELT_PARAM_MAX_OPEN */
    /* What a zero field becomes. All 0: zero is a value, not "default".
       `derived` set: the default depends on the mesh or on other fields
       and is said in `derived` (see pelt_fur_desc). */
    double def[3];
    const char *derived;
    const char *const *names;  /* PELT_PARAM_ENUM: the values' names, NULL-terminated */
} pelt_param;

/* The rows of pelt_fur_desc (hooks excepted), in the desc's order. */
const pelt_param *pelt_fur_params(size_t *count);

/* The row of pelt_fur_desc named `name` ("layers", "look.texture_size"),
 * or NULL. */
const pelt_param *pelt_fur_param(const char *name);

/* The rows of pelt_atlas_desc (pointers, the cache folder and hooks
 * excepted), and one of them by name ("max_stretch"), or NULL. */
const pelt_param *pelt_atlas_params(size_t *count);
const pelt_param *pelt_atlas_param(const char *name);

/* True when a zero in this field stands for its default. */
bool pelt_param_zero_is_default(const pelt_param *p);

/* The curl looks of Silva et al. Fig. 7 by name, NULL-terminated:
 * "straight", "wavy", "few-large-curls", "many-small-curls"
 * (pelt_fur_curl_look, pelt_fur_desc_curl_preset, the scene's fur.preset,
 * the viewer's preset key). */
extern const char *const pelt_curl_preset_names[];

/* The index of a curl look in pelt_curl_preset_names, its second spelling
 * ("large_curls", "small_curls") accepted; -1 for an unknown or NULL name. */
int pelt_curl_preset_index(const char *name);

#ifdef __cplusplus
}
#endif
#endif
