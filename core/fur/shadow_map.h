/* Deep opacity maps (docs/shadows.md): the C references of what the light
 * pass writes and the receivers read (gl/shaders/shadow_map.glsl mirrors
 * them; tests/gl/test_shadows.c renders both and compares).
 *
 * From the light, each texel of the map knows the depth z_skin of the
 * nearest skin. Its opacity slices start a slab of `span` in front of
 * that skin: a point at depth d sits at slice position
 * k = (d - (z_skin - span)) / (span / S) (S slices; k < 0 in front of the
 * slab, k = S at the skin). Slice j accumulates the fur in front of
 * position j + 1, with a one-slice linear ramp; the last slice holds all
 * the fur of the texel. Fur opacity adds as -ln(1 - alpha), so that
 * exp(-sum) is the product of the layers' transmittances. */
#ifndef PELT_SHADOW_MAP_H
#define PELT_SHADOW_MAP_H

#include "pelt/shadow.h"

/* The part a fragment at slice position k adds to slice j of S. */
float pelt__shadow_slice_weight(float k, unsigned j, unsigned slices);

/* What a fur fragment of coverage alpha adds: -ln(1 - alpha), alpha capped
 * at 0.98 so one layer never makes a perfect occluder. */
float pelt__shadow_sigma(float alpha);

/* The accumulated opacity in front of slice position k, from the texel's
 * S slice sums: linear between 0 at k = 0 and slice j's sum at k = j + 1,
 * the last slice's sum from k = S on. Non-decreasing in k. */
float pelt__shadow_opacity(const float slices_sum[PELT_SHADOW_MAX_SLICES], unsigned slices, float k);

/* Transmittance exp(-density * opacity). */
float pelt__shadow_transmittance(float opacity, float density);

/* The light's orthographic frame around a bounding sphere (world centre,
 * radius): `tex` maps a world point to (s, t, d, 1), s, t in [0, 1]
 * across the sphere seen from the light, d its depth from the light in
 * [0, 1] over the sphere's near side to `depth_range` radii behind its
 * centre... d = (dot(centre - p, l) + radius) / (radius (1 + depth_range)).
 * `clip` is the same as clip coordinates (2 s - 1, 2 t - 1, 2 d - 1, 1).
 * Both column-major. light_dir points towards the light, need not be
 * unit; (0, 0, 0) falls back to +Y. The frame's winding is that of a
 * camera looking along -light_dir. */
void pelt__shadow_light_frame(const float center[3], float radius, const float light_dir[3],
                              float depth_range, float tex[16], float clip[16]);

/* The settings with their defaults filled in (pelt/shadow.h). */
pelt_shadow_desc pelt__shadow_resolved(const pelt_shadow_desc *d);
pelt_ground_desc pelt__ground_resolved(const pelt_ground_desc *d);

#endif
