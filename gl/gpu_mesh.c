/* Vertex and index buffers: the mesh's attributes (through the public
 * pelt_mesh_get_data) with the fur's per-vertex data (core/fur/fur_gpu.h),
 * one VAO that every pass draws. The strand tips change every frame, so
 * they live in their own buffer, rewritten in place. */
#include "gl/gpu.h"

#include "core/base/error.h"
#include "core/fur/fur_gpu.h"

#include <string.h>

/* ---- vertex tables: per-vertex data as textures, PELT_TABLE_WIDTH texels
 * a row, for passes that fetch a vertex by index (the fins). ---- */

static GLuint table_create(GLenum internal, size_t texels)
{
    GLuint t;
    glGenTextures(1, &t);
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_VERTICES);
    glBindTexture(GL_TEXTURE_2D, t);
    size_t rows = (texels + PELT_TABLE_WIDTH - 1) / PELT_TABLE_WIDTH;
    GLenum format = internal == GL_R32UI ? GL_RED_INTEGER : GL_RGBA;
    GLenum type = internal == GL_R32UI ? GL_UNSIGNED_INT : GL_FLOAT;
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, PELT_TABLE_WIDTH, (GLsizei)(rows ? rows : 1), 0,
                 format, type, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    return t;
}

/* Writes texels [first, first + count) of a table, a partial first row,
 * whole rows, a partial last row; `data` points at texel `first`. */
static void table_write(GLuint t, GLenum internal, size_t first, size_t count, const void *data,
                        size_t texel_bytes)
{
    GLenum format = internal == GL_R32UI ? GL_RED_INTEGER : GL_RGBA;
    GLenum type = internal == GL_R32UI ? GL_UNSIGNED_INT : GL_FLOAT;
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_VERTICES);
    glBindTexture(GL_TEXTURE_2D, t);
    const uint8_t *p = data;
    while (count > 0) {
        size_t x = first % PELT_TABLE_WIDTH, y = first / PELT_TABLE_WIDTH;
        size_t n = PELT_TABLE_WIDTH - x;
        size_t rows = 1;
        if (x == 0 && count >= PELT_TABLE_WIDTH) {
            rows = count / PELT_TABLE_WIDTH;
            n = PELT_TABLE_WIDTH;
        } else if (n > count) {
            n = count;
        }
        glTexSubImage2D(GL_TEXTURE_2D, 0, (GLint)x, (GLint)y, (GLsizei)n, (GLsizei)rows, format, type, p);
        p += n * rows * texel_bytes;
        first += n * rows;
        count -= n * rows;
    }
}

/* The tips as the tip table wants them: 4 floats per vertex. */
static void write_tips(pelt__gpu_mesh *g, const float *tips)
{
    for (size_t i = 0; i < g->vertex_count; i++) {
        memcpy(g->tip_staging + 4 * i, tips + 3 * i, 3 * sizeof(float));
        g->tip_staging[4 * i + 3] = 0.0f;
    }
    table_write(g->table_tips, GL_RGBA32F, 0, g->vertex_count, g->tip_staging, 4 * sizeof(float));
}

/* The static table from the interleaved vertex data (layout of attrs). */
static pelt_status make_tables(pelt__gpu_mesh *g, const float *interleaved, unsigned floats,
                               pelt_fur *fur, pelt_error *err)
{
    size_t n = g->vertex_count;
    float *t = pelt__alloc_zero(&g->alloc, n ? n : 1, 4 * PELT_TABLE_TEXELS * sizeof(float));
    g->tip_staging = pelt__alloc_zero(&g->alloc, n ? n : 1, 4 * sizeof(float));
    if (!t || !g->tip_staging) {
        pelt__free(&g->alloc, t);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the vertex tables");
    }
    for (size_t i = 0; i < n; i++) {
        const float *v = interleaved + i * floats; /* pos 3, normal 3, uv 2, fur uv 2, tangent 4, comb 3 */
        float *o = t + i * 4 * PELT_TABLE_TEXELS;
        memcpy(o, v, 3 * sizeof(float));
        o[3] = v[13];                         /* tangent handedness */
        memcpy(o + 4, v + 3, 3 * sizeof(float));
        memcpy(o + 8, v + 10, 3 * sizeof(float));
        memcpy(o + 12, v + 6, 4 * sizeof(float)); /* uv, fur uv */
        memcpy(o + 16, v + 14, 3 * sizeof(float));
    }
    g->table_vertices = table_create(GL_RGBA32F, n * PELT_TABLE_TEXELS);
    table_write(g->table_vertices, GL_RGBA32F, 0, n * PELT_TABLE_TEXELS, t, 4 * sizeof(float));
    pelt__free(&g->alloc, t);
    g->table_tips = table_create(GL_RGBA32F, n);
    unsigned version;
    write_tips(g, pelt__fur_gpu_tips(fur, &version));
    size_t stride;
    const void *groom = pelt__fur_gpu_groom(fur, &stride);
    g->table_groom = table_create(GL_R32UI, n * PELT_GROOM_WORDS);
    table_write(g->table_groom, GL_R32UI, 0, n * PELT_GROOM_WORDS, groom, 4);
    return PELT_OK;
}

/* One interleaved attribute: where it comes from and where it goes. */
typedef struct attribute {
    GLuint location;      /* PELT_ATTR_* */
    unsigned size;        /* floats */
    const float *source;  /* per vertex, `stride` floats apart */
    unsigned stride;
} attribute;

pelt_status pelt__gpu_mesh_create(pelt__gpu_mesh *g, const pelt_mesh *mesh, pelt_fur *fur,
                                  const pelt_hooks *hooks, pelt_error *err)
{
    const pelt_mesh_data m = pelt_mesh_get_data(mesh);
    const float *tangents = pelt_mesh_tangents(mesh);
    /* Without a direction field, comb along the fur texture's u axis. */
    const attribute attrs[] = {
        {PELT_ATTR_POSITION, 3, m.positions, 3},
        {PELT_ATTR_NORMAL, 3, m.normals, 3},
        {PELT_ATTR_UV, 2, m.uvs, 2},
        {PELT_ATTR_FUR_UV, 2, pelt__fur_gpu_uvs(fur), 2},
        {PELT_ATTR_TANGENT, 4, tangents, 4},
        {PELT_ATTR_COMB, 3, m.comb ? m.comb : tangents, m.comb ? 3 : 4},
    };
    enum { ATTRS = sizeof attrs / sizeof attrs[0] };
    unsigned floats = 0;
    for (int k = 0; k < ATTRS; k++) floats += attrs[k].size;

    g->vertex_count = m.vertex_count;
    g->triangle_count = m.triangle_count;
    g->alloc = hooks->allocator;
    float *data = pelt__alloc_zero(&hooks->allocator, m.vertex_count, floats * sizeof(float));
    if (!data) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for vertex data");
    for (size_t i = 0; i < m.vertex_count; i++) {
        float *v = data + i * floats;
        for (int k = 0; k < ATTRS; k++) {
            memcpy(v, attrs[k].source + i * attrs[k].stride, attrs[k].size * sizeof(float));
            v += attrs[k].size;
        }
    }
    glGenVertexArrays(1, &g->vao);
    glBindVertexArray(g->vao);
    glGenBuffers(1, &g->vbo_static);
    glBindBuffer(GL_ARRAY_BUFFER, g->vbo_static);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(m.vertex_count * floats * sizeof(float)), data,
                 GL_STATIC_DRAW);
    pelt_status st = make_tables(g, data, floats, fur, err);
    pelt__free(&hooks->allocator, data);
    if (st != PELT_OK) return st;
    glBindBuffer(GL_ARRAY_BUFFER, g->vbo_static);
    size_t offset = 0;
    for (int k = 0; k < ATTRS; k++) {
        glEnableVertexAttribArray(attrs[k].location);
        glVertexAttribPointer(attrs[k].location, (GLint)attrs[k].size, GL_FLOAT, GL_FALSE,
                              (GLsizei)(floats * sizeof(float)), (const void *)offset);
        offset += attrs[k].size * sizeof(float);
    }

    glGenBuffers(1, &g->vbo_tips);
    glBindBuffer(GL_ARRAY_BUFFER, g->vbo_tips);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(m.vertex_count * 3 * sizeof(float)),
                 pelt__fur_gpu_tips(fur, &g->tips_version), GL_DYNAMIC_DRAW);
    glEnableVertexAttribArray(PELT_ATTR_TIP);
    glVertexAttribPointer(PELT_ATTR_TIP, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), NULL);

    /* The groom: one 20-byte record per vertex (core/fur/groom.h), lean,
     * length and density as floats, the hair colour as 4 normalised bytes. */
    size_t stride;
    const void *groom = pelt__fur_gpu_groom(fur, &stride);
    glGenBuffers(1, &g->vbo_groom);
    glBindBuffer(GL_ARRAY_BUFFER, g->vbo_groom);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(m.vertex_count * stride), groom, GL_DYNAMIC_DRAW);
    glEnableVertexAttribArray(PELT_ATTR_GROOM);
    glVertexAttribPointer(PELT_ATTR_GROOM, 4, GL_FLOAT, GL_FALSE, (GLsizei)stride, NULL);
    glEnableVertexAttribArray(PELT_ATTR_HAIR_COLOR);
    glVertexAttribPointer(PELT_ATTR_HAIR_COLOR, 4, GL_UNSIGNED_BYTE, GL_TRUE, (GLsizei)stride,
                          (const void *)(4 * sizeof(float)));
    size_t all[2];
    pelt__fur_gpu_take_groom_dirty(fur, all); /* all of it went up just now */

    /* One index buffer: the mesh's own triangles (the skin, and the shells
     * with level of detail off), then each level of detail's (lod.h). */
    const pelt__lod_chain *lod = pelt__fur_gpu_lod(fur);
    size_t total = m.triangle_count;
    for (unsigned k = 0; k < lod->count; k++) total += lod->levels[k].triangle_count;
    glGenBuffers(1, &g->ebo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g->ebo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(total * 3 * sizeof(uint32_t)), NULL, GL_STATIC_DRAW);
    glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0, (GLsizeiptr)(m.triangle_count * 3 * sizeof(uint32_t)), m.indices);
    size_t at = m.triangle_count * 3 * sizeof(uint32_t);
    g->level_count = lod->count;
    for (unsigned k = 0; k < lod->count; k++) {
        size_t bytes = lod->levels[k].triangle_count * 3 * sizeof(uint32_t);
        glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, (GLintptr)at, (GLsizeiptr)bytes, lod->levels[k].indices);
        g->level_offset[k] = at;
        g->level_triangles[k] = lod->levels[k].triangle_count;
        at += bytes;
    }
    glBindVertexArray(0);
    return PELT_OK;
}

size_t pelt__gpu_mesh_upload(pelt__gpu_mesh *g, pelt_fur *fur)
{
    size_t bytes = 0;
    unsigned version;
    const float *tips = pelt__fur_gpu_tips(fur, &version);
    if (version != g->tips_version) {
        bytes = g->vertex_count * 3 * sizeof(float);
        glBindBuffer(GL_ARRAY_BUFFER, g->vbo_tips);
        glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)bytes, tips);
        write_tips(g, tips);
        bytes *= 2;
        g->tips_version = version;
    }
    /* Only the vertices a brush or a map changed. */
    size_t range[2], stride;
    if (pelt__fur_gpu_take_groom_dirty(fur, range)) {
        const uint8_t *groom = pelt__fur_gpu_groom(fur, &stride);
        size_t n = (range[1] - range[0]) * stride;
        glBindBuffer(GL_ARRAY_BUFFER, g->vbo_groom);
        glBufferSubData(GL_ARRAY_BUFFER, (GLintptr)(range[0] * stride), (GLsizeiptr)n,
                        groom + range[0] * stride);
        table_write(g->table_groom, GL_R32UI, range[0] * PELT_GROOM_WORDS,
                    (range[1] - range[0]) * PELT_GROOM_WORDS, groom + range[0] * stride, 4);
        bytes += 2 * n;
    }
    return bytes;
}

void pelt__gpu_mesh_destroy(pelt__gpu_mesh *g)
{
    GLuint buffers[4] = {g->vbo_static, g->vbo_tips, g->vbo_groom, g->ebo};
    glDeleteBuffers(4, buffers);
    GLuint tables[3] = {g->table_vertices, g->table_tips, g->table_groom};
    glDeleteTextures(3, tables);
    pelt__free(&g->alloc, g->tip_staging);
    if (g->vao) glDeleteVertexArrays(1, &g->vao);
    memset(g, 0, sizeof *g);
}

void pelt__gpu_mesh_bind_tables(const pelt__gpu_mesh *g)
{
    const GLuint units[3] = {PELT_UNIT_VERTICES, PELT_UNIT_TIPS, PELT_UNIT_GROOM};
    const GLuint tables[3] = {g->table_vertices, g->table_tips, g->table_groom};
    for (int k = 0; k < 3; k++) {
        glActiveTexture(GL_TEXTURE0 + units[k]);
        glBindTexture(GL_TEXTURE_2D, tables[k]);
    }
}
