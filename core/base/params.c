/* Defaults and range checks driven by a desc's rows (pelt/params.h), for
 * every desc that has rows: the fur's (core/fur/fur_params.c) and the
 * atlas's (core/atlas/atlas_params.c). */
#include "core/base/params.h"

#include "core/base/error.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#define FMAX ((double)FLT_MAX)

const pelt_param *pelt__params_find(const pelt_param *rows, size_t count, const char *name)
{
    for (size_t i = 0; name && i < count; i++)
        if (strcmp(rows[i].name, name) == 0) return &rows[i];
    return NULL;
}

bool pelt_param_zero_is_default(const pelt_param *p)
{
    return p->derived || p->def[0] != 0.0 || p->def[1] != 0.0 || p->def[2] != 0.0;
}

/* A field's values as doubles (count of them). */
static unsigned read_values(const pelt_param *p, const void *desc, double v[3])
{
    const unsigned char *f = (const unsigned char *)desc + p->offset;
    switch (p->type) {
    case PELT_PARAM_UINT: v[0] = *(const unsigned *)(const void *)f; return 1;
    case PELT_PARAM_SEED: v[0] = *(const uint32_t *)(const void *)f; return 1;
    case PELT_PARAM_ENUM: v[0] = *(const int *)(const void *)f; return 1;
    case PELT_PARAM_BOOL: v[0] = *(const bool *)(const void *)f; return 1;
    case PELT_PARAM_FLOAT:
        for (unsigned k = 0; k < p->count; k++) v[k] = ((const float *)(const void *)f)[k];
        return p->count;
    }
    return 0;
}

void pelt__params_defaults(const pelt_param *rows, size_t count, void *desc)
{
    for (size_t i = 0; i < count; i++) {
        const pelt_param *p = &rows[i];
        if (p->derived || !pelt_param_zero_is_default(p)) continue;
        double v[3] = {0, 0, 0};
        unsigned n = read_values(p, desc, v);
        bool zero = true;
        for (unsigned k = 0; k < n; k++) zero = zero && v[k] == 0.0;
        if (!zero) continue;
        unsigned char *f = (unsigned char *)desc + p->offset;
        if (p->type == PELT_PARAM_UINT) *(unsigned *)(void *)f = (unsigned)p->def[0];
        else if (p->type == PELT_PARAM_SEED) *(uint32_t *)(void *)f = (uint32_t)p->def[0];
        else if (p->type == PELT_PARAM_FLOAT)
            for (unsigned k = 0; k < n; k++) ((float *)(void *)f)[k] = (float)p->def[k];
    }
}

bool pelt__param_in_range(const pelt_param *p, double x)
{
    if (!isfinite(x)) return false;
    if (p->type == PELT_PARAM_ENUM) {
        int n = 0;
        while (p->names[n]) n++;
        return x >= 0 && x < n;
    }
    if (p->type == PELT_PARAM_BOOL) return true;
    if ((p->flags & PELT_PARAM_MIN_OPEN) ? !(x > p->min) : !(x >= p->min)) return false;
    if ((p->flags & PELT_PARAM_MAX_OPEN) ? !(x < p->max) : !(x <= p->max)) return false;
    return true;
}

void pelt__param_range_text(const pelt_param *p, char *buf, size_t size)
{
    if (p->type == PELT_PARAM_ENUM) {
        size_t at = 0;
        buf[0] = '\0';
        for (int i = 0; p->names[i] && at < size; i++)
            at += (size_t)snprintf(buf + at, size - at, "%s%s", i ? ", " : "one of ", p->names[i]);
        return;
    }
    bool integer = p->type != PELT_PARAM_FLOAT;
    const char *what = integer ? "an integer" : "a number";
    char lo[32], hi[32];
    snprintf(lo, sizeof lo, "%g", p->min);
    snprintf(hi, sizeof hi, "%g", p->max);
    if (p->min <= -FMAX && p->max >= FMAX) snprintf(buf, size, "a finite number");
    else if (p->max >= FMAX)
        snprintf(buf, size, "%s %s %s", what, (p->flags & PELT_PARAM_MIN_OPEN) ? ">" : ">=", lo);
    else
        snprintf(buf, size, "%s in %c%s, %s%c", what, (p->flags & PELT_PARAM_MIN_OPEN) ? '(' : '[', lo, hi,
                 (p->flags & PELT_PARAM_MAX_OPEN) ? ')' : ']');
}

pelt_status pelt__params_check(const pelt_param *rows, size_t count, const void *desc, const char *what,
                               pelt_error *err)
{
    for (size_t i = 0; i < count; i++) {
        const pelt_param *p = &rows[i];
        double v[3] = {0, 0, 0};
        unsigned n = read_values(p, desc, v);
        for (unsigned k = 0; k < n; k++) {
            if (pelt__param_in_range(p, v[k])) continue;
            char range[160];
            pelt__param_range_text(p, range, sizeof range);
            if (n > 1)
                return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "%s %s[%u] must be %s, got %g", what, p->name, k,
                                  range, v[k]);
            return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "%s %s must be %s, got %g", what, p->name, range, v[k]);
        }
    }
    return PELT_OK;
}
