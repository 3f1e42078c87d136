/* Vertex and index buffers: the mesh's attributes (through the public
 * pelt_mesh_get_data) with the fur's per-vertex data (core/fur/fur_gpu.h),
 * one VAO that every pass draws. The strand tips change every frame, so
 * they live in their own buffer, rewritten in place; so do position,
 * normal and tangent, rewritten when an animation poses the mesh
 * (pelt_fur_set_pose), laid out as the fur's pose is.
 *
 * A skinned mesh also gets a second VAO for skinning in the vertex stage
 * (measured by pelt bench --animation against the pose made once on the
 * CPU): the bind-space position, normal and tangent, 4 bones and weights
 * a vertex, the other buffers shared. */
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

static unsigned floats_of(const attribute *attrs, int count)
{
    unsigned floats = 0;
    for (int k = 0; k < count; k++) floats += attrs[k].size;
    return floats;
}

/* A buffer of `count` attributes interleaved. */
static pelt_status interleave(GLuint *buffer, const attribute *attrs, int count, size_t vertices, GLenum usage,
                              const pelt_hooks *hooks, pelt_error *err)
{
    unsigned floats = floats_of(attrs, count);
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
    return PELT_OK;
}

/* Points the bound VAO's locations at an interleaved buffer. */
static void point(GLuint buffer, const attribute *attrs, int count)
{
    unsigned floats = floats_of(attrs, count);
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    size_t offset = 0;
    for (int k = 0; k < count; k++) {
        glEnableVertexAttribArray(attrs[k].location);
        glVertexAttribPointer(attrs[k].location, (GLint)attrs[k].size, GL_FLOAT, GL_FALSE,
                              (GLsizei)(floats * sizeof(float)), (const void *)offset);
        offset += attrs[k].size * sizeof(float);
    }
}

/* The attributes every VAO shares: uv, fur uv and comb; the tips; the
 * groom (one 20-byte record per vertex, core/fur/groom.h: lean, length
 * and density as floats, the hair colour as 4 normalised bytes); and
 * the index buffer. */
static void point_shared(const pelt__gpu_mesh *g, const attribute *attrs, int count, size_t groom_stride)
{
    point(g->vbo_static, attrs, count);
    glBindBuffer(GL_ARRAY_BUFFER, g->vbo_tips);
    glEnableVertexAttribArray(PELT_ATTR_TIP);
    glVertexAttribPointer(PELT_ATTR_TIP, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), NULL);
    glBindBuffer(GL_ARRAY_BUFFER, g->vbo_groom);
    glEnableVertexAttribArray(PELT_ATTR_GROOM);
    glVertexAttribPointer(PELT_ATTR_GROOM, 4, GL_FLOAT, GL_FALSE, (GLsizei)groom_stride, NULL);
    glEnableVertexAttribArray(PELT_ATTR_HAIR_COLOR);
    glVertexAttribPointer(PELT_ATTR_HAIR_COLOR, 4, GL_UNSIGNED_BYTE, GL_TRUE, (GLsizei)groom_stride,
                          (const void *)(4 * sizeof(float)));
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g->ebo);
    pelt__gpu_mesh_point_fit(g, true, 0);
}

void pelt__gpu_mesh_point_fit(const pelt__gpu_mesh *g, bool full_mesh, unsigned level)
{
    size_t slice = full_mesh || level > g->fit_levels ? 0 : level;
    glBindBuffer(GL_ARRAY_BUFFER, g->vbo_fit);
    glEnableVertexAttribArray(PELT_ATTR_FIT_NORMAL);
    glVertexAttribPointer(PELT_ATTR_FIT_NORMAL, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float),
                          (const void *)(slice * g->vertex_count * 3 * sizeof(float)));
}

/* The levels' fitted normals, one slice each after the zeros of slice 0. */
static void upload_fit(pelt__gpu_mesh *g, const pelt__lod_chain *lod)
{
    unsigned levels = 0;
    while (levels + 1 < lod->count && lod->levels[levels + 1].fit_normals) levels++;
    size_t slice = g->vertex_count * 3 * sizeof(float);
    glGenBuffers(1, &g->vbo_fit);
    glBindBuffer(GL_ARRAY_BUFFER, g->vbo_fit);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)((levels + 1) * (slice ? slice : 1)), NULL, GL_STATIC_DRAW);
    /* Slice 0 from the first level's zeros would need a copy: clear it. */
    for (size_t at = 0; at < slice;) {
        static const float zeros[3 * 256];
        size_t n = slice - at < sizeof zeros ? slice - at : sizeof zeros;
        glBufferSubData(GL_ARRAY_BUFFER, (GLintptr)at, (GLsizeiptr)n, zeros);
        at += n;
    }
    for (unsigned k = 1; k <= levels; k++)
        glBufferSubData(GL_ARRAY_BUFFER, (GLintptr)(k * slice), (GLsizeiptr)slice, lod->levels[k].fit_normals);
    g->fit_levels = levels;
}

/* The second VAO of a skinned mesh (see the top of this file). */
static pelt_status make_skin_vao(pelt__gpu_mesh *g, const pelt__gpu_skin *skin, const attribute *shared,
                                 int shared_count, size_t groom_stride, const pelt_hooks *hooks, pelt_error *err)
{
    const attribute bind[] = {
        {PELT_ATTR_POSITION, 3, skin->bind, 10},
        {PELT_ATTR_NORMAL, 3, skin->bind + 3, 10},
        {PELT_ATTR_TANGENT, 4, skin->bind + 6, 10},
        {PELT_ATTR_WEIGHTS, 4, skin->weights, 4},
    };
    glGenVertexArrays(1, &g->vao_skin);
    glBindVertexArray(g->vao_skin);
    pelt_status st = interleave(&g->vbo_bind, bind, 4, g->vertex_count, GL_STATIC_DRAW, hooks, err);
    if (st != PELT_OK) return st;
    point(g->vbo_bind, bind, 4);
    glGenBuffers(1, &g->vbo_bones);
    glBindBuffer(GL_ARRAY_BUFFER, g->vbo_bones);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(g->vertex_count * 4 * sizeof(uint16_t)), skin->bones, GL_STATIC_DRAW);
    glEnableVertexAttribArray(PELT_ATTR_BONES);
    glVertexAttribIPointer(PELT_ATTR_BONES, 4, GL_UNSIGNED_SHORT, 4 * sizeof(uint16_t), NULL);
    point_shared(g, shared, shared_count, groom_stride);
    /* The bones' matrices: 3 rows a bone, PELT_TABLE_WIDTH texels a row. */
    size_t texels = 3 * skin->bone_count, rows = (texels + PELT_TABLE_WIDTH - 1) / PELT_TABLE_WIDTH;
    g->bone_rows = (unsigned)(rows ? rows : 1);
    g->bone_staging = pelt__alloc_zero(&hooks->allocator, (size_t)g->bone_rows * PELT_TABLE_WIDTH, 4 * sizeof(float));
    if (!g->bone_staging) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the bones");
    g->alloc = hooks->allocator;
    glGenTextures(1, &g->bone_texture);
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_BONES);
    glBindTexture(GL_TEXTURE_2D, g->bone_texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, PELT_TABLE_WIDTH, (GLsizei)g->bone_rows, 0, GL_RGBA, GL_FLOAT, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
    g->skinned = true;
    return PELT_OK;
}

pelt_status pelt__gpu_mesh_create(pelt__gpu_mesh *g, const pelt_mesh *mesh, pelt_fur *fur,
                                  const pelt_hooks *hooks, pelt_error *err)
{
    const pelt_mesh_data m = pelt_mesh_get_data(mesh);
    const float *tangents = pelt_mesh_tangents(mesh);
    pelt__fur_snapshot fs;
    pelt__fur_gpu_snapshot(fur, &fs);
    const attribute pose_attrs[] = {
        {PELT_ATTR_POSITION, 3, m.positions, 3},
        {PELT_ATTR_NORMAL, 3, m.normals, 3},
        {PELT_ATTR_TANGENT, 4, tangents, 4},
    };
    /* Without a direction field, comb along the fur texture's u axis. */
    const attribute attrs[] = {
        {PELT_ATTR_UV, 2, m.uvs, 2},
        {PELT_ATTR_FUR_UV, 2, fs.fur_uvs, 2},
        {PELT_ATTR_COMB, 3, m.comb ? m.comb : tangents, m.comb ? 3 : 4},
    };
    enum { ATTRS = sizeof attrs / sizeof attrs[0] };
    g->vertex_count = m.vertex_count;
    g->triangle_count = m.triangle_count;
    g->alloc = hooks->allocator;
    glGenVertexArrays(1, &g->vao);
    glBindVertexArray(g->vao);
    pelt_status st = interleave(&g->vbo_pose, pose_attrs, 3, m.vertex_count, GL_DYNAMIC_DRAW, hooks, err);
    if (st == PELT_OK) st = interleave(&g->vbo_static, attrs, ATTRS, m.vertex_count, GL_STATIC_DRAW, hooks, err);
    if (st != PELT_OK) return st;
    g->pose_version = fs.pose_version;

    glGenBuffers(1, &g->vbo_tips);
    glBindBuffer(GL_ARRAY_BUFFER, g->vbo_tips);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(m.vertex_count * 3 * sizeof(float)),
                 fs.tips, GL_DYNAMIC_DRAW);
    g->tips_version = fs.tips_version;
    size_t stride = fs.groom_stride;
    const void *groom = fs.groom;
    glGenBuffers(1, &g->vbo_groom);
    glBindBuffer(GL_ARRAY_BUFFER, g->vbo_groom);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(m.vertex_count * stride), groom, GL_DYNAMIC_DRAW);
    size_t all[2];
    pelt__fur_gpu_take_groom_dirty(fur, all); /* all of it went up just now */

    /* One index buffer: the mesh's own triangles (the skin, and the shells
     * with level of detail off), then each level of detail's (lod.h). */
    const pelt__lod_chain *lod = fs.lod;
    size_t total = 3 * m.triangle_count; /* the mesh's, its wet split and its view split */
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
    g->split_offset = at;
    g->split_ok = pelt__wet_split_init(&g->split, m.indices, m.triangle_count, m.uvs, fs.mask_width,
                                       fs.mask_height, &hooks->allocator);
    if (g->split_ok) {
        /* The mask as it is now: the textures take its changes from here. */
        const unsigned whole[4] = {0, 0, fs.mask_width, fs.mask_height};
        pelt__wet_split_update(&g->split, fs.mask, whole);
        glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, (GLintptr)at,
                        (GLsizeiptr)(m.triangle_count * 3 * sizeof(uint32_t)), g->split.indices);
    }
    g->view_offset = at + m.triangle_count * 3 * sizeof(uint32_t);
    g->view_indices = pelt__alloc_zero(&hooks->allocator, m.triangle_count * 3, sizeof(uint32_t));
    g->view_staging = pelt__alloc_zero(&hooks->allocator, m.triangle_count * 3, sizeof(uint32_t));
    g->view_side = pelt__alloc_zero(&hooks->allocator, m.vertex_count ? m.vertex_count : 1, 1);
    g->view_ok = g->view_indices && g->view_staging && g->view_side;
    upload_fit(g, lod);
    point(g->vbo_pose, pose_attrs, 3);
    point_shared(g, attrs, ATTRS, stride);

    if (fs.skinned) st = make_skin_vao(g, &fs.skin, attrs, ATTRS, stride, hooks, err);
    glBindVertexArray(0);
    return st;
}

size_t pelt__gpu_mesh_upload(pelt__gpu_mesh *g, pelt_fur *fur, const pelt__fur_snapshot *fs)
{
    size_t bytes = 0;
    unsigned version = fs->pose_version;
    const float *pose = fs->pose;
    if (pose && version != g->pose_version) {
        size_t n = g->vertex_count * 10 * sizeof(float);
        glBindBuffer(GL_ARRAY_BUFFER, g->vbo_pose);
        glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)n, pose);
        g->pose_version = version;
        bytes += n;
    }
    const float *tips = fs->tips;
    version = fs->tips_version;
    if (version != g->tips_version) {
        size_t n = g->vertex_count * 3 * sizeof(float);
        glBindBuffer(GL_ARRAY_BUFFER, g->vbo_tips);
        glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)n, tips);
        bytes += n;
        g->tips_version = version;
    }
    /* Only the vertices a brush or a map changed. */
    size_t range[2], stride = fs->groom_stride;
    if (pelt__fur_gpu_take_groom_dirty(fur, range)) {
        const uint8_t *groom = fs->groom;
        size_t n = (range[1] - range[0]) * stride;
        glBindBuffer(GL_ARRAY_BUFFER, g->vbo_groom);
        glBufferSubData(GL_ARRAY_BUFFER, (GLintptr)(range[0] * stride), (GLsizeiptr)n,
                        groom + range[0] * stride);
        bytes += n;
    }
    return bytes;
}

size_t pelt__gpu_mesh_upload_bones(pelt__gpu_mesh *g, pelt_fur *fur)
{
    pelt__fur_snapshot fs;
    pelt__fur_gpu_snapshot(fur, &fs);
    if (!g->skinned || !fs.skinned) return 0;
    const pelt__gpu_skin skin = fs.skin;
    /* Rows 0..2 of each column-major 4x4: x, y, z of the blend. */
    for (size_t b = 0; b < skin.bone_count; b++)
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 4; c++) g->bone_staging[4 * (3 * b + (size_t)r) + (size_t)c] = skin.matrices[16 * b + 4 * c + r];
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_BONES);
    glBindTexture(GL_TEXTURE_2D, g->bone_texture);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, PELT_TABLE_WIDTH, (GLsizei)g->bone_rows, GL_RGBA, GL_FLOAT,
                    g->bone_staging);
    glActiveTexture(GL_TEXTURE0);
    return (size_t)g->bone_rows * PELT_TABLE_WIDTH * 4 * sizeof(float);
}

size_t pelt__gpu_mesh_update_split(pelt__gpu_mesh *g, const pelt__fur_snapshot *fs, const unsigned rect[4])
{
    if (!g->split_ok || !pelt__wet_split_update(&g->split, fs->mask, rect)) return 0;
    size_t bytes = g->split.triangle_count * 3 * sizeof(uint32_t);
    /* The VAO holds the element buffer: bind it there, as every draw does. */
    glBindVertexArray(g->vao);
    glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, (GLintptr)g->split_offset, (GLsizeiptr)bytes, g->split.indices);
    glBindVertexArray(0);
    return bytes;
}

/* Sends the view split in view_staging where it differs from the last:
 * face of total triangles, then (a wet frame's) wet_face of wet_total. */
static size_t view_upload(pelt__gpu_mesh *g, bool wet, size_t face, size_t total, size_t wet_face, size_t wet_total)
{
    size_t bytes = (total + wet_total) * 3 * sizeof(uint32_t);
    bool same = wet == g->view_wet && face == g->view_face && total == g->view_total &&
                wet_face == g->view_wet_face && wet_total == g->view_wet_total &&
                !memcmp(g->view_staging, g->view_indices, bytes);
    g->view_wet = wet, g->view_face = face, g->view_total = total;
    g->view_wet_face = wet_face, g->view_wet_total = wet_total;
    if (same) return 0;
    memcpy(g->view_indices, g->view_staging, bytes);
    /* The VAO holds the element buffer (WebGL2 binds an element buffer to
     * no other target): through it, and it stays bound for the shells. */
    glBindVertexArray(g->vao);
    glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, (GLintptr)g->view_offset, (GLsizeiptr)bytes, g->view_indices);
    return bytes;
}

size_t pelt__gpu_mesh_update_view(pelt__gpu_mesh *g, const pelt_fur *fur, const pelt__view_split_desc *d)
{
    if (!g->view_ok) return 0;
    /* A level never holds more triangles than the mesh: room for them. */
    size_t total, face = pelt__fur_gpu_view_split(fur, d, g->view_side, g->view_staging, &total);
    return view_upload(g, false, face, total, 0, 0);
}

size_t pelt__gpu_mesh_update_view_wet(pelt__gpu_mesh *g, const pelt_fur *fur, const pelt__view_split_desc *d)
{
    if (!g->view_ok || !g->split_ok) return 0;
    const size_t dry = g->split.dry_count, all = g->split.triangle_count;
    pelt__view_split_desc part = *d;
    part.triangles = g->split.indices, part.triangle_count = dry;
    size_t total, face = pelt__fur_gpu_view_split(fur, &part, g->view_side, g->view_staging, &total);
    part.triangles = g->split.indices + 3 * dry, part.triangle_count = all - dry;
    size_t wet_total, wet_face =
        pelt__fur_gpu_view_split(fur, &part, g->view_side, g->view_staging + 3 * dry, &wet_total);
    return view_upload(g, true, face, total, wet_face, wet_total);
}

void pelt__gpu_mesh_destroy(pelt__gpu_mesh *g)
{
    pelt__wet_split_free(&g->split);
    if (g->view_indices) pelt__free(&g->alloc, g->view_indices);
    if (g->view_staging) pelt__free(&g->alloc, g->view_staging);
    if (g->view_side) pelt__free(&g->alloc, g->view_side);
    GLuint buffers[8] = {g->vbo_static, g->vbo_pose, g->vbo_tips, g->vbo_groom,
                         g->ebo,        g->vbo_bind, g->vbo_bones, g->vbo_fit};
    glDeleteBuffers(8, buffers);
    if (g->vao) glDeleteVertexArrays(1, &g->vao);
    if (g->vao_skin) glDeleteVertexArrays(1, &g->vao_skin);
    if (g->bone_texture) glDeleteTextures(1, &g->bone_texture);
    if (g->bone_staging) pelt__free(&g->alloc, g->bone_staging);
    memset(g, 0, sizeof *g);
}
