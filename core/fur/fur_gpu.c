/* The renderer's read-only view of a pelt_fur (see fur_gpu.h). */
#include "core/fur/fur_gpu.h"
#include "core/mesh/skeleton.h"

#include "core/fur/fur_internal.h"
#include "core/fur/shading.h"

const pelt_mesh *pelt__fur_gpu_mesh(const pelt_fur *f) { return f->mesh; }

const uint8_t *pelt__fur_gpu_volume(const pelt_fur *f, unsigned *size, unsigned *slices)
{
    *size = f->desc.look.texture_size;
    *slices = f->texture_slices;
    return f->texture;
}

bool pelt__fur_gpu_skin(const pelt_fur *f, pelt__gpu_skin *out)
{
    const pelt__skeleton *k = pelt__mesh_skeleton(f->mesh);
    if (!k) return false;
    out->bones = k->bones;
    out->weights = k->weights;
    out->bind = k->bind;
    out->matrices = k->scratch_skin;
    out->bone_count = k->bone_count;
    return true;
}

const float *pelt__fur_gpu_pose(const pelt_fur *f, unsigned *version)
{
    *version = f->pose_version;
    return f->pose;
}

const uint8_t *pelt__fur_gpu_volume_lod(const pelt_fur *f, unsigned *slices)
{
    *slices = f->lod_slice_count;
    return f->lod_slices;
}

unsigned pelt__fur_gpu_ringlet_levels(const pelt_fur *f) { return f->ringlet_levels; }

float pelt__fur_gpu_vertex_curl_radius(const pelt_fur *f) { return pelt__fur_vertex_curl_radius(&f->desc); }

const float *pelt__fur_gpu_uvs(const pelt_fur *f) { return f->fur_uvs; }

void pelt__fur_gpu_per_uv(const pelt_fur *f, float out[2])
{
    out[0] = f->fur_per_uv[0];
    out[1] = f->fur_per_uv[1];
}

const float *pelt__fur_gpu_tips(const pelt_fur *f, unsigned *version)
{
    *version = f->tips_version;
    return f->tips;
}

const uint8_t *pelt__fur_gpu_color(const pelt_fur *f, unsigned *width, unsigned *height,
                                   unsigned *version)
{
    *width = f->color_width;
    *height = f->color_height;
    *version = f->color_version;
    return f->color_texture;
}

const float *pelt__fur_gpu_mask(const pelt_fur *f, unsigned *width, unsigned *height)
{
    *width = pelt__water_mask(f->water)->width;
    *height = pelt__water_mask(f->water)->height;
    return pelt__water_mask(f->water)->texels;
}

bool pelt__fur_gpu_take_mask_dirty(pelt_fur *f, unsigned rect[4])
{
    return pelt__water_take_dirty(f->water, rect);
}

const void *pelt__fur_gpu_groom(const pelt_fur *f, size_t *stride)
{
    *stride = sizeof(pelt__groom_vertex);
    return f->groom.v;
}

bool pelt__fur_gpu_take_groom_dirty(pelt_fur *f, size_t range[2])
{
    return pelt__groom_take_dirty(&f->groom, range);
}


const pelt__lod_chain *pelt__fur_gpu_lod(const pelt_fur *f) { return &f->lod; }

const uint8_t *pelt__fur_gpu_fin_texture(const pelt_fur *f, unsigned *width, unsigned *height)
{
    *width = f->fin_width;
    *height = f->fin_height;
    return f->fin_texture;
}

_Static_assert(PELT__FUR_GPU_LIGHT_TABLE == PELT__LIGHT_TABLE, "one table size");

void pelt__fur_gpu_light_table(const pelt_fur *f, float *out)
{
    pelt__lengyel_table(f->desc.look.diffuse_power, f->desc.look.shininess, out);
}

bool pelt__fur_gpu_any_wet(const pelt_fur *f) { return !pelt__rect_empty(pelt__water_mask(f->water)->wet); }
