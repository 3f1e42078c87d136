/* The fur's textures: the hair volume (Lengyel et al. 2001 §2.2), the
 * colour texture and the wetness mask (Silva et al. §3.1), read through
 * core/fur/fur_gpu.h. After the first upload only what changed goes up:
 * a new colour texture, the changed rectangle of the mask. Each texture is
 * bound on its own unit while it is uploaded, so no other unit is touched. */
#include "gl/gpu.h"

#include "core/fur/fur_gpu.h"

#include <string.h>

static void bind(GLenum unit, GLenum target, GLuint texture)
{
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(target, texture);
}

void pelt__gpu_fur_create(pelt__gpu_fur *g, pelt_fur *fur, const pelt__fur_snapshot *snap)
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
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA8, (GLsizei)size, (GLsizei)size, (GLsizei)(levels * stride),
                 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    for (unsigned k = 0; k < levels; k++) {
        glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, (GLint)(k * stride), (GLsizei)size, (GLsizei)size,
                        (GLsizei)slices, GL_RGBA, GL_UNSIGNED_BYTE, volume + (size_t)k * slices * slice_bytes);
        if (lod_slices)
            glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, (GLint)(k * stride + slices), (GLsizei)size,
                            (GLsizei)size, (GLsizei)lod_slices, GL_RGBA, GL_UNSIGNED_BYTE,
                            lod + (size_t)k * lod_slices * slice_bytes);
    }
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glGenerateMipmap(GL_TEXTURE_2D_ARRAY);

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
