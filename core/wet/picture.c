/* The wetness mask as an RGBA8 picture (Silva et al. Fig. 11 insets). */
#include "core/wet/picture.h"

#include "core/base/vec.h"

#include <math.h>

void pelt__wetness_to_rgba8(const pelt__wetness *m, uint8_t *rgba)
{
    unsigned W = m->width, H = m->height;
    for (unsigned j = 0; j < H; j++) {
        const float *row = m->texels + (size_t)j * W * 4;
        uint8_t *out = rgba + (size_t)(H - 1 - j) * W * 4;
        float v = ((float)j + 0.5f) / (float)H;
        for (unsigned i = 0; i < W; i++) {
            const float *t = row + (size_t)i * 4;
            uint8_t *o = out + (size_t)i * 4;
            o[0] = o[1] = o[2] = 0;
            o[3] = 255;
            if (!(t[3] > 0.0f)) continue;
            float u = ((float)i + 0.5f) / (float)W;
            float dist = t[2] > 0.0f ? hypotf(u - t[0], v - t[1]) / t[2] : 0.0f;
            float shade = 1.0f - 0.4f * clampf(dist, 0.0f, 1.0f);
            o[2] = (uint8_t)lroundf(255.0f * clampf(t[3], 0.0f, 1.0f) * shade);
        }
    }
}
