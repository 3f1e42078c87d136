/* Scene files: JSON (cJSON) into pelt_scene, driven by one table of keys
 * (scene_keys.c) so that parsing, --set overrides and error messages all
 * agree. */
#include "pelt/scene.h"
#include "pelt/params.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/vec.h"
#include "scene/scene_keys.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Enum fields are written through an int. */
_Static_assert(sizeof(pelt_scene_shape) == sizeof(int), "enum size");
_Static_assert(sizeof(pelt_color_pattern) == sizeof(int), "enum size");
_Static_assert(sizeof(pelt_atlas_mode) == sizeof(int), "enum size");
_Static_assert(sizeof(pelt_vertex_colors_use) == sizeof(int), "enum size");
_Static_assert(sizeof(pelt_brush_tool) == sizeof(int), "enum size");
_Static_assert(sizeof(pelt_shading_model) == sizeof(int), "enum size");
_Static_assert(sizeof(pelt_lod_mode) == sizeof(int), "enum size");
_Static_assert(sizeof(pelt_strand_curl_shape) == sizeof(int), "enum size");
_Static_assert(sizeof(pelt_curl_phase) == sizeof(int), "enum size");
_Static_assert(sizeof(pelt_draw_mode) == sizeof(int), "enum size");
_Static_assert(sizeof(pelt_tone) == sizeof(int), "enum size");

typedef pelt__scene_key key_def;
typedef pelt__scene_keys table;

/* ------------------------------------------------------------ the parser */

typedef struct ctx {
    const char *name;     /* starts every message */
    const char *base_dir; /* relative paths resolve against it; NULL = as given */
    size_t base_len;
    pelt_error *err;
} ctx;

#define KEY_MAX 256

/* A short description of what a JSON node holds, for "got ..." */
static void describe(const cJSON *v, char *buf, size_t size)
{
    if (cJSON_IsNumber(v)) snprintf(buf, size, "%.9g", v->valuedouble);
    else if (cJSON_IsString(v)) {
        const char *str = v->valuestring;
        size_t n = strlen(str);
        if (n > 40) snprintf(buf, size, "\"%.40s...\"", str);
        else snprintf(buf, size, "\"%s\"", str);
    } else if (cJSON_IsBool(v)) snprintf(buf, size, "%s", cJSON_IsTrue(v) ? "true" : "false");
    else if (cJSON_IsNull(v)) snprintf(buf, size, "null");
    else if (cJSON_IsArray(v)) snprintf(buf, size, "an array of %d", cJSON_GetArraySize(v));
    else if (cJSON_IsObject(v)) snprintf(buf, size, "an object");
    else snprintf(buf, size, "something else");
}

static pelt_status bad(const ctx *c, const char *key, const char *expected, const cJSON *v)
{
    char got[64];
    describe(v, got, sizeof got);
    return pelt__fail(c->err, PELT_ERR_FORMAT, "%s: %s: expected %s, got %s", c->name, key,
                      expected, got);
}

/* The range [lo, hi] in words, for messages. */
static void range_text(const key_def *d, bool integer, char *buf, size_t size)
{
    const char *what = integer ? "an integer" : "a number";
    const char *zero = (d->flags & F_ZERO_OK) ? " (or 0 for the default)" : "";
    if (d->lo <= -BIG && d->hi >= BIG) snprintf(buf, size, "a finite number");
    else if (d->hi >= BIG && d->lo == 0 && (d->flags & F_LO_OPEN))
        snprintf(buf, size, "a positive %s%s", integer ? "integer" : "number", zero);
    else if (d->hi >= BIG)
        snprintf(buf, size, "%s %s %g%s", what, (d->flags & F_LO_OPEN) ? ">" : ">=", d->lo, zero);
    else if (d->flags & (F_LO_OPEN | F_HI_OPEN))
        snprintf(buf, size, "%s in %c%g, %g%c%s", what, (d->flags & F_LO_OPEN) ? '(' : '[', d->lo, d->hi,
                 (d->flags & F_HI_OPEN) ? ')' : ']', zero);
    else if (integer)
        snprintf(buf, size, "%s from %g to %g%s", what, d->lo, d->hi, zero);
    else snprintf(buf, size, "%s in [%g, %g]%s", what, d->lo, d->hi, zero);
}

static bool in_range(const key_def *d, double x)
{
    if (!isfinite(x)) return false;
    if ((d->flags & F_ZERO_OK) && x == 0.0) return true;
    if (d->flags & F_LO_OPEN ? !(x > d->lo) : !(x >= d->lo)) return false;
    if ((d->flags & F_HI_OPEN) ? !(x < d->hi) : !(x <= d->hi)) return false;
    /* A double that fits the range may still overflow a float. */
    return fabs(x) <= 3.0e38;
}

/* A number node checked against d's range, or an error naming `key`. */
static pelt_status number(const ctx *c, const key_def *d, const char *key, const cJSON *v,
                          bool integer, double *out)
{
    char expected[96];
    range_text(d, integer, expected, sizeof expected);
    if (!cJSON_IsNumber(v)) return bad(c, key, expected, v);
    double x = v->valuedouble;
    if (!in_range(d, x) || (integer && x != floor(x))) return bad(c, key, expected, v);
    *out = x;
    return PELT_OK;
}

static pelt_status numbers(const ctx *c, const key_def *d, const char *key, const cJSON *v,
                           unsigned count, float *out)
{
    char expected[64];
    snprintf(expected, sizeof expected, "an array of %u numbers", count);
    if (d->flags & F_ACCEPT3) snprintf(expected, sizeof expected, "an array of 3 or 4 numbers");
    if (!cJSON_IsArray(v)) return bad(c, key, expected, v);
    int n = cJSON_GetArraySize(v);
    if (!(n == (int)count || ((d->flags & F_ACCEPT3) && n == 3))) return bad(c, key, expected, v);
    float tmp[4] = {0, 0, 0, 1};
    int i = 0;
    for (const cJSON *e = v->child; e; e = e->next, i++) {
        char sub[KEY_MAX + 16];
        snprintf(sub, sizeof sub, "%s[%d]", key, i);
        double x = 0.0;
        pelt_status st = number(c, d, sub, e, false, &x);
        if (st != PELT_OK) return st;
        tmp[i] = (float)x;
    }
    if ((d->flags & F_NONZERO) && tmp[0] == 0 && tmp[1] == 0 && tmp[2] == 0)
        return bad(c, key, "a non-zero vector", v);
    memcpy(out, tmp, count * sizeof(float));
    return PELT_OK;
}

/* Stores `str` into dst as it would be opened from the scene's directory. */
static pelt_status store_path(const ctx *c, const char *key, const char *str, char *dst)
{
    size_t n = strlen(str);
    bool relative = n > 0 && str[0] != '/';
    size_t prefix = relative && c->base_dir ? c->base_len + 1 : 0;
    if (prefix + n + 1 > PELT_SCENE_PATH_MAX)
        return pelt__fail(c->err, PELT_ERR_FORMAT,
                          "%s: %s: path longer than %u bytes: \"%.40s...\"", c->name, key,
                          PELT_SCENE_PATH_MAX - 1, str);
    if (prefix) {
        memcpy(dst, c->base_dir, c->base_len);
        dst[c->base_len] = '/';
    }
    memcpy(dst + prefix, str, n + 1);
    return PELT_OK;
}

static pelt_status name_in(const ctx *c, const char *key, const cJSON *v,
                           const char *const *names, bool empty_ok, int *index)
{
    char expected[160] = "one of";
    for (size_t i = 0; names[i]; i++) {
        size_t used = strlen(expected);
        snprintf(expected + used, sizeof expected - used, "%s \"%s\"", i ? "," : "", names[i]);
    }
    if (!cJSON_IsString(v)) return bad(c, key, expected, v);
    if (empty_ok && v->valuestring[0] == '\0') {
        *index = -1;
        return PELT_OK;
    }
    for (int i = 0; names[i]; i++)
        if (strcmp(v->valuestring, names[i]) == 0) {
            *index = i;
            return PELT_OK;
        }
    return bad(c, key, expected, v);
}

static pelt_status walk_object(const ctx *c, const table *t, void *base, const cJSON *obj,
                               const char *prefix, const char *shown);

/* Reads an array of small objects (droplets, wind keys) described by `t`
 * into a new array of `elem_size` items, each starting as `init`. */
static pelt_status read_list(const ctx *c, const char *key, const cJSON *v, const table *t,
                             size_t elem_size, const void *init, const char *const *required,
                             size_t cap, void **out, size_t *out_count)
{
    if (!cJSON_IsArray(v)) return bad(c, key, "an array of objects", v);
    int n = cJSON_GetArraySize(v);
    if ((size_t)n > cap)
        return pelt__fail(c->err, PELT_ERR_FORMAT, "%s: %s: at most %zu entries, got %d",
                          c->name, key, cap, n);
    unsigned char *items = n ? pelt__calloc((size_t)n, elem_size) : NULL;
    if (n && !items)
        return pelt__fail(c->err, PELT_ERR_OUT_OF_MEMORY, "%s: %s: no memory for %d entries",
                          c->name, key, n);
    int i = 0;
    for (const cJSON *e = v->child; e; e = e->next, i++) {
        char sub[KEY_MAX + 16];
        snprintf(sub, sizeof sub, "%s[%d]", key, i);
        void *item = items + (size_t)i * elem_size;
        memcpy(item, init, elem_size);
        pelt_status st = PELT_OK;
        if (!cJSON_IsObject(e)) st = bad(c, sub, "an object", e);
        for (size_t r = 0; st == PELT_OK && required[r]; r++)
            if (!cJSON_GetObjectItemCaseSensitive(e, required[r]))
                st = pelt__fail(c->err, PELT_ERR_FORMAT, "%s: %s: missing key '%s'", c->name,
                                sub, required[r]);
        if (st == PELT_OK) st = walk_object(c, t, item, e, "", sub);
        if (st != PELT_OK) {
            free(items);
            return st;
        }
    }
    *out = items;
    *out_count = (size_t)n;
    return PELT_OK;
}

/* Applies one JSON value to the field `d` describes. `key` is the key as the
 * user sees it (for messages). Never frees what the field held before: the
 * callers own that decision (see pelt_scene_set). */
/* A K_PARAM row as the row of the library's table makes it: the field
 * inside the embedded desc, its kind, range and whether 0 means default. */
static bool resolve_param(const key_def *d, key_def *out)
{
    const pelt_param *p = d->lookup ? d->lookup(d->param) : NULL;
    if (!p) return false;
    *out = *d;
    out->off = d->off + p->offset;
    out->lo = p->min, out->hi = p->max, out->count = 0, out->names = NULL;
    out->flags = ((p->flags & PELT_PARAM_MIN_OPEN) ? F_LO_OPEN : 0u) | ((p->flags & PELT_PARAM_MAX_OPEN) ? F_HI_OPEN : 0u);
    bool zero_in_range = (p->flags & PELT_PARAM_MIN_OPEN) ? 0.0 > p->min : 0.0 >= p->min;
    if (pelt_param_zero_is_default(p) && !zero_in_range) out->flags |= F_ZERO_OK;
    switch (p->type) {
    case PELT_PARAM_UINT: out->k = K_UINT; break;
    case PELT_PARAM_SEED: out->k = K_U32; break;
    case PELT_PARAM_BOOL: out->k = K_BOOL; break;
    case PELT_PARAM_ENUM: out->k = K_ENUM, out->names = p->names; break;
    case PELT_PARAM_FLOAT:
        out->k = p->count > 1 ? K_VEC : K_FLOAT;
        out->count = p->count > 1 ? p->count : 0;
        break;
    }
    return true;
}

static pelt_status apply(const ctx *c, const key_def *d, void *base, const cJSON *v,
                         const char *key)
{
    key_def resolved;
    if (d->k == K_PARAM) {
        if (!resolve_param(d, &resolved))
            return pelt__fail(c->err, PELT_ERR_FORMAT, "%s: %s: the library has no parameter '%s'", c->name, key,
                              d->param);
        d = &resolved;
    }
    unsigned char *field = (unsigned char *)base + d->off;
    pelt_status st = PELT_OK;
    double x;
    int index;
    switch (d->k) {
    case K_UINT:
        if ((st = number(c, d, key, v, true, &x)) == PELT_OK) *(unsigned *)(void *)field = (unsigned)x;
        break;
    case K_BOOL:
        if (!cJSON_IsBool(v)) return bad(c, key, "true or false", v);
        *(bool *)(void *)field = cJSON_IsTrue(v);
        break;
    case K_NOT:
        if (!cJSON_IsBool(v)) return bad(c, key, "true or false", v);
        *(bool *)(void *)field = !cJSON_IsTrue(v);
        break;
    case K_U32:
        if ((st = number(c, d, key, v, true, &x)) == PELT_OK) *(uint32_t *)(void *)field = (uint32_t)x;
        break;
    case K_FLOAT:
        if ((st = number(c, d, key, v, false, &x)) == PELT_OK) *(float *)(void *)field = (float)x;
        break;
    case K_VEC:
        st = numbers(c, d, key, v, d->count, (float *)(void *)field);
        break;
    case K_RANGE: {
        float mm[2];
        if ((st = numbers(c, d, key, v, 2, mm)) != PELT_OK) break;
        if (mm[0] > mm[1]) return bad(c, key, "[min, max] with min <= max", v);
        *(float *)(void *)field = mm[0];
        *(float *)(void *)((unsigned char *)base + d->off2) = mm[1];
        break;
    }
    case K_NAME: {
        char *out = (char *)field;
        if (cJSON_IsNumber(v) && v->valuedouble >= 0.0 && v->valuedouble < 1e9 &&
            v->valuedouble == (double)(long)v->valuedouble) {
            snprintf(out, PELT_ANIMATION_NAME_MAX, "%ld", (long)v->valuedouble);
        } else if (cJSON_IsString(v) && strlen(v->valuestring) < PELT_ANIMATION_NAME_MAX) {
            memcpy(out, v->valuestring, strlen(v->valuestring) + 1);
        } else {
            return bad(c, key, "an animation's name (a string under 64 bytes) or index (an integer >= 0)", v);
        }
        break;
    }
    case K_PATH:
        if (!cJSON_IsString(v)) return bad(c, key, "a file path (string)", v);
        st = store_path(c, key, v->valuestring, (char *)field);
        break;
    case K_ENUM:
        if ((st = name_in(c, key, v, d->names, false, &index)) == PELT_OK)
            memcpy(field, &index, sizeof index);
        break;
    case K_PRESET: {
        /* "" clears it; a name (or its second spelling) is stored as the
           one name pelt_curl_preset_names gives it. */
        if (cJSON_IsString(v) && v->valuestring[0] == '\0') {
            ((char *)field)[0] = '\0';
            break;
        }
        index = cJSON_IsString(v) ? pelt_curl_preset_index(v->valuestring) : -1;
        if (index < 0 && (st = name_in(c, key, v, pelt_curl_preset_names, true, &index)) != PELT_OK) break;
        if (index < 0) {
            ((char *)field)[0] = '\0';
            break;
        }
        snprintf((char *)field, PELT_SCENE_NAME_MAX, "%s", pelt_curl_preset_names[index]);
        break;
    }
    case K_PARAM: /* resolved above */
        break;
    case K_DROPLETS: {
        static const char *const required[] = {"center", "radius", NULL};
        const pelt_droplet init = {{0, 0}, 0, 1.0f};
        void *items = NULL;
        size_t n = 0;
        st = read_list(c, key, v, &pelt__droplet_key_table, sizeof(pelt_droplet), &init, required,
                       PELT_SCENE_MAX_DROPLETS, &items, &n);
        if (st != PELT_OK) break;
        memcpy(field, &items, sizeof items);
        memcpy((unsigned char *)base + d->off2, &n, sizeof n);
        break;
    }
    case K_WINDKEYS: {
        static const char *const required[] = {"time", "wind", NULL};
        const pelt_wind_key init = {0, {0, 0, 0}};
        void *items = NULL;
        size_t n = 0;
        st = read_list(c, key, v, &pelt__wind_key_table, sizeof(pelt_wind_key), &init, required,
                       PELT_SCENE_MAX_WIND_KEYS, &items, &n);
        if (st != PELT_OK) break;
        const pelt_wind_key *keys = items;
        for (size_t i = 1; i < n; i++)
            if (!(keys[i].time > keys[i - 1].time)) {
                st = pelt__fail(c->err, PELT_ERR_FORMAT,
                                "%s: %s[%zu].time: expected times in increasing order, "
                                "got %g after %g",
                                c->name, key, i, (double)keys[i].time,
                                (double)keys[i - 1].time);
                free(items);
                return st;
            }
        memcpy(field, &items, sizeof items);
        memcpy((unsigned char *)base + d->off2, &n, sizeof n);
        break;
    }
    case K_STROKES: {
        static const char *const required[] = {"tool", "radius", NULL};
        pelt_scene_stroke init;
        memset(&init, 0, sizeof init);
        init.at[0] = init.at[1] = init.at[2] = NAN;
        init.brush.strength = 1.0f;
        void *items = NULL;
        size_t n = 0;
        st = read_list(c, key, v, &pelt__stroke_key_table, sizeof(pelt_scene_stroke), &init, required,
                       PELT_SCENE_MAX_STROKES, &items, &n);
        if (st != PELT_OK) break;
        /* Where it lands: a pixel or a point, exactly one of them. */
        size_t i = 0;
        for (const cJSON *e = v->child; e; e = e->next, i++) {
            bool px = cJSON_GetObjectItemCaseSensitive(e, "pixel") != NULL;
            bool at = cJSON_GetObjectItemCaseSensitive(e, "at") != NULL;
            if (px != at) continue;
            free(items);
            return pelt__fail(c->err, PELT_ERR_FORMAT, "%s: %s[%zu]: give either 'pixel' or 'at'%s",
                              c->name, key, i, px ? ", not both" : "");
        }
        memcpy(field, &items, sizeof items);
        memcpy((unsigned char *)base + d->off2, &n, sizeof n);
        break;
    }
    }
    return st;
}

/* Keys whose values exclude each other: a mesh file or a procedural shape,
 * an image or a pattern. Setting one clears the other. */
static void fixup(const key_def *d, pelt_scene *s)
{
    if (strcmp(d->path, "mesh.file") == 0 && s->mesh.file[0]) s->mesh.shape = PELT_SHAPE_FILE;
    if (strcmp(d->path, "mesh.shape") == 0 && s->mesh.shape != PELT_SHAPE_FILE) s->mesh.file[0] = '\0';
    if (strcmp(d->path, "texture.image") == 0 && s->texture.image[0]) s->texture.pattern = PELT_COLOR_PATTERN_NONE;
    if (strcmp(d->path, "texture.pattern") == 0 && s->texture.pattern != PELT_COLOR_PATTERN_NONE)
        s->texture.image[0] = '\0';
}

static const key_def *find(const table *t, const char *path)
{
    for (size_t i = 0; i < t->count; i++)
        if (strcmp(t->keys[i].path, path) == 0) return &t->keys[i];
    return NULL;
}

/* True when `path` names a group of keys ("fur", "animation.shake"). */
static bool is_group(const table *t, const char *path)
{
    size_t n = strlen(path);
    for (size_t i = 0; i < t->count; i++)
        if (strncmp(t->keys[i].path, path, n) == 0 && t->keys[i].path[n] == '.') return true;
    return false;
}

/* Levenshtein distance, for "did you mean". */
static size_t edit_distance(const char *a, const char *b)
{
    size_t na = strlen(a), nb = strlen(b);
    if (na > KEY_MAX || nb > KEY_MAX) return (size_t)-1;
    size_t row[KEY_MAX + 1];
    for (size_t j = 0; j <= nb; j++) row[j] = j;
    for (size_t i = 1; i <= na; i++) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= nb; j++) {
            size_t up = row[j];
            size_t best = diag + (a[i - 1] != b[j - 1]);
            if (up + 1 < best) best = up + 1;
            if (row[j - 1] + 1 < best) best = row[j - 1] + 1;
            row[j] = best;
            diag = up;
        }
    }
    return row[nb];
}

/* The known key or group nearest to `path`, if it is close; else "". */
static void nearest(const table *t, const char *path, char *out, size_t size)
{
    size_t best = (size_t)-1;
    out[0] = '\0';
    for (size_t i = 0; i < t->count; i++) {
        const char *k = t->keys[i].path;
        /* the key itself and each group above it */
        for (size_t n = 1; n <= strlen(k); n++) {
            if (k[n] != '.' && k[n] != '\0') continue;
            char cand[KEY_MAX];
            if (n >= sizeof cand) continue;
            memcpy(cand, k, n);
            cand[n] = '\0';
            size_t dist = edit_distance(path, cand);
            if (dist < best) {
                best = dist;
                snprintf(out, size, "%s", cand);
            }
        }
    }
    size_t len = strlen(path);
    size_t allowed = len / 3 > 2 ? len / 3 : 2;
    if (best == 0 || best > allowed) out[0] = '\0';
}

static bool join(char *out, size_t size, const char *prefix, const char *name)
{
    int n = snprintf(out, size, "%s%s%s", prefix, prefix[0] ? "." : "", name);
    return n >= 0 && (size_t)n < size;
}

static pelt_status unknown_key(const ctx *c, const table *t, const char *path,
                               const char *prefix, const char *shown, const char *shown_key)
{
    char near[KEY_MAX], near_shown[2 * KEY_MAX];
    nearest(t, path, near, sizeof near);
    if (!near[0])
        return pelt__fail(c->err, PELT_ERR_FORMAT, "%s: unknown key '%s'", c->name, shown_key);
    /* In a list item the table's keys are relative to the item. */
    if (strcmp(prefix, shown) == 0) snprintf(near_shown, sizeof near_shown, "%s", near);
    else snprintf(near_shown, sizeof near_shown, "%s.%s", shown, near);
    return pelt__fail(c->err, PELT_ERR_FORMAT, "%s: unknown key '%s' (did you mean '%s'?)",
                      c->name, shown_key, near_shown);
}

/* One value at `path` (a key or a group) applied to the scene or item. */
static pelt_status apply_path(const ctx *c, const table *t, void *base, const cJSON *v,
                              const char *path, const char *prefix, const char *shown,
                              const char *shown_key)
{
    const key_def *d = find(t, path);
    if (d) {
        pelt_status st = apply(c, d, base, v, shown_key);
        if (st == PELT_OK && t == &pelt__scene_key_table) fixup(d, base);
        return st;
    }
    if (is_group(t, path)) {
        if (cJSON_IsObject(v)) return walk_object(c, t, base, v, path, shown_key);
        /* "mesh": "bunny.off" is short for "mesh": {"file": "bunny.off"} */
        char file_key[KEY_MAX];
        if (cJSON_IsString(v) && join(file_key, sizeof file_key, path, "file") &&
            (d = find(t, file_key)) != NULL) {
            pelt_status st = apply(c, d, base, v, shown_key);
            if (st == PELT_OK && t == &pelt__scene_key_table) fixup(d, base);
            return st;
        }
        return bad(c, shown_key, "an object", v);
    }
    return unknown_key(c, t, path, prefix, shown, shown_key);
}

static pelt_status walk_object(const ctx *c, const table *t, void *base, const cJSON *obj,
                               const char *prefix, const char *shown)
{
    for (const cJSON *m = obj->child; m; m = m->next) {
        const char *name = m->string ? m->string : "";
        char path[KEY_MAX], shown_key[2 * KEY_MAX];
        bool fits = join(path, sizeof path, prefix, name);
        join(shown_key, sizeof shown_key, shown, name);
        if (name[0] == '_') continue; /* "_comment" and the like */
        for (const cJSON *p = obj->child; p != m; p = p->next)
            if (p->string && strcmp(p->string, name) == 0)
                return pelt__fail(c->err, PELT_ERR_FORMAT, "%s: duplicate key '%s'", c->name,
                                  shown_key);
        if (!fits)
            return pelt__fail(c->err, PELT_ERR_FORMAT, "%s: unknown key '%s'", c->name, shown_key);
        pelt_status st = apply_path(c, t, base, m, path, prefix, shown, shown_key);
        if (st != PELT_OK) return st;
    }
    return PELT_OK;
}

/* Checks that need more than one key. */
static pelt_status validate(const ctx *c, const pelt_scene *s)
{
    if (s->mesh.shape == PELT_SHAPE_FILE && s->mesh.file[0] == '\0')
        return pelt__fail(c->err, PELT_ERR_FORMAT,
                          "%s: mesh.file: needed when mesh.shape is \"file\"", c->name);
    if (s->wetness.rain_stop != 0.0f && !(s->wetness.rain_stop > s->wetness.rain_start))
        return pelt__fail(c->err, PELT_ERR_FORMAT,
                          "%s: wetness.rain.stop: expected 0 (never) or a time after "
                          "wetness.rain.start (%g), got %g",
                          c->name, (double)s->wetness.rain_start, (double)s->wetness.rain_stop);
    return PELT_OK;
}

/* In one file, a mesh file beside a procedural shape (or an image beside a
 * pattern) is a contradiction, not an override. */
static pelt_status check_exclusive(const ctx *c, const cJSON *root, const char *group,
                                   const char *a, const char *b, const char *b_ok)
{
    const cJSON *g = cJSON_GetObjectItemCaseSensitive(root, group);
    if (!cJSON_IsObject(g)) return PELT_OK;
    const cJSON *va = cJSON_GetObjectItemCaseSensitive(g, a);
    const cJSON *vb = cJSON_GetObjectItemCaseSensitive(g, b);
    if (cJSON_IsString(va) && va->valuestring[0] && cJSON_IsString(vb) &&
        strcmp(vb->valuestring, b_ok) != 0)
        return pelt__fail(c->err, PELT_ERR_FORMAT,
                          "%s: %s: give either %s.%s or %s.%s, not both", c->name, group,
                          group, a, group, b);
    return PELT_OK;
}

static bool is_space(char ch) { return ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r'; }

/* cJSON points just past the offending token, often at the whitespace after
 * it: step back to the token, then show its line around it. */
static pelt_status syntax_error(const ctx *c, const char *text, const char *at)
{
    if (!at) return pelt__fail(c->err, PELT_ERR_FORMAT, "%s: JSON syntax error", c->name);
    const char *rest = at;
    while (is_space(*rest)) rest++;
    bool at_end = *rest == '\0';
    const char *q = at;
    while (q > text && (*q == '\0' || is_space(*q))) q--;
    size_t line = 1;
    for (const char *p = text; p < q; p++) line += *p == '\n';

    const char *from = q, *to = q;
    while (from > text && q - from < 20 && from[-1] != '\n' && from[-1] != '\r') from--;
    while (is_space(*from) && from < q) from++;
    while (*to && *to != '\n' && *to != '\r' && to - q < 20) to++;
    char near[48];
    size_t n = (size_t)(to - from) < sizeof near - 1 ? (size_t)(to - from) : sizeof near - 1;
    memcpy(near, from, n);
    near[n] = '\0';
    return pelt__fail(c->err, PELT_ERR_FORMAT, "%s: line %zu: JSON syntax error near '%s'%s",
                      c->name, line, near, at_end ? " (unexpected end of the file)" : "");
}

static pelt_status parse_into(const ctx *c, const char *text, pelt_scene *s)
{
    if (strncmp(text, "\xEF\xBB\xBF", 3) == 0) text += 3; /* UTF-8 byte order mark */
    const char *p = text;
    while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r') p++;
    if (*p == '\0') return pelt__fail(c->err, PELT_ERR_FORMAT, "%s: empty file", c->name);

    const char *end = NULL;
    cJSON *root = cJSON_ParseWithOpts(text, &end, 1);
    if (!root) return syntax_error(c, text, end);
    pelt_status st = PELT_OK;
    if (!cJSON_IsObject(root))
        st = bad(c, "top level", "an object {...}", root);
    if (st == PELT_OK) st = check_exclusive(c, root, "mesh", "file", "shape", "file");
    if (st == PELT_OK) st = check_exclusive(c, root, "texture", "image", "pattern", "none");
    if (st == PELT_OK) st = walk_object(c, &pelt__scene_key_table, s, root, "", "");
    if (st == PELT_OK) st = validate(c, s);
    cJSON_Delete(root);
    return st;
}

pelt_status pelt_scene_parse(const char *json_text, const char *name_for_errors,
                             pelt_scene *s, pelt_error *err)
{
    if (!s) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_scene_parse: no scene");
    pelt_scene_defaults(s);
    ctx c = {name_for_errors ? name_for_errors : "scene", NULL, 0, err};
    if (!json_text)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "%s: no text", c.name);
    const char *slash = name_for_errors ? strrchr(name_for_errors, '/') : NULL;
    if (slash) {
        c.base_dir = name_for_errors;
        c.base_len = (size_t)(slash - name_for_errors);
    }
    pelt_scene tmp;
    pelt_scene_defaults(&tmp);
    pelt_status st = parse_into(&c, json_text, &tmp);
    if (st != PELT_OK) {
        pelt_scene_free(&tmp);
        return st;
    }
    *s = tmp;
    return PELT_OK;
}

pelt_status pelt_scene_load(const char *path, pelt_scene *s, pelt_error *err)
{
    if (!s) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_scene_load: no scene");
    pelt_scene_defaults(s);
    if (!path || !path[0])
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_scene_load: no file name");
    FILE *f = fopen(path, "rb");
    if (!f) return pelt__fail(err, PELT_ERR_IO, "%s: cannot open: %s", path, strerror(errno));

    /* Read in growing chunks (works for pipes too), never past the cap. */
    size_t cap = 0, len = 0;
    char *buf = NULL;
    pelt_status st = PELT_OK;
    for (;;) {
        if (len == cap) {
            if (cap > PELT_SCENE_FILE_MAX) {
                st = pelt__fail(err, PELT_ERR_IO, "%s: larger than %u MiB, refused", path,
                                PELT_SCENE_FILE_MAX >> 20);
                break;
            }
            size_t next = cap ? cap * 2 : 65536;
            char *grown = realloc(buf, next + 1);
            if (!grown) {
                st = pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: no memory to read it", path);
                break;
            }
            buf = grown;
            cap = next;
        }
        size_t got = fread(buf + len, 1, cap - len, f);
        len += got;
        if (got == 0) {
            if (ferror(f))
                st = pelt__fail(err, PELT_ERR_IO, "%s: cannot read: %s", path, strerror(errno));
            break;
        }
    }
    fclose(f);
    if (st == PELT_OK && len > PELT_SCENE_FILE_MAX)
        st = pelt__fail(err, PELT_ERR_IO, "%s: larger than %u MiB, refused", path,
                        PELT_SCENE_FILE_MAX >> 20);
    if (st == PELT_OK && len == 0) st = pelt__fail(err, PELT_ERR_FORMAT, "%s: empty file", path);
    if (st == PELT_OK && memchr(buf, '\0', len))
        st = pelt__fail(err, PELT_ERR_FORMAT, "%s: holds a NUL byte: not a JSON text file", path);
    if (st == PELT_OK) {
        buf[len] = '\0';
        st = pelt_scene_parse(buf, path, s, err);
    }
    free(buf);
    return st;
}

pelt_status pelt_scene_set(pelt_scene *s, const char *key_path, const char *value,
                           pelt_error *err)
{
    if (!s || !key_path || !value)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "--set: needs KEY=VALUE");
    ctx c = {"--set", NULL, 0, err};
    if (strlen(key_path) >= KEY_MAX)
        return pelt__fail(err, PELT_ERR_FORMAT, "--set: unknown key '%.64s...'", key_path);

    /* JSON when it parses as JSON, else the bare string (a path, a name).
       Keys that only take strings always get one: a file may be named 123. */
    const key_def *d = find(&pelt__scene_key_table, key_path);
    key_def resolved;
    if (d && d->k == K_PARAM && resolve_param(d, &resolved)) d = &resolved;
    bool string_only = d ? (d->k == K_PATH || d->k == K_ENUM || d->k == K_PRESET)
                         : (is_group(&pelt__scene_key_table, key_path) && value[0] != '{');
    cJSON *v = cJSON_Parse(value);
    if (v && string_only && !cJSON_IsString(v)) {
        cJSON_Delete(v);
        v = NULL;
    }
    if (!v) v = cJSON_CreateString(value);
    if (!v) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "--set %s: no memory", key_path);

    pelt_scene tmp = *s;
    pelt_status st = apply_path(&c, &pelt__scene_key_table, &tmp, v, key_path, "", "", key_path);
    if (st == PELT_OK) st = validate(&c, &tmp);
    cJSON_Delete(v);

    /* Arrays replaced in tmp are new; free whichever side loses. */
    if (st == PELT_OK) {
        if (tmp.wetness.droplets != s->wetness.droplets) free(s->wetness.droplets);
        if (tmp.animation.wind_keys != s->animation.wind_keys) free(s->animation.wind_keys);
        if (tmp.groom.strokes != s->groom.strokes) free(s->groom.strokes);
        *s = tmp;
    } else {
        if (tmp.wetness.droplets != s->wetness.droplets) free(tmp.wetness.droplets);
        if (tmp.animation.wind_keys != s->animation.wind_keys) free(tmp.animation.wind_keys);
        if (tmp.groom.strokes != s->groom.strokes) free(tmp.groom.strokes);
    }
    return st;
}

const char *pelt_scene_key_name(size_t i)
{
    return i < pelt__scene_key_table.count ? pelt__scene_key_table.keys[i].path : NULL;
}
