/* The renderer's read-only view of a pelt_fur (see fur_gpu.h). */
#include "core/fur/fur_gpu.h"
#include "core/mesh/skeleton.h"

#include "core/fur/fur_internal.h"
#include "core/fur/shading.h"

void pelt__fur_gpu_snapshot(const pelt_fur *f, pelt__fur_snapshot *out)
{
    const pelt__wetness *mask = pelt__water_mask(f->water);
    const pelt__skeleton *k = pelt__mesh_skeleton(f->mesh);
    *out = (pelt__fur_snapshot){
        .mesh = f->mesh,
        .lod = &f->lod,
        .volume = f->texture,
        .volume_size = f->desc.look.texture_size,
        .volume_slices = f->texture_slices,
        .volume_lod = f->lod_slices,
        .lod_slices = f->lod_slice_count,
        .ringlet_levels = f->ringlet_levels,
        .occlusion_depth = pelt__occlusion_depth(f->desc.look.density, f->desc.look.strand_radius,
                                                 f->desc.look.texture_size),
        .vertex_curl_radius = pelt__fur_vertex_curl_radius(&f->desc),
        .clump_lean = pelt__fur_clump_lean(&f->desc),
        .wet_lie = pelt__fur_wet_lie(&f->desc),
        .fur_uvs = f->fur_uvs,
        .fur_per_uv = {f->fur_per_uv[0], f->fur_per_uv[1]},
        .tips = f->tips,
        .tips_version = f->tips_version,
        .pose = f->pose,
        .pose_version = f->pose_version,
        .skinned = k != NULL,
        .groom = f->groom.v,
        .groom_stride = sizeof(pelt__groom_vertex),
        .fin_texture = f->fin_texture,
        .fin_width = f->fin_width,
        .fin_height = f->fin_height,
        .color = f->color_texture,
        .color_width = f->color_width,
        .color_height = f->color_height,
        .color_version = f->color_version,
        .mask = mask->texels,
        .mask_width = mask->width,
        .mask_height = mask->height,
        .any_wet = !pelt__rect_empty(mask->wet),
    };
    if (k) out->skin = (pelt__gpu_skin){k->bones, k->weights, k->bind, k->scratch_skin, k->bone_count};
}

bool pelt__fur_gpu_take_mask_dirty(pelt_fur *f, unsigned rect[4])
{
    return pelt__water_take_dirty(f->water, rect);
}

bool pelt__fur_gpu_take_groom_dirty(pelt_fur *f, size_t range[2])
{
    return pelt__groom_take_dirty(&f->groom, range);
}


_Static_assert(PELT__FUR_GPU_LIGHT_TABLE == PELT__LIGHT_TABLE, "one table size");

void pelt__fur_gpu_light_table(const pelt_fur *f, float *out)
{
    pelt__lengyel_table(f->desc.look.diffuse_power, f->desc.look.shininess, out);
}


void pelt__fur_gpu_linear_rgb(const float srgb[3], float out[3])
{
    for (int k = 0; k < 3; k++) out[k] = pelt__srgb_decode(srgb[k]);
}

void pelt__fur_gpu_mip_down(const uint8_t *up, unsigned w, unsigned h, uint8_t *down)
{
    unsigned dw = w > 1 ? w / 2 : 1, dh = h > 1 ? h / 2 : 1;
    unsigned sx = w > 1 ? 2 : 1, sy = h > 1 ? 2 : 1, n = sx * sy;
    for (unsigned y = 0; y < dh; y++) {
        for (unsigned x = 0; x < dw; x++) {
            unsigned sum[4] = {0, 0, 0, 0};
            const uint8_t *top = NULL; /* the texel with the most coverage */
            for (unsigned j = 0; j < sy; j++) {
                for (unsigned i = 0; i < sx; i++) {
                    const uint8_t *t = up + ((size_t)(y * sy + j) * w + x * sx + i) * 4;
                    for (int c = 0; c < 4; c++) sum[c] += t[c];
                    if (!top || t[3] > top[3]) top = t;
                }
            }
            uint8_t *o = down + ((size_t)y * dw + x) * 4;
            for (int c = 0; c < 4; c++) o[c] = (uint8_t)((sum[c] + n - 1) / n);
            /* The top texel's own id (b / a) at the block's coverage. */
            unsigned id = top[3] ? (top[2] * o[3] + top[3] / 2u) / top[3] : 0;
            o[2] = (uint8_t)(id < o[3] ? id : o[3]);
        }
    }
}
