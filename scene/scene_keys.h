/* The scene file's keys: one row per key (its path, kind, field and range),
 * read by the JSON binder (scene_file.c), --set and the CLI's key list.
 * Internal to scene/. */
#ifndef PELT_SCENE_KEYS_H
#define PELT_SCENE_KEYS_H

#include "pelt/params.h"
#include "pelt/scene.h"

#include <stddef.h>

/* A bound that stands for "none". */
#define BIG 1e30

typedef enum pelt__key_kind {
    K_UINT,     /* unsigned, integer in [lo, hi] */
    K_BOOL,     /* true or false into a bool */
    K_NOT,      /* true or false into a bool, inverted (draw.skin into no_skin) */
    K_U32,      /* uint32_t seed, integer in [0, 2^32-1] */
    K_FLOAT,    /* float in [lo, hi] */
    K_VEC,      /* `count` floats, each in [lo, hi] */
    K_RANGE,    /* [min, max] into two floats at off and off2, min <= max */
    K_PATH,     /* string into char[PELT_SCENE_PATH_MAX], resolved */
    K_ENUM,     /* one of names[], stored as its index in an int */
    K_PRESET,   /* a curl preset name or "", stored as its name in pelt_curl_preset_names */
    K_PARAM,    /* a field of the embedded pelt_fur_desc, read as its row (pelt/params.h) says */
    K_NAME,     /* a name (string) or an index (integer) into char[PELT_ANIMATION_NAME_MAX] */
    K_DROPLETS, /* array of droplet objects: pointer at off, count at off2 */
    K_WINDKEYS, /* array of wind keyframes: pointer at off, count at off2 */
    K_STROKES   /* array of brush strokes: pointer at off, count at off2 */
} pelt__key_kind;

enum {
    F_LO_OPEN = 1u << 0,  /* the lower bound itself is not allowed */
    F_ZERO_OK = 1u << 1,  /* 0 is allowed as "default" below the range */
    F_NONZERO = 1u << 2,  /* a vector that must not be all zero */
    F_ACCEPT3 = 1u << 3,  /* a 4-vector may be given with 3 numbers */
    F_HI_OPEN = 1u << 4   /* the upper bound itself is not allowed */
};

typedef struct pelt__scene_key {
    const char *path;
    pelt__key_kind k;
    size_t off, off2;
    double lo, hi;
    unsigned flags;
    unsigned count;           /* K_VEC */
    const char *const *names; /* K_ENUM; NULL-terminated */
    const char *param;        /* K_PARAM: the row's name ... */
    const pelt_param *(*lookup)(const char *name); /* ... in this table (pelt_fur_param) */
} pelt__scene_key;

typedef struct pelt__scene_keys {
    const pelt__scene_key *keys;
    size_t count;
} pelt__scene_keys;

extern const pelt__scene_keys pelt__scene_key_table;   /* the scene object */
extern const pelt__scene_keys pelt__droplet_key_table; /* one droplet of wetness.droplets */
extern const pelt__scene_keys pelt__wind_key_table;    /* one key of animation.wind_keys */
extern const pelt__scene_keys pelt__stroke_key_table;  /* one stroke of groom.strokes */

#endif
