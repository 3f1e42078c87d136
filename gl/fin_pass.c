/* Fins (Lengyel et al. 2001 §2.3 pass 2): after the skin, before the
 * shells, every fin in ONE instanced draw, blended, depth tested without
 * depth write. Each frame the fins the view shows and their fade ("we
 * collect the fins with nonzero alpha"), and the displaced strands of the
 * vertices they stand on, come from core/fur/fin_frame.c into two table
 * textures; an instance draws PELT_FIN_CHUNK fins, each a strip rising
 * along the strands of its two ends. */
#include "gl/passes.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/vec.h"
#include "core/fur/fur_gpu.h"
#include "gl/programs.h"

#include <math.h>
#include <string.h>

/* A table texture of `texels` RGBA texels (32-bit), PELT_TABLE_WIDTH a
 * row. RGBA, not RGB: an RGB upload makes Mesa convert (and allocate). */
static GLuint table_create(GLenum unit, GLenum internal, size_t texels)
{
    GLuint t;
    glGenTextures(1, &t);
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, t);
    size_t rows = (texels + PELT_TABLE_WIDTH - 1) / PELT_TABLE_WIDTH;
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, PELT_TABLE_WIDTH, (GLsizei)(rows ? rows : 1), 0,
                 internal == GL_RGBA32UI ? GL_RGBA_INTEGER : GL_RGBA,
                 internal == GL_RGBA32UI ? GL_UNSIGNED_INT : GL_FLOAT, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    return t;
}

/* A fin program with `features` (PELT__FIN_FEATURES bits) compiled in, as
 * the shells' variants (gl/shell_pass.c); PELT__FIN_FEATURES is generic. */
static pelt_status build(pelt__fin_pass *p, unsigned features, pelt_error *err)
{
    char defines[PELT__FEATURE_DEFINES_MAX];
    pelt__shell_feature_defines(features & PELT__FIN_FEATURES, defines);
    const char *vs[] = {defines,                   pelt__shader_shading,   pelt__shader_shadow_map,
                        pelt__shader_fur_light,    pelt__shader_fur_shape, pelt__shader_own_light,
                        pelt__shader_outline_hair, pelt__shader_fin_table, pelt__shader_fin_vs, NULL};
    const char *fs[] = {defines,           pelt__shader_shading,   pelt__shader_fur_shape, pelt__shader_own_light,
                        pelt__shader_clump, pelt__shader_shell_lod, pelt__shader_fin_fs,    NULL};
    pelt_status st = pelt__gl_program_create("fin", vs, fs, &p->hooks, &p->variants[features], err);
    if (st != PELT_OK) {
        p->failed[features] = true;
        return st;
    }
    p->fin_count[features] = glGetUniformLocation(p->variants[features], "u_fin_count");
    p->fin_rows[features] = glGetUniformLocation(p->variants[features], "u_fin_rows");
    p->fin_first[features] = glGetUniformLocation(p->variants[features], "u_fin_first");
    p->fin_hairs[features] = glGetUniformLocation(p->variants[features], "u_outline_on");
    p->fin_viewport[features] = glGetUniformLocation(p->variants[features], "u_viewport");
    return PELT_OK;
}

/* The outline's hairs' program with `features` (PELT__OUTLINE_FEATURES
 * bits), built on first use; false where it does not build. */
static bool build_outline(pelt__fin_pass *p, unsigned features)
{
    if (p->outline[features]) return true;
    if (p->outline_failed[features]) return false;
    char defines[PELT__FEATURE_DEFINES_MAX];
    pelt__shell_feature_defines(features, defines);
    const char *vs[] = {defines,                   pelt__shader_shading,   pelt__shader_shadow_map,
                        pelt__shader_fur_light,    pelt__shader_outline_hair, pelt__shader_fin_table,
                        pelt__shader_outline_vs,   NULL};
    const char *fs[] = {pelt__shader_shading, pelt__shader_outline_fs, NULL};
    GLuint prog = 0;
    if (pelt__gl_program_create("outline", vs, fs, &p->hooks, &prog, NULL) != PELT_OK) {
        p->outline_failed[features] = true;
        return false;
    }
    p->outline[features] = prog;
    p->outline_count[features] = glGetUniformLocation(prog, "u_fin_count");
    p->outline_rows[features] = glGetUniformLocation(prog, "u_fin_rows");
    p->outline_hairs[features] = glGetUniformLocation(prog, "u_outline_hairs");
    p->outline_viewport[features] = glGetUniformLocation(prog, "u_viewport");
    return true;
}

/* The hairs a fur tile of a fin's edge holds: fins.hairs, the share of
 * the fin slab's (look.density a tile, fins.density texels of the tile's
 * texture_size wide), from the resolved desc. */
static float outline_hairs_per_tile(const pelt_fur_desc *d)
{
    return d->fins.hairs * d->look.density * d->fins.density / (float)d->look.texture_size;
}

pelt_status pelt__fin_pass_create(pelt__fin_pass *p, pelt_fur *fur, const pelt__fur_snapshot *fs,
                                  const pelt_hooks *hooks, pelt_error *err)
{
    memset(p, 0, sizeof *p);
    p->hooks = *hooks;
    pelt_status st = build(p, PELT__FIN_FEATURES, err);
    if (st != PELT_OK) return st;

    /* The fin texture: repeats along the fin, clamped at root and tip; a
     * layer a ringlet level, as the fur volume (wet fins lose their curl). */
    pelt__gl_unpack_defaults();
    glGenTextures(1, &p->texture);
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_FIN);
    glBindTexture(GL_TEXTURE_2D_ARRAY, p->texture);
    unsigned fw = fs->fin_width, fh = fs->fin_height;
    uint8_t *chain = pelt__alloc(&hooks->allocator, pelt__gpu_hair_chain_bytes(fw, fh));
    if (!chain) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the fin texture's mip chain");
    pelt__gpu_hair_array_create(fw, fh, fs->ringlet_levels);
    for (unsigned k = 0; k < fs->ringlet_levels; k++)
        pelt__gpu_hair_array_slice(k, fs->fin_texture + (size_t)k * fw * fh * 4, fw, fh, chain);
    pelt__free(&hooks->allocator, chain);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

    /* Room for the most fins and fin vertices any level has. */
    _Static_assert(PELT__FIN_HEIGHTS == PELT_FIN_HEIGHTS && PELT__FIN_VERTEX_TEXELS == PELT_FIN_VERTEX_TEXELS &&
                       PELT_FIN_ROWS < PELT_FIN_HEIGHTS,
                   "core/fur/fur_gpu.h and bindings.glsl agree on the fin vertices");
    const pelt__lod_chain *lod = fs->lod;
    size_t most = 0, most_vertices = 0;
    for (unsigned k = 0; k < lod->count; k++) {
        if (lod->levels[k].fin_count > most) most = lod->levels[k].fin_count;
        if (lod->levels[k].fin_vertex_count > most_vertices) most_vertices = lod->levels[k].fin_vertex_count;
    }
    p->fur = fur;
    p->lod = lod;
    p->alloc = hooks->allocator;
    p->fins = pelt__alloc(&p->alloc, (most ? most : 1) * 4 * sizeof *p->fins);
    p->vertices = pelt__alloc(&p->alloc, (most_vertices ? most_vertices : 1) * 4 * PELT_FIN_VERTEX_TEXELS * sizeof(float));
    if (!p->fins || !p->vertices) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for %zu fins", most);
    p->edges = table_create(PELT_UNIT_FIN_EDGES, GL_RGBA32UI, most);
    p->vertex_table = table_create(PELT_UNIT_FIN_VERTICES, GL_RGBA32F, most_vertices * PELT_FIN_VERTEX_TEXELS);
    /* The outline's hairs: a table of their own. */
    const pelt_fur_desc d = pelt_fur_get_desc(fur);
    p->hairs_per_tile = outline_hairs_per_tile(&d);
    p->tiling = d.look.tiling;
    p->slab = d.fins.density / (float)d.look.texture_size;
    /* Fur that curls in its texture keeps the fin texture's quads, which
     * carry its ringlets and curl (the hairs rise along the vertex strands
     * alone). */
    p->curled = fs->ringlet_levels > 1 || d.look.strand_curl > 0.0f || d.fins.curl > 0.0f;
    if (p->hairs_per_tile > 0.0f) {
        p->hairs = pelt__alloc(&p->alloc, PELT__OUTLINE_HAIR_BUDGET * 4 * sizeof *p->hairs);
        if (!p->hairs) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the outline's hairs");
        p->hair_table = table_create(PELT_UNIT_FIN_EDGES, GL_RGBA32UI, PELT__OUTLINE_HAIR_BUDGET);
    }

    /* One chunk of PELT_FIN_CHUNK strips of r quads as triangles, for each
     * r = 1 .. PELT_FIN_ROWS one after the other: fin c's corner k is vertex
     * c * corners + k, so the vertex cache shades each corner once. */
    enum { MAX_INDICES = PELT_FIN_CHUNK * 6 * PELT_FIN_ROWS };
    uint32_t indices[MAX_INDICES];
    glGenVertexArrays(1, &p->vao);
    glBindVertexArray(p->vao);
    glGenBuffers(1, &p->ebo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, p->ebo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(PELT_FIN_ROWS * sizeof indices), NULL, GL_STATIC_DRAW);
    for (uint32_t r = 1; r <= PELT_FIN_ROWS; r++) {
        uint32_t corners = 2 * (r + 1);
        for (uint32_t c = 0; c < PELT_FIN_CHUNK; c++)
            for (uint32_t q = 0; q < r; q++) {
                uint32_t *t = indices + (c * r + q) * 6, v = c * corners + 2 * q;
                t[0] = v, t[1] = v + 1, t[2] = v + 2, t[3] = v + 1, t[4] = v + 3, t[5] = v + 2;
            }
        glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, (GLintptr)((r - 1) * sizeof indices),
                        (GLsizeiptr)(PELT_FIN_CHUNK * 6 * r * sizeof(uint32_t)), indices);
    }
    glBindVertexArray(0);
    return PELT_OK;
}

/* Writes texels [0, count) of a table (4 words or floats each), whole
 * rows then the last one. */
static void table_write(GLenum unit, GLuint t, GLenum internal, const void *texels, size_t count)
{
    GLenum format = internal == GL_RGBA32UI ? GL_RGBA_INTEGER : GL_RGBA;
    GLenum type = internal == GL_RGBA32UI ? GL_UNSIGNED_INT : GL_FLOAT;
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, t);
    size_t rows = count / PELT_TABLE_WIDTH, rest = count % PELT_TABLE_WIDTH;
    const uint8_t *bytes = texels;
    if (rows) glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, PELT_TABLE_WIDTH, (GLsizei)rows, format, type, bytes);
    if (rest)
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, (GLint)rows, (GLsizei)rest, 1, format, type,
                        bytes + rows * PELT_TABLE_WIDTH * 16);
}

/* Fins [first, end) of the table with the variant of `features` (the
 * generic one where that fails to build), in instances of PELT_FIN_CHUNK. */
/* `count` strips of `rows` quads (fins or the outline's hairs), PELT_FIN_CHUNK
 * an instance: the element buffer's chunk of strips with that many rows. */
static void draw_strips(unsigned rows, size_t count)
{
    const size_t at = (rows - 1) * PELT_FIN_CHUNK * 6 * PELT_FIN_ROWS * sizeof(uint32_t);
    glDrawElementsInstanced(GL_TRIANGLES, (GLsizei)(6 * rows * PELT_FIN_CHUNK), GL_UNSIGNED_INT, (const void *)at,
                            (GLsizei)((count + PELT_FIN_CHUNK - 1) / PELT_FIN_CHUNK));
}

static void draw_fins(pelt__fin_pass *p, const pelt__pass_frame *f, unsigned features, size_t first, size_t end,
                      unsigned rows)
{
    if (end <= first) return;
    if (!p->variants[features] && !p->failed[features]) build(p, features, NULL);
    if (!p->variants[features]) features = PELT__FIN_FEATURES;
    glUseProgram(p->variants[features]);
    glUniform1i(p->fin_first[features], (GLint)first);
    glUniform1i(p->fin_count[features], (GLint)end);
    glUniform1i(p->fin_rows[features], (GLint)rows);
    glUniform1i(p->fin_hairs[features], p->hairs_on);
    if (p->hairs_on) glUniform2f(p->fin_viewport[features], p->viewport[0], p->viewport[1]);
    draw_strips(rows, end - first);
    f->stats->fin_draw_calls++;
}

/* The outline's hairs of the fins the fin pass wrote this frame: one table
 * entry a hair (pelt__outline_hairs), PELT_FIN_CHUNK hairs an instance,
 * each a strip of the fins' rows (the fins' chunks of strips). */
void pelt__fin_pass_draw_outline(pelt__fin_pass *p, const pelt__pass_frame *f)
{
    size_t fins = p->frame_fins;
    unsigned rows = p->frame_rows;
    p->frame_fins = 0;
    float hairs = p->hairs_per_tile;
    unsigned features = f->shell_features & PELT__OUTLINE_FEATURES;
    if (!p->hairs_on || fins == 0 || !build_outline(p, features)) return;
    /* The eye in mesh units: the model's inverse (rotation, uniform scale
     * and translation) applied to it. */
    const float *m = f->view->model, *e = f->view->eye;
    float view_proj[16]; /* as the frame block's u_view_proj */
    pelt__mat4_mul(view_proj, f->view->proj, f->view->view);
    float s2 = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];
    float dx = e[0] - m[12], dy = e[1] - m[13], dz = e[2] - m[14];
    pelt__outline_frame of = {p->vertices,
                              4 * PELT_FIN_VERTEX_TEXELS,
                              4 * 2 * PELT_FIN_HEIGHTS,
                              {(m[0] * dx + m[1] * dy + m[2] * dz) / s2, (m[4] * dx + m[5] * dy + m[6] * dz) / s2,
                               (m[8] * dx + m[9] * dy + m[10] * dz) / s2},
                              sqrtf(s2) * p->tiling,
                              p->slab,
                              hairs,
                              PELT__OUTLINE_LEAST_FADE,
                              view_proj,
                              m,
                              {p->viewport[0], p->viewport[1]},
                              4 * 2 * (size_t)rows};
    size_t count = pelt__outline_hairs(p->fins, fins, &of, p->hairs, PELT__OUTLINE_HAIR_BUDGET);
    if (count == 0) return;
    table_write(PELT_UNIT_FIN_EDGES, p->hair_table, GL_RGBA32UI, p->hairs, count);
    f->stats->upload_bytes += 16 * count;
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_FIN_VERTICES);
    glBindTexture(GL_TEXTURE_2D, p->vertex_table);
    pelt__gl_blended_hair_state();
    glBindVertexArray(p->vao);
    glUseProgram(p->outline[features]);
    glUniform1i(p->outline_count[features], (GLint)count);
    glUniform1i(p->outline_rows[features], (GLint)rows);
    glUniform1f(p->outline_hairs[features], hairs);
    glUniform2f(p->outline_viewport[features], p->viewport[0], p->viewport[1]);
    draw_strips(rows, count);
    f->stats->outline_hairs = count;
    f->stats->triangles += count * 2 * rows;
    glBindVertexArray(f->mesh->vao);
}

void pelt__fin_pass_draw(pelt__fin_pass *p, const pelt__pass_frame *f)
{
    unsigned level = f->lod.full_mesh ? 0 : f->lod.fin_level;
    const pelt__lod_level *l = &p->lod->levels[level];
    /* The view direction in mesh space: the transpose of the model's
     * rotation (exact for rotations and uniform scale). */
    const float *m = f->view->model, *v = f->view->view;
    pelt_vec3 fwd = v3(-v[2], -v[6], -v[10]);
    pelt_vec3 local = v3(m[0] * fwd.x + m[1] * fwd.y + m[2] * fwd.z, m[4] * fwd.x + m[5] * fwd.y + m[6] * fwd.z,
                         m[8] * fwd.x + m[9] * fwd.y + m[10] * fwd.z);
    local = v3_norm_or(local, v3(0.0f, 0.0f, -1.0f));
    /* Where the shells' back faces are culled and the skin is drawn, it hides the fins behind too.
     * Wet fins drawn apart from dry ones, as the shells are (gl/shell_pass.c):
     * on the full mesh, whose vertices the wet split marks. */
    const unsigned wet_bits = PELT__SHELL_WET;
    const pelt__gpu_mesh *mesh = f->mesh;
    bool split = (f->shell_features & wet_bits) && level == 0 && mesh->split_ok && !f->draw->debug.no_wet_split;
    pelt__fin_frame_desc fd = {level, PELT_FIN_ROWS, f->lod.fin_row_error, {local.x, local.y, local.z},
                               f->draw->fins_unfaded, f->lod.cull && !f->draw->no_skin,
                               split ? mesh->split.vertex_wet : NULL,
                               f->lod.sub_shells > 1 ? 1.0f / (float)f->lod.sub_shells : 1.0f};
    unsigned rows;
    size_t dry = 0;
    size_t count = pelt__fur_gpu_fin_frame(p->fur, &fd, p->fins, p->vertices, &rows, &dry);
    p->frame_fins = count;
    p->frame_rows = rows;
    p->hairs_on = p->hairs && !p->curled && !f->draw->no_outline_hairs && !f->draw->fins_unfaded;
    /* A hair's length and width in pixels need the viewport's: the view's,
     * or GL's where the view leaves it out (0). */
    p->viewport[0] = (float)f->view->width, p->viewport[1] = (float)f->view->height;
    if (p->hairs_on && (f->view->width == 0 || f->view->height == 0)) {
        GLint vp[4];
        glGetIntegerv(GL_VIEWPORT, vp);
        p->viewport[0] = (float)vp[2], p->viewport[1] = (float)vp[3];
    }
    if (count == 0) return;
    table_write(PELT_UNIT_FIN_VERTICES, p->vertex_table, GL_RGBA32F, p->vertices,
                l->fin_vertex_count * PELT_FIN_VERTEX_TEXELS);
    f->stats->upload_bytes += 16 * l->fin_vertex_count * PELT_FIN_VERTEX_TEXELS;
    f->stats->fins += count;
    f->stats->fin_rows = rows;
    table_write(PELT_UNIT_FIN_EDGES, p->edges, GL_RGBA32UI, p->fins, count);
    f->stats->upload_bytes += 16 * count;
    pelt__gl_blended_hair_state();
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_FIN);
    glBindTexture(GL_TEXTURE_2D_ARRAY, p->texture);
    glBindVertexArray(p->vao);
    unsigned features = f->shell_features & PELT__FIN_FEATURES;
    if (split) {
        draw_fins(p, f, features & ~wet_bits, 0, dry, rows);
        draw_fins(p, f, features, dry, count, rows);
    } else {
        draw_fins(p, f, features, 0, count, rows);
    }
    glBindVertexArray(f->mesh->vao);
    f->stats->triangles += count * 2 * rows;
}

void pelt__fin_pass_destroy(pelt__fin_pass *p)
{
    for (int k = 0; k < PELT__FIN_VARIANTS; k++)
        if (p->variants[k]) glDeleteProgram(p->variants[k]);
    for (int k = 0; k <= PELT__OUTLINE_FEATURES; k++)
        if (p->outline[k]) glDeleteProgram(p->outline[k]);
    if (p->ebo) glDeleteBuffers(1, &p->ebo);
    if (p->edges) glDeleteTextures(1, &p->edges);
    if (p->vertex_table) glDeleteTextures(1, &p->vertex_table);
    pelt__free(&p->alloc, p->fins);
    pelt__free(&p->alloc, p->vertices);
    pelt__free(&p->alloc, p->hairs);
    if (p->hair_table) glDeleteTextures(1, &p->hair_table);
    if (p->vao) glDeleteVertexArrays(1, &p->vao);
    if (p->texture) glDeleteTextures(1, &p->texture);
    memset(p, 0, sizeof *p);
}
