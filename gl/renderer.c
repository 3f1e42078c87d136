/* The fur renderer (Lengyel et al. 2001 §2.3, Silva et al. §4): an opaque
 * skin pass with depth write, then every shell in one instanced draw,
 * blended inner to outer, depth tested without depth write. */
#include "pelt/render.h"

#include "core/base/error.h"
#include "core/fur/fur_gpu.h"
#include "core/base/vec.h"
#include "gl/programs.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { UNIT_FUR = 0, UNIT_COLOR = 1, UNIT_MASK = 2 };

/* Uniform locations of one program (-1 where a program lacks one). */
typedef struct uniforms {
    GLint model, view_proj, layers, length, curl_frequency, curl_radius;
    GLint color, tip_color, specular, shininess, shadow, eye;
    GLint light_dir, light_color, ambient;
    GLint fur, color_tex, mask;
    GLint clump_blend, clump_tightness, wet_darken, fur_per_uv, color_scale, slant;
    GLint first_layer;
} uniforms;

struct pelt_renderer {
    const pelt_mesh *mesh;
    pelt_fur *fur;
    pelt_renderer_desc desc;
    GLuint vao, vbo_static, vbo_tips, ebo;
    GLuint skin_program, shell_program;
    uniforms skin_u, shell_u;
    GLuint fur_texture, color_texture, mask_texture;
    GLsizei index_count;
    unsigned tips_version, color_version;
    unsigned shell_draw_calls;
};

static void find_uniforms(GLuint p, uniforms *u)
{
#define LOC(field, name) u->field = glGetUniformLocation(p, name)
    LOC(model, "u_model"); LOC(view_proj, "u_view_proj"); LOC(layers, "u_layers");
    LOC(length, "u_length"); LOC(curl_frequency, "u_curl_frequency");
    LOC(curl_radius, "u_curl_radius"); LOC(color, "u_color"); LOC(tip_color, "u_tip_color");
    LOC(specular, "u_specular"); LOC(shininess, "u_shininess"); LOC(shadow, "u_shadow");
    LOC(eye, "u_eye"); LOC(light_dir, "u_light_dir"); LOC(light_color, "u_light_color");
    LOC(ambient, "u_ambient"); LOC(fur, "u_fur"); LOC(color_tex, "u_color_tex");
    LOC(mask, "u_mask"); LOC(clump_blend, "u_clump_blend");
    LOC(clump_tightness, "u_clump_tightness"); LOC(wet_darken, "u_wet_darken");
    LOC(fur_per_uv, "u_fur_per_uv"); LOC(color_scale, "u_color_scale");
    LOC(slant, "u_slant"); LOC(first_layer, "u_first_layer");
#undef LOC
    glUseProgram(p);
    glUniform1i(u->fur, UNIT_FUR);
    glUniform1i(u->color_tex, UNIT_COLOR);
    glUniform1i(u->mask, UNIT_MASK);
}

/* Interleaved static vertex data: position, normal, uv, fur uv, tangent,
 * comb direction. */
enum { STATIC_FLOATS = 3 + 3 + 2 + 2 + 4 + 3 };

static pelt_status upload_geometry(pelt_renderer *r, pelt_error *err)
{
    const pelt_mesh_data m = pelt_mesh_get_data(r->mesh);
    const float *tangents = pelt_mesh_tangents(r->mesh), *fur_uvs = pelt__fur_gpu_uvs(r->fur);
    float *data = pelt__calloc(m.vertex_count, STATIC_FLOATS * sizeof(float));
    if (!data) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for vertex data");
    for (size_t i = 0; i < m.vertex_count; i++) {
        float *v = data + i * STATIC_FLOATS;
        memcpy(v + 0, m.positions + 3 * i, 3 * sizeof(float));
        memcpy(v + 3, m.normals + 3 * i, 3 * sizeof(float));
        memcpy(v + 6, m.uvs + 2 * i, 2 * sizeof(float));
        memcpy(v + 8, fur_uvs + 2 * i, 2 * sizeof(float));
        memcpy(v + 10, tangents + 4 * i, 4 * sizeof(float));
        /* Without a direction field, comb along the fur texture's u axis. */
        memcpy(v + 14, m.comb ? m.comb + 3 * i : tangents + 4 * i, 3 * sizeof(float));
    }
    glGenVertexArrays(1, &r->vao);
    glBindVertexArray(r->vao);
    glGenBuffers(1, &r->vbo_static);
    glBindBuffer(GL_ARRAY_BUFFER, r->vbo_static);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(m.vertex_count * STATIC_FLOATS * sizeof(float)),
                 data, GL_STATIC_DRAW);
    free(data);
    const GLsizei stride = STATIC_FLOATS * sizeof(float);
    const int sizes[] = {3, 3, 2, 2, 4, 3};
    const GLuint locations[] = {0, 1, 2, 3, 4, 6};
    size_t offset = 0;
    for (GLuint k = 0; k < 6; k++) {
        GLuint a = locations[k];
        glEnableVertexAttribArray(a);
        glVertexAttribPointer(a, sizes[k], GL_FLOAT, GL_FALSE, stride, (const void *)offset);
        offset += (size_t)sizes[k] * sizeof(float);
    }
    /* Strand tips change every frame: their own buffer, updated in place. */
    glGenBuffers(1, &r->vbo_tips);
    glBindBuffer(GL_ARRAY_BUFFER, r->vbo_tips);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(m.vertex_count * 3 * sizeof(float)),
                 pelt__fur_gpu_tips(r->fur, &r->tips_version), GL_DYNAMIC_DRAW);
    glEnableVertexAttribArray(5);
    glVertexAttribPointer(5, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), NULL);

    glGenBuffers(1, &r->ebo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->ebo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(m.triangle_count * 3 * sizeof(uint32_t)),
                 m.indices, GL_STATIC_DRAW);
    r->index_count = (GLsizei)(m.triangle_count * 3);
    glBindVertexArray(0);
    return PELT_OK;
}

static void upload_textures(pelt_renderer *r)
{
    pelt_fur *f = r->fur;
    unsigned size, slices;
    const uint8_t *volume = pelt__fur_gpu_volume(f, &size, &slices);
    GLsizei s = (GLsizei)size;
    glGenTextures(1, &r->fur_texture);
    glBindTexture(GL_TEXTURE_2D_ARRAY, r->fur_texture);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA8, s, s, (GLsizei)slices, 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, volume);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glGenerateMipmap(GL_TEXTURE_2D_ARRAY);

    static const uint8_t white[4] = {255, 255, 255, 255};
    glGenTextures(1, &r->color_texture);
    glBindTexture(GL_TEXTURE_2D, r->color_texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, white);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    r->color_version = (unsigned)-1;

    /* The wetness mask: float texels, nearest sampling (Silva §3.1). */
    unsigned mw, mh;
    const float *texels = pelt__fur_gpu_mask(f, &mw, &mh);
    glGenTextures(1, &r->mask_texture);
    glBindTexture(GL_TEXTURE_2D, r->mask_texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, (GLsizei)mw, (GLsizei)mh, 0, GL_RGBA,
                 GL_FLOAT, texels);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    unsigned rect[4];
    pelt__fur_gpu_take_mask_dirty(f, rect); /* all of it went up just now */
}

pelt_status pelt_renderer_create(const pelt_mesh *mesh, pelt_fur *fur,
                                 const pelt_renderer_desc *desc, pelt_renderer **out,
                                 pelt_error *err)
{
    if (!out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_renderer_create: out is NULL");
    *out = NULL;
    if (!mesh || !fur || pelt__fur_gpu_mesh(fur) != mesh)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "pelt_renderer_create: needs a mesh and a fur made for that mesh");
    if (pelt_mesh_get_data(mesh).triangle_count * 3 > 0x7fffffff)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "mesh too large for one draw call");
    pelt_renderer *r = calloc(1, sizeof *r);
    if (!r) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory");
    r->mesh = mesh;
    r->fur = fur;
    if (desc) r->desc = *desc;

    const char *skin_vs[] = {pelt__shader_skin_vs, NULL};
    const char *skin_fs[] = {pelt__shader_shading, pelt__shader_skin_fs, NULL};
    const char *shell_vs[] = {pelt__shader_fur_shape, pelt__shader_shell_vs, NULL};
    const char *shell_fs[] = {pelt__shader_shading, pelt__shader_clump, pelt__shader_shell_fs, NULL};
    pelt_status st = pelt__program_build("skin", skin_vs, skin_fs, &r->skin_program, err);
    if (st == PELT_OK)
        st = pelt__program_build("shell", shell_vs, shell_fs, &r->shell_program, err);
    if (st == PELT_OK) st = upload_geometry(r, err);
    if (st != PELT_OK) {
        pelt_renderer_destroy(r);
        return st;
    }
    find_uniforms(r->skin_program, &r->skin_u);
    find_uniforms(r->shell_program, &r->shell_u);
    upload_textures(r);
    glUseProgram(0);
    *out = r;
    return PELT_OK;
}

void pelt_renderer_destroy(pelt_renderer *r)
{
    if (!r) return;
    GLuint buffers[3] = {r->vbo_static, r->vbo_tips, r->ebo};
    GLuint textures[3] = {r->fur_texture, r->color_texture, r->mask_texture};
    glDeleteBuffers(3, buffers);
    glDeleteTextures(3, textures);
    if (r->vao) glDeleteVertexArrays(1, &r->vao);
    if (r->skin_program) glDeleteProgram(r->skin_program);
    if (r->shell_program) glDeleteProgram(r->shell_program);
    free(r);
}

/* Brings GPU copies up to date with what changed in the fur since the last
 * frame: the tip buffer in place, the colour texture when it was set, and
 * only the changed rectangle of the wetness mask. */
void pelt_renderer_upload(pelt_renderer *r)
{
    pelt_fur *f = r->fur;
    unsigned tips_version, color_version, cw, ch;
    const float *tips = pelt__fur_gpu_tips(f, &tips_version);
    if (r->tips_version != tips_version) {
        glBindBuffer(GL_ARRAY_BUFFER, r->vbo_tips);
        glBufferSubData(GL_ARRAY_BUFFER, 0,
                        (GLsizeiptr)(pelt_mesh_get_data(r->mesh).vertex_count * 3 * sizeof(float)), tips);
        r->tips_version = tips_version;
    }
    const uint8_t *color = pelt__fur_gpu_color(f, &cw, &ch, &color_version);
    if (r->color_version != color_version && color) {
        glBindTexture(GL_TEXTURE_2D, r->color_texture);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, (GLsizei)cw, (GLsizei)ch,
                     0, GL_RGBA, GL_UNSIGNED_BYTE, color);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
        glGenerateMipmap(GL_TEXTURE_2D);
        r->color_version = color_version;
    }
    /* Only the rectangle of the mask that changed since the last upload. */
    unsigned rect[4];
    if (pelt__fur_gpu_take_mask_dirty(f, rect)) {
        unsigned mw, mh;
        const float *texels = pelt__fur_gpu_mask(f, &mw, &mh);
        glBindTexture(GL_TEXTURE_2D, r->mask_texture);
        glPixelStorei(GL_UNPACK_ROW_LENGTH, (GLint)mw);
        glTexSubImage2D(GL_TEXTURE_2D, 0, (GLint)rect[0], (GLint)rect[1], (GLsizei)(rect[2] - rect[0]),
                        (GLsizei)(rect[3] - rect[1]), GL_RGBA, GL_FLOAT,
                        texels + ((size_t)rect[1] * mw + rect[0]) * 4);
        glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    }
}

static void set_common(const pelt_renderer *r, const uniforms *u, const pelt_view *v,
                       const float view_proj[16])
{
    const pelt_fur_desc desc = pelt_fur_get_desc(r->fur), *d = &desc;
    float fur_per_uv[2];
    pelt__fur_gpu_per_uv(r->fur, fur_per_uv);
    glUniformMatrix4fv(u->model, 1, GL_FALSE, v->model);
    glUniformMatrix4fv(u->view_proj, 1, GL_FALSE, view_proj);
    glUniform1f(u->layers, (float)d->layers);
    glUniform1f(u->length, d->length);
    glUniform1f(u->curl_frequency, d->look.curl_frequency);
    glUniform1f(u->curl_radius, d->look.curl_radius);
    glUniform3fv(u->color, 1, d->look.color);
    glUniform3fv(u->tip_color, 1, d->look.tip_color);
    glUniform3fv(u->specular, 1, d->look.specular);
    glUniform1f(u->shininess, d->look.shininess);
    glUniform1f(u->shadow, d->look.shadow);
    glUniform3fv(u->eye, 1, v->eye);
    glUniform3fv(u->light_dir, 1, v->light.direction);
    glUniform3fv(u->light_color, 1, v->light.color);
    glUniform1f(u->ambient, v->light.ambient);
    glUniform1f(u->clump_blend, d->wet.clump_blend);
    glUniform1f(u->clump_tightness, d->wet.clump_tightness);
    glUniform1f(u->wet_darken, d->wet.darken);
    glUniform2fv(u->fur_per_uv, 1, fur_per_uv);
    glUniform1f(u->color_scale, d->look.color_scale);
    glUniform1f(u->slant, tanf(d->comb.slant * 3.14159265f / 180.0f));
}

void pelt_renderer_draw(pelt_renderer *r, const pelt_view *v)
{
    float view_proj[16];
    pelt__mat4_mul(view_proj, v->proj, v->view);
    pelt_renderer_upload(r);

    glBindVertexArray(r->vao);
    glActiveTexture(GL_TEXTURE0 + UNIT_FUR);
    glBindTexture(GL_TEXTURE_2D_ARRAY, r->fur_texture);
    glActiveTexture(GL_TEXTURE0 + UNIT_COLOR);
    glBindTexture(GL_TEXTURE_2D, r->color_texture);
    glActiveTexture(GL_TEXTURE0 + UNIT_MASK);
    glBindTexture(GL_TEXTURE_2D, r->mask_texture);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDisable(GL_CULL_FACE);

    if (!r->desc.no_skin) {
        glDepthMask(GL_TRUE);
        glDisable(GL_BLEND);
        glUseProgram(r->skin_program);
        set_common(r, &r->skin_u, v, view_proj);
        glDrawElements(GL_TRIANGLES, r->index_count, GL_UNSIGNED_INT, NULL);
    }
    r->shell_draw_calls = 0;
    unsigned layers = pelt_fur_get_desc(r->fur).layers, first = r->desc.first_layer;
    unsigned count = first >= layers ? 0 : layers - first;
    if (r->desc.layer_count && r->desc.layer_count < count) count = r->desc.layer_count;
    if (!r->desc.no_shells && count > 0) {
        glDepthMask(GL_FALSE);
        glEnable(GL_BLEND);
        /* Alpha accumulates as coverage, so an opaque background stays opaque. */
        glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        glUseProgram(r->shell_program);
        set_common(r, &r->shell_u, v, view_proj);
        glUniform1f(r->shell_u.first_layer, (float)first);
        /* Instances are drawn in order, so layers blend inner to outer. */
        glDrawElementsInstanced(GL_TRIANGLES, r->index_count, GL_UNSIGNED_INT, NULL,
                                (GLsizei)count);
        r->shell_draw_calls++;
        glDepthMask(GL_TRUE);
        glDisable(GL_BLEND);
    }
    glUseProgram(0);
    glBindVertexArray(0);
}

unsigned pelt_renderer_shell_draw_calls(const pelt_renderer *r) { return r->shell_draw_calls; }
