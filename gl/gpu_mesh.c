/* Vertex and index buffers: the mesh's attributes (through the public
 * pelt_mesh_get_data) with the fur's per-vertex data (core/fur/fur_gpu.h),
 * one VAO that every pass draws. The strand tips change every frame, so
 * they live in their own buffer, rewritten in place; so do position,
 * normal and tangent, rewritten when an animation poses the mesh
 * (pelt_fur_set_pose), laid out as the fur's pose is. */
#include "gl/gpu.h"

#include "core/base/error.h"
#include "core/fur/fur_gpu.h"

#include <string.h>

/* One interleaved attribute: where it comes from and where it goes. */
typedef struct attribute {
    GLuint location;      /* PELT_ATTR_* */
    unsigned size;        /* floats */
    const float *source;  /* per vertex, `stride` floats apart */
    unsigned stride;
} attribute;

/* A buffer of `count` attributes interleaved, bound to their locations
 * in the bound VAO. */
static pelt_status interleave(GLuint *buffer, const attribute *attrs, int count, size_t vertices, GLenum usage,
                              const pelt_hooks *hooks, pelt_error *err)
{
    unsigned floats = 0;
    for (int k = 0; k < count; k++) floats += attrs[k].size;
    float *data = pelt__alloc_zero(&hooks->allocator, vertices, floats * sizeof(float));
    if (!data) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for vertex data");
    for (size_t i = 0; i < vertices; i++) {
        float *v = data + i * floats;
        for (int k = 0; k < count; k++) {
            memcpy(v, attrs[k].source + i * attrs[k].stride, attrs[k].size * sizeof(float));
            v += attrs[k].size;
        }
    }
    glGenBuffers(1, buffer);
    glBindBuffer(GL_ARRAY_BUFFER, *buffer);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(vertices * floats * sizeof(float)), data, usage);
    pelt__free(&hooks->allocator, data);
    size_t offset = 0;
    for (int k = 0; k < count; k++) {
        glEnableVertexAttribArray(attrs[k].location);
        glVertexAttribPointer(attrs[k].location, (GLint)attrs[k].size, GL_FLOAT, GL_FALSE,
                              (GLsizei)(floats * sizeof(float)), (const void *)offset);
        offset += attrs[k].size * sizeof(float);
    }
    return PELT_OK;
}

pelt_status pelt__gpu_mesh_create(pelt__gpu_mesh *g, const pelt_mesh *mesh, pelt_fur *fur,
                                  const pelt_hooks *hooks, pelt_error *err)
{
    const pelt_mesh_data m = pelt_mesh_get_data(mesh);
    const float *tangents = pelt_mesh_tangents(mesh);
    /* Without a direction field, comb along the fur texture's u axis. */
    const attribute pose_attrs[] = {
        {PELT_ATTR_POSITION, 3, m.positions, 3},
        {PELT_ATTR_NORMAL, 3, m.normals, 3},
        {PELT_ATTR_TANGENT, 4, tangents, 4},
    };
    const attribute attrs[] = {
        {PELT_ATTR_UV, 2, m.uvs, 2},
        {PELT_ATTR_FUR_UV, 2, pelt__fur_gpu_uvs(fur), 2},
        {PELT_ATTR_COMB, 3, m.comb ? m.comb : tangents, m.comb ? 3 : 4},
    };
    enum { ATTRS = sizeof attrs / sizeof attrs[0] };
    glGenVertexArrays(1, &g->vao);
    glBindVertexArray(g->vao);
    pelt_status st = interleave(&g->vbo_pose, pose_attrs, 3, m.vertex_count, GL_DYNAMIC_DRAW, hooks, err);
    if (st != PELT_OK) return st;
    pelt__fur_gpu_pose(fur, &g->pose_version);
    st = interleave(&g->vbo_static, attrs, ATTRS, m.vertex_count, GL_STATIC_DRAW, hooks, err);
    if (st != PELT_OK) return st;
    g->vertex_count = m.vertex_count;
    g->triangle_count = m.triangle_count;

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
    const float *pose = pelt__fur_gpu_pose(fur, &version);
    if (pose && version != g->pose_version) {
        size_t n = g->vertex_count * 10 * sizeof(float);
        glBindBuffer(GL_ARRAY_BUFFER, g->vbo_pose);
        glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)n, pose);
        g->pose_version = version;
        bytes += n;
    }
    const float *tips = pelt__fur_gpu_tips(fur, &version);
    if (version != g->tips_version) {
        size_t n = g->vertex_count * 3 * sizeof(float);
        glBindBuffer(GL_ARRAY_BUFFER, g->vbo_tips);
        glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)n, tips);
        bytes += n;
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
        bytes += n;
    }
    return bytes;
}

void pelt__gpu_mesh_destroy(pelt__gpu_mesh *g)
{
    GLuint buffers[5] = {g->vbo_static, g->vbo_pose, g->vbo_tips, g->vbo_groom, g->ebo};
    glDeleteBuffers(5, buffers);
    if (g->vao) glDeleteVertexArrays(1, &g->vao);
    memset(g, 0, sizeof *g);
}
