/* The uniform blocks of shaders/blocks.glsl: the frame block goes up once
 * a draw, the fur block only when the look changed. The C structs in
 * gl/gpu.h are their std140 images; the asserts below pin the offsets
 * std140 gives (tests/gl/test_render.c asks GL for them too). */
#include "gl/gpu.h"

#include "core/base/vec.h"
#include "core/fur/fur_gpu.h"

#include <math.h>
#include <string.h>

#define OFFSET(type, field, at) _Static_assert(offsetof(type, field) == (at), #type "." #field)
OFFSET(pelt__frame_block, model, 0);
OFFSET(pelt__frame_block, view_proj, 64);
OFFSET(pelt__frame_block, eye, 128);
OFFSET(pelt__frame_block, ambient, 140);
OFFSET(pelt__frame_block, light_dir, 144);
OFFSET(pelt__frame_block, exposure, 156);
OFFSET(pelt__frame_block, light_color, 160);
OFFSET(pelt__frame_block, tone, 172);
OFFSET(pelt__frame_block, view_dir, 176);
OFFSET(pelt__frame_block, light_matrix, 192);
OFFSET(pelt__frame_block, shadow_map, 256);
OFFSET(pelt__frame_block, shadow_slab, 272);
_Static_assert(sizeof(pelt__frame_block) == 288, "std140 size of pelt_frame_block");
OFFSET(pelt__fur_block, color, 0);
OFFSET(pelt__fur_block, layers, 12);
OFFSET(pelt__fur_block, tip_color, 16);
OFFSET(pelt__fur_block, length, 28);
OFFSET(pelt__fur_block, specular, 32);
OFFSET(pelt__fur_block, shininess, 44);
OFFSET(pelt__fur_block, fur_per_uv, 48);
OFFSET(pelt__fur_block, shadow, 56);
OFFSET(pelt__fur_block, curl_frequency, 60);
OFFSET(pelt__fur_block, curl_radius, 64);
OFFSET(pelt__fur_block, clump_blend, 68);
OFFSET(pelt__fur_block, clump_tightness, 72);
OFFSET(pelt__fur_block, wet_darken, 76);
OFFSET(pelt__fur_block, color_scale, 80);
OFFSET(pelt__fur_block, slant, 84);
OFFSET(pelt__fur_block, wet_gloss, 88);
OFFSET(pelt__fur_block, wet_sharpness, 92);
OFFSET(pelt__fur_block, skin_color, 96);
OFFSET(pelt__fur_block, tiling, 108);
OFFSET(pelt__fur_block, fin_length, 112);
OFFSET(pelt__fur_block, ringlets, 128);
OFFSET(pelt__fur_block, occlusion, 136);
OFFSET(pelt__fur_block, wet_strays, 140);
OFFSET(pelt__fur_block, ringlet_radius, 144);
OFFSET(pelt__fur_block, strand_curl_radius, 148);
OFFSET(pelt__fur_block, strand_curl_omega, 152);
OFFSET(pelt__fur_block, strand_curl_wave, 156);
OFFSET(pelt__fur_block, clump_lean, 160);
OFFSET(pelt__fur_block, hair_width, 164);
OFFSET(pelt__fur_block, taper, 168);
OFFSET(pelt__fur_block, wet_lie, 172);
_Static_assert(sizeof(pelt__fur_block) == 176, "std140 size of pelt_fur_block");
#undef OFFSET

static GLuint make_buffer(size_t bytes)
{
    GLuint b;
    glGenBuffers(1, &b);
    glBindBuffer(GL_UNIFORM_BUFFER, b);
    glBufferData(GL_UNIFORM_BUFFER, (GLsizeiptr)bytes, NULL, GL_DYNAMIC_DRAW);
    return b;
}

void pelt__gpu_blocks_create(pelt__gpu_blocks *b)
{
    b->frame = make_buffer(sizeof(pelt__frame_block));
    b->fur = make_buffer(sizeof(pelt__fur_block));
    b->fur_valid = false;
}

static void send(GLuint buffer, const void *data, size_t bytes)
{
    glBindBuffer(GL_UNIFORM_BUFFER, buffer);
    glBufferSubData(GL_UNIFORM_BUFFER, 0, (GLsizeiptr)bytes, data);
}

size_t pelt__gpu_blocks_set_frame(pelt__gpu_blocks *b, const pelt_view *v, const pelt_draw_desc *draw,
                                  const pelt__frame_shadow *shadow)
{
    pelt__frame_block f;
    memset(&f, 0, sizeof f);
    memcpy(f.model, v->model, sizeof f.model);
    pelt__mat4_mul(f.view_proj, v->proj, v->view);
    memcpy(f.eye, v->eye, sizeof f.eye);
    f.ambient = v->light.ambient;
    memcpy(f.light_dir, v->light.direction, sizeof f.light_dir);
    memcpy(f.light_color, v->light.color, sizeof f.light_color);
    f.exposure = draw->exposure > 0.0f ? draw->exposure : 1.0f;
    f.tone = draw->tone == PELT_TONE_NONE ? 1.0f : 0.0f;
    /* Forward is minus the third row of the view rotation. */
    pelt_vec3 fwd = v3_norm_or(v3(-v->view[2], -v->view[6], -v->view[10]), v3(0.0f, 0.0f, -1.0f));
    v3_store(f.view_dir, fwd);
    memcpy(f.light_matrix, shadow->light_matrix, sizeof f.light_matrix);
    memcpy(f.shadow_map, shadow->map, sizeof f.shadow_map);
    memcpy(f.shadow_slab, shadow->slab, sizeof f.shadow_slab);
    send(b->frame, &f, sizeof f);
    return sizeof f;
}

size_t pelt__gpu_blocks_set_fur(pelt__gpu_blocks *b, const pelt_fur *fur, const pelt__fur_snapshot *fs)
{
    const pelt_fur_desc d = pelt_fur_get_desc(fur);
    pelt__fur_block k;
    memset(&k, 0, sizeof k); /* the padding too: the struct is compared bytewise */
    /* The look's colours are sRGB; the shaders light in linear light. */
    pelt__fur_gpu_linear_rgb(d.look.color, k.color);
    k.layers = (float)d.layers;
    pelt__fur_gpu_linear_rgb(d.look.tip_color, k.tip_color);
    k.length = d.length;
    memcpy(k.specular, d.look.specular, sizeof k.specular); /* a gain, not a colour to decode */
    k.shininess = d.look.shininess;
    memcpy(k.fur_per_uv, fs->fur_per_uv, sizeof k.fur_per_uv);
    k.shadow = d.look.shadow;
    k.curl_frequency = d.look.curl_frequency;
    k.curl_radius = fs->vertex_curl_radius; /* 0 with ringlets: the texture curls */
    k.clump_blend = d.wet.clump_blend;
    k.clump_tightness = d.wet.clump_tightness;
    k.wet_darken = d.wet.darken;
    k.wet_strays = d.wet.strays;
    k.wet_gloss = d.wet.gloss;
    k.wet_sharpness = d.wet.gloss_sharpness;
    k.color_scale = d.look.color_scale;
    k.slant = tanf(d.comb.slant * 3.14159265f / 180.0f); /* Lengyel et al. §3 */
    pelt__fur_gpu_linear_rgb(d.look.skin_color, k.skin_color);
    k.tiling = d.look.tiling;
    k.fin_length = d.fins.length;
    k.inter_shadow = d.look.inter_shadow ? d.look.inter_shadow_darkness : 0.0f;
    k.inter_shadow_step = d.look.inter_shadow_offset / (float)d.look.texture_size;
    k.shading_model = (float)d.look.shading;
    k.ringlets[0] = (float)fs->ringlet_levels;
    k.ringlets[1] = (float)(fs->volume_slices + fs->lod_slices);
    k.occlusion = fs->occlusion_depth;
    k.ringlet_radius = fs->ringlet_levels > 1 ? d.look.curl_radius : 0.0f;
    /* The texture's own curl, texels over texels a world unit times the
     * fur's length: lit along the curl with the ringlets (own_light.glsl). */
    float texels_per_length = (float)d.look.texture_size * d.look.tiling * d.length;
    k.strand_curl_radius = texels_per_length > 0.0f ? d.look.strand_curl / texels_per_length : 0.0f;
    k.strand_curl_omega = 6.2831853f * d.look.strand_curl_turns;
    k.strand_curl_wave = d.look.strand_curl_shape == PELT_STRAND_CURL_WAVE ? 1.0f : 0.0f;
    k.clump_lean = fs->clump_lean; /* 0 but for natural clumps */
    /* The hair's width at the root in world units: two radii of texels a
     * tile's texture_size to tiling's world unit (the shells' over-count). */
    float texels_per_unit = (float)d.look.texture_size * d.look.tiling;
    k.hair_width = texels_per_unit > 0.0f ? 2.0f * d.look.strand_radius / texels_per_unit : 0.0f;
    k.taper = d.look.taper;
    k.wet_lie = fs->wet_lie;
    if (b->fur_valid && !memcmp(&k, &b->fur_sent, sizeof k)) return 0;
    send(b->fur, &k, sizeof k);
    b->fur_sent = k;
    b->fur_valid = true;
    return sizeof k;
}

void pelt__gpu_blocks_bind(const pelt__gpu_blocks *b)
{
    glBindBufferBase(GL_UNIFORM_BUFFER, PELT_BLOCK_FRAME, b->frame);
    glBindBufferBase(GL_UNIFORM_BUFFER, PELT_BLOCK_FUR, b->fur);
}

void pelt__gpu_blocks_destroy(pelt__gpu_blocks *b)
{
    GLuint buffers[2] = {b->frame, b->fur};
    glDeleteBuffers(2, buffers);
    memset(b, 0, sizeof *b);
}
