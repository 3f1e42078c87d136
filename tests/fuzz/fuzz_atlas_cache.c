/* Fuzz target: atlas cache files (pelt__atlas_cache_load_memory, which the
 * file loader calls). The key and input counts are taken from the header
 * itself, so a mutated file reaches the checks behind them; each input is
 * read twice, as it is and with its checksum made right, so the checks
 * behind the checksum are fuzzed too. */
#include "core/atlas/atlas_cache.h"

#include <stdlib.h>
#include <string.h>

static uint64_t u64_at(const uint8_t *data, size_t size, size_t at)
{
    uint64_t v = 0;
    if (size >= at + 8) memcpy(&v, data + at, 8);
    return v;
}

static void load(const uint8_t *data, size_t size)
{
    uint64_t key = u64_at(data, size, PELT__ATLAS_CACHE_KEY_AT);
    uint64_t in_v = u64_at(data, size, PELT__ATLAS_CACHE_KEY_AT + 8);
    uint64_t in_t = u64_at(data, size, PELT__ATLAS_CACHE_KEY_AT + 16);
    /* The real loader is given the counts of a mesh that exists. */
    if (in_v > (1u << 20) || in_t > (1u << 20)) in_v = in_t = 1u << 20;
    pelt__atlas_record r;
    char why[128];
    if (pelt__atlas_cache_load_memory(data, size, key, in_v, in_t, &r, why, sizeof why)) {
        /* Everything a load accepts is in range. */
        for (size_t i = 0; i < 3 * r.triangle_count; i++)
            if (r.indices[i] >= r.vertex_count) abort();
        pelt__atlas_record_free(&r);
    } else if (!why[0]) {
        abort(); /* a rejected file always says why */
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    load(data, size);
    if (size > 8) {
        uint8_t *fixed = malloc(size);
        if (!fixed) return 0;
        memcpy(fixed, data, size);
        pelt__atlas_hash s = pelt__atlas_hash_begin();
        pelt__atlas_hash_bytes(&s, fixed, size - 8);
        memcpy(fixed + size - 8, &s.h, 8);
        load(fixed, size);
        free(fixed);
    }
    return 0;
}
