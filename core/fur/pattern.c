/* Procedural colour patterns for the fur (multiplied with the hair colour):
 * tileable, seeded, white where the colour is unchanged. */
#include "core/fur/fur_internal.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/noise.h"
#include "core/base/vec.h"

#include <stdlib.h>

pelt_status pelt_fur_set_color_pattern(pelt_fur *fur, pelt_color_pattern pattern, uint32_t seed,
                                       pelt_error *err)
{
    enum { SIZE = 512, PERIOD = 8 };
    if (pattern == PELT_COLOR_PATTERN_NONE) {
        static const uint8_t white[4] = {255, 255, 255, 255};
        return pelt_fur_set_color_texture(fur, white, 1, 1, err);
    }
    if (pattern < PELT_COLOR_PATTERN_NONE || pattern > PELT_COLOR_PATTERN_NOISE)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "unknown colour pattern %d", (int)pattern);
    const pelt_allocator *a = &fur->desc.hooks.allocator;
    uint8_t *rgba = pelt__alloc(a, (size_t)SIZE * SIZE * 4);
    if (!rgba) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for a colour pattern");
    const uint32_t noise_seed = seed ^ 0x70617474u; /* "patt": unlike the gusts of the same seed */
    for (int y = 0; y < SIZE; y++)
        for (int x = 0; x < SIZE; x++) {
            float u = (float)x / SIZE, v = (float)y / SIZE;
            /* Three octaves of tileable value noise in [0, 1]: periods 8,
             * 16, 32 over the texture, octave o on lattice slice o. */
            float n = 0.0f, amp = 0.5f;
            for (int o = 0; o < 3; o++) {
                int period = PERIOD << o;
                const float at[2] = {u * (float)period, v * (float)period};
                float octave = 0.5f + 0.5f * pelt__value_noise(noise_seed, 2, at, o, period).x;
                n += amp * octave;
                amp *= 0.5f;
            }
            n /= 0.875f;
            float k; /* brightness multiplier */
            switch (pattern) {
            case PELT_COLOR_PATTERN_SPOTS:
                /* Dark blotches where the noise is high: a leopard-ish coat. */
                k = 1.0f - 0.8f * clampf((n - 0.58f) * 8.0f, 0.0f, 1.0f);
                break;
            case PELT_COLOR_PATTERN_STRIPES: {
                /* Bands along v, wobbled by the noise: a tabby's stripes. */
                float s = sinf(6.2831853f * (4.0f * u + 0.6f * n));
                k = 1.0f - 0.75f * clampf((s - 0.3f) * 3.0f, 0.0f, 1.0f);
                break;
            }
            default:
                k = 0.65f + 0.35f * n;
                break;
            }
            uint8_t c = (uint8_t)(clampf(k, 0.0f, 1.0f) * 255.0f + 0.5f);
            uint8_t *p = rgba + ((size_t)y * SIZE + (size_t)x) * 4;
            p[0] = p[1] = p[2] = c;
            p[3] = 255;
        }
    pelt_status st = pelt_fur_set_color_texture(fur, rgba, SIZE, SIZE, err);
    pelt__free(a, rgba);
    return st;
}
