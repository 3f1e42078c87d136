/* The fur's textures: the hair volume (Lengyel et al. 2001 §2.2), the
 * colour texture and the wetness mask (Silva et al. §3.1), read through
 * core/fur/fur_gpu.h. After the first upload only what changed goes up:
 * a new colour texture, the changed rectangle of the mask. Each texture is
 * bound on its own unit while it is uploaded, so no other unit is touched. */
#include "gl/gpu.h"

#include "core/fur/fur_gpu.h"
#include "core/base/error.h"
#include "core/base/hooks.h"

#include <string.h>

static void bind(GLenum unit, GLenum target, GLuint texture)
{
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(target, texture);
}

size_t pelt__gpu_hair_chain_bytes(unsigned w, unsigned h)
{
    size_t bytes = 0;
    while (w > 1 || h > 1) {
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
        bytes += (size_t)w * h * 4;
    }
    return bytes ? bytes : 4;
}

void pelt__gpu_hair_array_create(unsigned w, unsigned h, unsigned depth)
{
    for (GLint m = 0;; m++, w = w > 1 ? w / 2 : 1, h = h > 1 ? h / 2 : 1) {
        glTexImage3D(GL_TEXTURE_2D_ARRAY, m, GL_RGBA8, (GLsizei)w, (GLsizei)h, (GLsizei)depth, 0, GL_RGBA,
                     GL_UNSIGNED_BYTE, NULL);
        if (w == 1 && h == 1) break;
    }
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
}

void pelt__gpu_hair_array_slice(unsigned z, const uint8_t *texels, unsigned w, unsigned h, uint8_t *chain)
{
    glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, (GLint)z, (GLsizei)w, (GLsizei)h, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                    texels);
    const uint8_t *up = texels;
    uint8_t *down = chain;
    for (GLint m = 1; w > 1 || h > 1; m++) {
        pelt__fur_gpu_mip_down(up, w, h, down);
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
        glTexSubImage3D(GL_TEXTURE_2D_ARRAY, m, 0, 0, (GLint)z, (GLsizei)w, (GLsizei)h, 1, GL_RGBA,
                        GL_UNSIGNED_BYTE, down);
        up = down;
        down += (size_t)w * h * 4;
    }
}

pelt_status pelt__gpu_fur_create(pelt__gpu_fur *g, pelt_fur *fur, const pelt__fur_snapshot *snap,
                                 const pelt_hooks *hooks, pelt_error *err)
{
    pelt__gl_unpack_defaults();
    const pelt__fur_snapshot fs = *snap;
    unsigned size = fs.volume_size, slices = fs.volume_slices;
    const uint8_t *volume = fs.volume;
    glGenTextures(1, &g->volume);
    bind(PELT_UNIT_FUR, GL_TEXTURE_2D_ARRAY, g->volume);
    /* The shell levels of detail (Lengyel §2.4) follow the volume's slices. */
    unsigned lod_slices = fs.lod_slices;
    const uint8_t *lod = fs.volume_lod;
    /* Ringlets: one such set per amplitude level of the curl. */
    unsigned levels = fs.ringlet_levels, stride = slices + lod_slices;
    size_t slice_bytes = (size_t)size * size * 4;
    uint8_t *chain = pelt__alloc(&hooks->allocator, pelt__gpu_hair_chain_bytes(size, size));
    if (!chain) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the fur texture's mip chain");
    pelt__gpu_hair_array_create(size, size, levels * stride);
    for (unsigned k = 0; k < levels; k++) {
        for (unsigned s = 0; s < stride; s++) {
            const uint8_t *slice = s < slices ? volume + ((size_t)k * slices + s) * slice_bytes
                                              : lod + ((size_t)k * lod_slices + (s - slices)) * slice_bytes;
            pelt__gpu_hair_array_slice(k * stride + s, slice, size, size, chain);
        }
    }
    pelt__free(&hooks->allocator, chain);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_REPEAT);

    /* White until the fur has a colour texture: the hair colour alone. */
    static const uint8_t white[4] = {255, 255, 255, 255};
    glGenTextures(1, &g->color);
    bind(PELT_UNIT_COLOR, GL_TEXTURE_2D, g->color);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, white);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    g->color_version = (unsigned)-1;

    /* The wetness mask: float texels, nearest sampling (Silva §3.1). */
    unsigned w = fs.mask_width, h = fs.mask_height;
    const float *texels = fs.mask;
    glGenTextures(1, &g->mask);
    bind(PELT_UNIT_MASK, GL_TEXTURE_2D, g->mask);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, (GLsizei)w, (GLsizei)h, 0, GL_RGBA, GL_FLOAT, texels);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    unsigned rect[4];
    pelt__fur_gpu_take_mask_dirty(fur, rect); /* all of it went up just now */

    /* Lengyel's lighting table: it depends on the material only (P_d, P_s);
     * the light enters through u = T.L and v = T.H per fragment. */
    float table[PELT__FUR_GPU_LIGHT_TABLE * PELT__FUR_GPU_LIGHT_TABLE * 2];
    pelt__fur_gpu_light_table(fur, table);
    glGenTextures(1, &g->light_table);
    bind(PELT_UNIT_LIGHT_TABLE, GL_TEXTURE_2D, g->light_table);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RG32F, PELT__FUR_GPU_LIGHT_TABLE, PELT__FUR_GPU_LIGHT_TABLE, 0,
                 GL_RG, GL_FLOAT, table);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return PELT_OK;
}

size_t pelt__gpu_fur_upload(pelt__gpu_fur *g, pelt_fur *fur, const pelt__fur_snapshot *fs, unsigned mask_rect[4])
{
    size_t bytes = 0;
    unsigned w = fs->color_width, h = fs->color_height, version = fs->color_version;
    const uint8_t *color = fs->color;
    if (color && version != g->color_version) {
        bind(PELT_UNIT_COLOR, GL_TEXTURE_2D, g->color);
        /* sRGB texels: GL decodes them to linear light when sampled (and
           filters after decoding), in GL 3.3 and GLSL ES 3.00 alike. */
        glTexImage2D(GL_TEXTURE_2D, 0, GL_SRGB8_ALPHA8, (GLsizei)w, (GLsizei)h, 0, GL_RGBA,
                     GL_UNSIGNED_BYTE, color);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
        glGenerateMipmap(GL_TEXTURE_2D);
        g->color_version = version;
        bytes += (size_t)w * h * 4;
    }
    /* Only the rectangle of the mask that changed since the last upload. */
    unsigned *r = mask_rect;
    r[0] = r[1] = r[2] = r[3] = 0;
    if (pelt__fur_gpu_take_mask_dirty(fur, r)) {
        const float *texels = fs->mask;
        w = fs->mask_width;
        bind(PELT_UNIT_MASK, GL_TEXTURE_2D, g->mask);
        glPixelStorei(GL_UNPACK_ROW_LENGTH, (GLint)w);
        glTexSubImage2D(GL_TEXTURE_2D, 0, (GLint)r[0], (GLint)r[1], (GLsizei)(r[2] - r[0]),
                        (GLsizei)(r[3] - r[1]), GL_RGBA, GL_FLOAT,
                        texels + ((size_t)r[1] * w + r[0]) * 4);
        glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
        bytes += (size_t)(r[2] - r[0]) * (r[3] - r[1]) * 4 * sizeof(float);
    }
    return bytes;
}

void pelt__gpu_fur_bind(const pelt__gpu_fur *g)
{
    bind(PELT_UNIT_FUR, GL_TEXTURE_2D_ARRAY, g->volume);
    bind(PELT_UNIT_COLOR, GL_TEXTURE_2D, g->color);
    bind(PELT_UNIT_MASK, GL_TEXTURE_2D, g->mask);
    bind(PELT_UNIT_LIGHT_TABLE, GL_TEXTURE_2D, g->light_table);
}

void pelt__gpu_fur_destroy(pelt__gpu_fur *g)
{
    GLuint textures[4] = {g->volume, g->color, g->mask, g->light_table};
    glDeleteTextures(4, textures);
    memset(g, 0, sizeof *g);
}
