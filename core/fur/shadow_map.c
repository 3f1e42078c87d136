/* Deep opacity maps: the C references (core/fur/shadow_map.h). */
#include "core/fur/shadow_map.h"

#include "core/base/vec.h"

#include <math.h>
#include <string.h>


float pelt__shadow_slice_weight(float k, unsigned j, unsigned slices)
{
    if (j + 1 >= slices) return 1.0f;
    return clampf((float)(j + 1) - k, 0.0f, 1.0f);
}

float pelt__shadow_sigma(float alpha)
{
    return -logf(1.0f - clampf(alpha, 0.0f, 0.98f));
}

float pelt__shadow_opacity(const float sum[PELT_SHADOW_MAX_SLICES], unsigned slices, float k)
{
    if (slices == 0) return 0.0f;
    if (slices > PELT_SHADOW_MAX_SLICES) slices = PELT_SHADOW_MAX_SLICES;
    float x = clampf(k, 0.0f, (float)slices);
    unsigned i = (unsigned)floorf(x); /* between position i and i + 1 */
    if (i >= slices) return sum[slices - 1];
    float below = i == 0 ? 0.0f : sum[i - 1];
    return below + (sum[i] - below) * (x - (float)i);
}

float pelt__shadow_transmittance(float opacity, float density)
{
    return expf(-density * opacity);
}

void pelt__shadow_light_frame(const float center[3], float radius, const float light_dir[3],
                              float depth_range, float tex[16], float clip[16])
{
    pelt_vec3 l = v3_norm_or(v3_load(light_dir), v3(0.0f, 1.0f, 0.0f));
    /* Any up that is not along l: the right-handed frame (x, y, l) of a
       camera looking along -l. */
    pelt_vec3 helper = fabsf(l.y) < 0.9f ? v3(0.0f, 1.0f, 0.0f) : v3(1.0f, 0.0f, 0.0f);
    pelt_vec3 x = v3_norm_or(v3_cross(helper, l), v3(1.0f, 0.0f, 0.0f));
    pelt_vec3 y = v3_cross(l, x);
    pelt_vec3 c = v3_load(center);
    float r = radius > 0.0f ? radius : 1.0f;
    float depth = r * (1.0f + (depth_range > 0.0f ? depth_range : 1.0f));
    /* s = 0.5 + x.(p - c) / 2r, t likewise, d = (r - l.(p - c)) / depth. */
    const float row[3][4] = {
        {x.x / (2 * r), x.y / (2 * r), x.z / (2 * r), 0.5f - v3_dot(x, c) / (2 * r)},
        {y.x / (2 * r), y.y / (2 * r), y.z / (2 * r), 0.5f - v3_dot(y, c) / (2 * r)},
        {-l.x / depth, -l.y / depth, -l.z / depth, (r + v3_dot(l, c)) / depth}};
    memset(tex, 0, 16 * sizeof *tex);
    for (int i = 0; i < 3; i++)
        for (int col = 0; col < 4; col++) tex[4 * col + i] = row[i][col];
    tex[15] = 1.0f;
    for (int col = 0; col < 4; col++) {
        for (int i = 0; i < 3; i++) clip[4 * col + i] = 2.0f * tex[4 * col + i] - (col == 3 ? 1.0f : 0.0f);
        clip[4 * col + 3] = tex[4 * col + 3];
    }
}

pelt_shadow_desc pelt__shadow_resolved(const pelt_shadow_desc *d)
{
    pelt_shadow_desc r = d ? *d : (pelt_shadow_desc){0};
    if (r.map_size == 0) r.map_size = 512;
    if (r.slices == 0) r.slices = 4;
    if (r.slices > PELT_SHADOW_MAX_SLICES) r.slices = PELT_SHADOW_MAX_SLICES;
    if (r.softness == 0.0f) r.softness = 1.0f;
    if (r.softness < 0.0f) r.softness = 0.0f;
    if (r.depth <= 0.0f) r.depth = 2.0f;
    if (r.density <= 0.0f) r.density = 1.0f;
    return r;
}

pelt_ground_desc pelt__ground_resolved(const pelt_ground_desc *d)
{
    pelt_ground_desc r = d ? *d : (pelt_ground_desc){0};
    if (r.color[0] == 0.0f && r.color[1] == 0.0f && r.color[2] == 0.0f) {
        r.color[0] = 0.42f;
        r.color[1] = 0.40f;
        r.color[2] = 0.36f;
    }
    if (r.size <= 0.0f) r.size = 4.0f;
    return r;
}
