/* Welding of vertices by exact position (and normal): one open-addressing
 * hash pass, see weld.h (Lengyel et al. 2001 §2, crack-free shells). */
#include "core/base/weld.h"

#include <stdlib.h>
#include <string.h>

/* The bits of a key component, with -0 folded into +0 so equal floats hash
 * alike. */
static uint32_t key_bits(float f)
{
    if (f == 0.0f) f = 0.0f;
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

static uint64_t mix(uint64_t h, float f)
{
    h ^= key_bits(f);
    h *= 0x100000001b3ULL;
    return h ^ (h >> 29);
}

static uint64_t key_hash(const float *p, const float *n)
{
    uint64_t h = 0xcbf29ce484222325ULL;
    for (int k = 0; k < 3; k++) h = mix(h, p[k]);
    if (n)
        for (int k = 0; k < 3; k++) h = mix(h, n[k]);
    /* Final avalanche (MurmurHash3 fmix64): the table index is the low bits. */
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    return h;
}

static bool same3(const float *a, const float *b)
{
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

bool pelt__weld(const float *positions, const float *normals, size_t count, uint32_t *canon)
{
    if (count > (size_t)UINT32_MAX) return false;
    size_t cap = 16;
    while (cap < 2 * count) {
        if (cap > SIZE_MAX / 2 / sizeof(uint32_t)) return false;
        cap *= 2;
    }
    uint32_t *slot = malloc(cap * sizeof *slot); /* a vertex index or PELT__WELD_NONE */
    if (!slot) return false;
    memset(slot, 0xff, cap * sizeof *slot);
    /* Vertices in ascending order: the first to claim a key is the smallest. */
    for (size_t v = 0; v < count; v++) {
        const float *p = positions + 3 * v, *n = normals ? normals + 3 * v : NULL;
        size_t s = (size_t)key_hash(p, n) & (cap - 1);
        for (;;) {
            uint32_t o = slot[s];
            if (o == PELT__WELD_NONE) {
                slot[s] = (uint32_t)v;
                canon[v] = (uint32_t)v;
                break;
            }
            if (same3(positions + 3 * (size_t)o, p) && (!n || same3(normals + 3 * (size_t)o, n))) {
                canon[v] = o;
                break;
            }
            s = (s + 1) & (cap - 1);
        }
    }
    free(slot);
    return true;
}

size_t pelt__weld_ids(const uint32_t *canon, size_t count, uint32_t *ids)
{
    size_t groups = 0;
    for (size_t i = 0; i < count; i++) {
        uint32_t c = canon[i]; /* read before ids[i] is written: ids may be canon */
        ids[i] = c == i ? (uint32_t)groups++ : ids[c];
    }
    return groups;
}

void pelt__weld_chain(const uint32_t *canon, size_t count, uint32_t *next)
{
    for (size_t i = 0; i < count; i++) next[i] = PELT__WELD_NONE;
    /* Inserting right after the group's head, largest first, leaves each
     * chain in ascending order. */
    for (size_t i = count; i-- > 0;) {
        uint32_t c = canon[i];
        if (c == i) continue;
        next[i] = next[c];
        next[c] = (uint32_t)i;
    }
}
