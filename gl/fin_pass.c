/* Fins (Lengyel et al. 2001 §2.3 pass 2): after the skin, before the
 * shells, every fin in ONE instanced draw, blended, depth tested without
 * depth write. Each frame the fins the view may show are gathered on the
 * CPU ("we collect the fins with nonzero alpha") into a table texture; an
 * instance draws PELT_FIN_CHUNK of them, each a strip rising along the
 * displaced strands of the edge's two vertices, read from the vertex
 * tables (gl/gpu_mesh.c). The exact fade (shaders/fins.glsl) still
 * collapses the faded ones in the vertex stage. */
#include "gl/passes.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/vec.h"
#include "core/fur/fur_gpu.h"
#include "gl/programs.h"

#include <string.h>

/* A fin program with `features` (PELT__FIN_FEATURES bits) compiled in, as
 * the shells' variants (gl/shell_pass.c); PELT__FIN_FEATURES is generic. */
static pelt_status build(pelt__fin_pass *p, unsigned features, pelt_error *err)
{
    static const struct { unsigned bit; const char *define; } defines[] = {
        {PELT__SHELL_WET, "#define PELT_WET 1\n"},
        {PELT__SHELL_COLOR_TEXTURE, "#define PELT_COLOR_TEXTURE 1\n"},
        {PELT__SHELL_KAJIYA_KAY, "#define PELT_SHADING_KK 1\n"},
        {PELT__SHELL_LIGHT_TABLE, "#define PELT_SHADING_TABLE 1\n"},
    };
    const char *fs[8], *vs[10];
    int n = 0;
    for (size_t k = 0; k < sizeof defines / sizeof defines[0]; k++)
        if (features & defines[k].bit) fs[n++] = defines[k].define;
    memcpy(vs, fs, (size_t)n * sizeof *fs);
    int m = n;
    fs[n++] = pelt__shader_shading;
    fs[n++] = pelt__shader_fin_fs;
    fs[n] = NULL;
    vs[m++] = pelt__shader_shading;
    vs[m++] = pelt__shader_fur_light;
    vs[m++] = pelt__shader_fur_shape;
    vs[m++] = pelt__shader_fins;
    vs[m++] = pelt__shader_fin_vs;
    vs[m] = NULL;
    pelt_status st = pelt__gl_program_create("fin", vs, fs, &p->hooks, &p->variants[features], err);
    if (st != PELT_OK) {
        p->failed[features] = true;
        return st;
    }
    p->unfaded[features] = glGetUniformLocation(p->variants[features], "u_unfaded");
    p->fin_count[features] = glGetUniformLocation(p->variants[features], "u_fin_count");
    p->fin_rows[features] = glGetUniformLocation(p->variants[features], "u_fin_rows");
    return PELT_OK;
}

pelt_status pelt__fin_pass_create(pelt__fin_pass *p, pelt_fur *fur, const pelt_hooks *hooks,
                                  pelt_error *err)
{
    memset(p, 0, sizeof *p);
    p->hooks = *hooks;
    pelt_status st = build(p, PELT__FIN_FEATURES, err);
    if (st != PELT_OK) return st;

    /* The fin texture: repeats along the fin, clamped at root and tip. */
    pelt__gl_unpack_defaults();
    unsigned w, h;
    const uint8_t *texels = pelt__fur_gpu_fin_texture(fur, &w, &h);
    glGenTextures(1, &p->texture);
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_FIN);
    glBindTexture(GL_TEXTURE_2D, p->texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, (GLsizei)w, (GLsizei)h, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glGenerateMipmap(GL_TEXTURE_2D);

    /* The fins of every level (core/fur/lod.h); a frame's go to the table. */
    const pelt__lod_chain *lod = pelt__fur_gpu_lod(fur);
    size_t most = 0;
    for (unsigned k = 0; k < lod->count; k++)
        if (lod->levels[k].fin_count > most) most = lod->levels[k].fin_count;
    p->lod = lod;
    p->alloc = hooks->allocator;
    p->staging = pelt__alloc(&p->alloc, (most ? most : 1) * sizeof *p->staging);
    p->texels = pelt__alloc(&p->alloc, (most ? most : 1) * 4 * sizeof *p->texels);
    if (!p->staging || !p->texels) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for %zu fins", most);
    size_t rows = (most + PELT_TABLE_WIDTH - 1) / PELT_TABLE_WIDTH;
    glGenTextures(1, &p->edges);
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_FIN_EDGES);
    glBindTexture(GL_TEXTURE_2D, p->edges);
    /* RGBA, not RGB: an RGB upload makes Mesa convert (and allocate) each time. */
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32UI, PELT_TABLE_WIDTH, (GLsizei)(rows ? rows : 1), 0, GL_RGBA_INTEGER,
                 GL_UNSIGNED_INT, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);

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

/* Writes fins [0, count) into the table (a, b, start bits, 0 per texel),
 * whole rows then the last one. */
static void write_table(const pelt__fin_pass *p, const pelt__fin_edge *fins, size_t count)
{
    uint32_t *t = p->texels;
    for (size_t i = 0; i < count; i++) {
        t[4 * i] = fins[i].a;
        t[4 * i + 1] = fins[i].b;
        memcpy(&t[4 * i + 2], &fins[i].start, sizeof(uint32_t));
        t[4 * i + 3] = 0;
    }
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_FIN_EDGES);
    glBindTexture(GL_TEXTURE_2D, p->edges);
    size_t rows = count / PELT_TABLE_WIDTH, rest = count % PELT_TABLE_WIDTH;
    if (rows)
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, PELT_TABLE_WIDTH, (GLsizei)rows, GL_RGBA_INTEGER, GL_UNSIGNED_INT, t);
    if (rest)
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, (GLint)rows, (GLsizei)rest, 1, GL_RGBA_INTEGER, GL_UNSIGNED_INT,
                        t + 4 * rows * PELT_TABLE_WIDTH);
}

void pelt__fin_pass_draw(pelt__fin_pass *p, const pelt__pass_frame *f)
{
    unsigned level = f->lod.full_mesh ? 0 : f->lod.mesh_level;
    const pelt__lod_level *l = &p->lod->levels[level];
    size_t count = l->fin_count;
    const pelt__fin_edge *fins = l->fins;
    if (count == 0) return;
    if (!f->draw->fins_unfaded) {
        /* The view direction in mesh space: the transpose of the model's
         * rotation (exact for rotations and uniform scale; the margin
         * covers mild non-uniform scale). */
        const float *m = f->view->model, *v = f->view->view;
        pelt_vec3 fwd = v3(-v[2], -v[6], -v[10]);
        pelt_vec3 local = v3(m[0] * fwd.x + m[1] * fwd.y + m[2] * fwd.z, m[4] * fwd.x + m[5] * fwd.y + m[6] * fwd.z,
                             m[8] * fwd.x + m[9] * fwd.y + m[10] * fwd.z);
        local = v3_norm_or(local, v3(0.0f, 0.0f, -1.0f));
        count = pelt__fins_facing(l->fins, l->fin_normals, l->fin_count, local, 0.05f, p->staging);
        if (count == 0) return;
        fins = p->staging;
    }
    write_table(p, fins, count);
    pelt__gl_blended_hair_state();
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_FIN);
    glBindTexture(GL_TEXTURE_2D, p->texture);
    unsigned features = f->shell_features & PELT__FIN_FEATURES;
    if (!p->variants[features] && !p->failed[features]) build(p, features, NULL);
    if (!p->variants[features]) features = PELT__FIN_FEATURES;
    glUseProgram(p->variants[features]);
    glUniform1i(p->unfaded[features], f->draw->fins_unfaded ? 1 : 0);
    glUniform1i(p->fin_count[features], (GLint)count);
    unsigned rows = f->lod.fin_rows ? f->lod.fin_rows : PELT_FIN_ROWS;
    glUniform1i(p->fin_rows[features], (GLint)rows);
    glBindVertexArray(p->vao);
    const size_t at = (rows - 1) * PELT_FIN_CHUNK * 6 * PELT_FIN_ROWS * sizeof(uint32_t);
    glDrawElementsInstanced(GL_TRIANGLES, (GLsizei)(6 * rows * PELT_FIN_CHUNK), GL_UNSIGNED_INT, (const void *)at,
                            (GLsizei)((count + PELT_FIN_CHUNK - 1) / PELT_FIN_CHUNK));
    glBindVertexArray(f->mesh->vao);
    f->stats->fin_draw_calls++;
    f->stats->fins += count;
    f->stats->triangles += count * 2 * rows;
}

void pelt__fin_pass_destroy(pelt__fin_pass *p)
{
    for (int k = 0; k < PELT__SHELL_VARIANTS; k++)
        if (p->variants[k]) glDeleteProgram(p->variants[k]);
    if (p->ebo) glDeleteBuffers(1, &p->ebo);
    if (p->edges) glDeleteTextures(1, &p->edges);
    pelt__free(&p->alloc, p->staging);
    pelt__free(&p->alloc, p->texels);
    if (p->vao) glDeleteVertexArrays(1, &p->vao);
    if (p->texture) glDeleteTextures(1, &p->texture);
    memset(p, 0, sizeof *p);
}
