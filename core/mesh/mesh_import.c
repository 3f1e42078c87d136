/* Mesh files through assimp's C API, merged into one triangle mesh and then
 * validated by pelt_mesh_create (Lengyel et al. 2001 §2 takes any triangle
 * mesh as input). Corrupt files must end in a clean error, so mesh_check.c
 * reads them before assimp sees them. */
#define _POSIX_C_SOURCE 200809L /* fileno, fstat */
#include "core/mesh/mesh_internal.h"
#include "core/mesh/skeleton_import.h"

#include "core/base/error.h"
#include "core/base/vec.h"
#include "core/base/hooks.h"

#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/metadata.h>
#include <assimp/scene.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* How much of the file the header checks look at. */
#define PELT__HEAD_BYTES 65536u

/* Opens and sizes the file and checks it (mesh_check.c). The formats it
 * checks are read whole (bounded by the real file size). */
static pelt_status precheck(const char *path, pelt_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f) return pelt__fail(err, PELT_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
    struct stat sb;
    if (fstat(fileno(f), &sb) != 0 || S_ISDIR(sb.st_mode)) {
        int e = S_ISDIR(sb.st_mode) ? EISDIR : errno;
        fclose(f);
        return pelt__fail(err, PELT_ERR_IO, "cannot open '%s': %s", path, strerror(e));
    }
    const long long size = (long long)sb.st_size;
    char *buf = pelt__calloc(PELT__HEAD_BYTES + 1, 1);
    if (!buf) {
        fclose(f);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    size_t len = fread(buf, 1, PELT__HEAD_BYTES, f);
    int failed = ferror(f), e = errno;
    if (!failed && pelt__mesh_check_reads_whole(path, buf, len) && len == PELT__HEAD_BYTES &&
        size > (long long)len && (unsigned long long)size < (size_t)-1) {
        char *whole = realloc(buf, (size_t)size + 1);
        if (!whole) {
            free(buf);
            fclose(f);
            return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: no memory to read %lld bytes", path, size);
        }
        buf = whole;
        len += fread(buf + len, 1, (size_t)size - len, f);
        buf[len] = '\0';
        failed = ferror(f);
        e = errno;
    }
    fclose(f);
    pelt_status st = failed ? pelt__fail(err, PELT_ERR_IO, "cannot open '%s': %s", path, strerror(e))
                            : pelt__mesh_check(path, buf, len, size, err);
    free(buf);
    return st;
}

/* ---- merging the scene ------------------------------------------------- */

typedef struct merge_state {
    const struct aiScene *scene;
    const char *path;
    pelt_error *err;
    size_t vertex_count, triangle_count;
    int have_normals, have_uvs, have_colors; /* every instanced mesh has them */
    /* Output arrays (second pass only). */
    float *positions, *normals, *uvs, *directions, *colors;
    uint32_t *indices;
    size_t v_at, t_at;
    pelt__skeleton_import skeleton; /* files with bones or animations */
} merge_state;

static int is_triangle_mesh(const struct aiMesh *mesh)
{
    return mesh && (mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) && mesh->mVertices &&
           mesh->mFaces && mesh->mNumVertices > 0;
}

static size_t count_triangles(const struct aiMesh *mesh)
{
    size_t n = 0;
    for (unsigned f = 0; f < mesh->mNumFaces; f++)
        if (mesh->mFaces[f].mNumIndices == 3 && mesh->mFaces[f].mIndices) n++;
    return n;
}











/* One vertex of a mesh instance under transform m. */
static pelt_status append_vertex(merge_state *s, const struct aiMesh *mesh, unsigned v, size_t base,
                                 const struct aiMatrix4x4 *m)
{
    const float *x = &m->a1;
    /* Normals go through the cofactor matrix (det * inverse transpose), signed
     * so that mirroring transforms keep them pointing outwards. */
    float c[9] = {
        x[5] * x[10] - x[6] * x[9], x[6] * x[8] - x[4] * x[10], x[4] * x[9] - x[5] * x[8],
        x[2] * x[9] - x[1] * x[10], x[0] * x[10] - x[2] * x[8], x[1] * x[8] - x[0] * x[9],
        x[1] * x[6] - x[2] * x[5], x[2] * x[4] - x[0] * x[6], x[0] * x[5] - x[1] * x[4],
    };
    float det = x[0] * c[0] + x[1] * c[1] + x[2] * c[2];
    float sign = det < 0.0f ? -1.0f : 1.0f;
    {
        const struct aiVector3D p = mesh->mVertices[v];
        float *o = s->positions + 3 * (base + v);
        for (int k = 0; k < 3; k++) o[k] = x[4 * k] * p.x + x[4 * k + 1] * p.y + x[4 * k + 2] * p.z + x[4 * k + 3];
        if (s->have_normals) {
            const struct aiVector3D n = mesh->mNormals[v];
            float *on = s->normals + 3 * (base + v);
            for (int k = 0; k < 3; k++) on[k] = sign * (c[3 * k] * n.x + c[3 * k + 1] * n.y + c[3 * k + 2] * n.z);
        }
        if (s->have_uvs) {
            s->uvs[2 * (base + v)] = mesh->mTextureCoords[0][v].x;
            s->uvs[2 * (base + v) + 1] = mesh->mTextureCoords[0][v].y;
        }
        if (s->have_colors) {
            /* A flow map: rgb in [0,1] encodes a direction 2 rgb - 1, a
             * vector carried by the node's linear part. */
            const struct aiColor4D c4 = mesh->mColors[0][v];
            const float d[3] = {2.0f * c4.r - 1.0f, 2.0f * c4.g - 1.0f, 2.0f * c4.b - 1.0f};
            float *od = s->directions + 3 * (base + v);
            for (int k = 0; k < 3; k++) od[k] = x[4 * k] * d[0] + x[4 * k + 1] * d[1] + x[4 * k + 2] * d[2];
            float *oc = s->colors + 4 * (base + v);
            oc[0] = c4.r, oc[1] = c4.g, oc[2] = c4.b, oc[3] = c4.a;
        }
    }
    return PELT_OK;
}

/* The faces of a mesh instance whose vertices start at `base`; a node
 * transform that mirrors flips them to keep them counter-clockwise. */
static pelt_status append_faces(merge_state *s, const struct aiMesh *mesh, const struct aiMatrix4x4 *m, size_t base)
{
    const float *x = &m->a1;
    float det = x[0] * (x[5] * x[10] - x[6] * x[9]) + x[1] * (x[6] * x[8] - x[4] * x[10]) +
                x[2] * (x[4] * x[9] - x[5] * x[8]);
    for (unsigned f = 0; f < mesh->mNumFaces; f++) {
        const struct aiFace *face = &mesh->mFaces[f];
        if (face->mNumIndices != 3 || !face->mIndices) continue;
        uint32_t *o = s->indices + 3 * s->t_at;
        for (int k = 0; k < 3; k++) {
            unsigned i = face->mIndices[det < 0.0f ? 2 - k : k]; /* mirrored: keep CCW */
            if (i >= mesh->mNumVertices)
                return pelt__fail(s->err, PELT_ERR_FORMAT,
                                  "%s: face %u of mesh '%s' refers to vertex %u of %u", s->path, f,
                                  mesh->mName.data, i, mesh->mNumVertices);
            o[k] = (uint32_t)(base + i);
        }
        s->t_at++;
    }
    s->v_at += mesh->mNumVertices;
    return PELT_OK;
}

/* Appends one mesh instance under transform m (row-major, column vectors). */
static pelt_status append_mesh(merge_state *s, const struct aiMesh *mesh, const struct aiNode *node,
                               const struct aiMatrix4x4 *node_m)
{
    float *skin = NULL, *weight = NULL;
    if (mesh->mNumBones > 0 && mesh->mBones) {
        skin = pelt__calloc(mesh->mNumVertices, 12 * sizeof(float));
        weight = pelt__calloc(mesh->mNumVertices, sizeof(float));
        pelt_status st = skin && weight ? pelt__skeleton_import_skin(&s->skeleton, mesh, skin, weight)
                                        : pelt__fail(s->err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory", s->path);
        if (st) {
            free(skin);
            free(weight);
            return st;
        }
    }
    pelt_status st = PELT_OK;
    size_t base = s->v_at;
    for (unsigned v = 0; v < mesh->mNumVertices && st == PELT_OK; v++) {
        /* This vertex's transform: its bones' blend (weights renormalised)
           or the node's. */
        struct aiMatrix4x4 mv = *node_m;
        if (skin && weight[v] > 0.0f) {
            float *x = &mv.a1;
            for (int k = 0; k < 12; k++) x[k] = skin[12 * (size_t)v + k] / weight[v];
            x[12] = x[13] = x[14] = 0.0f, x[15] = 1.0f;
        }
        st = append_vertex(s, mesh, v, base, &mv);
    }
    free(skin);
    free(weight);
    if (st == PELT_OK) st = pelt__skeleton_import_weigh(&s->skeleton, mesh, node, base);
    if (st) return st;
    return append_faces(s, mesh, node_m, base);
}

/* Walks the node tree; counts (first pass, positions == NULL) or copies. */
static pelt_status visit(merge_state *s, const struct aiNode *node, const struct aiMatrix4x4 *parent,
                         int depth)
{
    if (!node) return PELT_OK;
    if (depth > PELT__MAX_NODE_DEPTH)
        return pelt__fail(s->err, PELT_ERR_FORMAT, "%s: node tree deeper than %d levels", s->path,
                          PELT__MAX_NODE_DEPTH);
    struct aiMatrix4x4 m;
    pelt__ai_mat_mul(&m, parent, &node->mTransformation);
    for (unsigned k = 0; k < node->mNumMeshes; k++) {
        unsigned mi = node->mMeshes[k];
        if (mi >= s->scene->mNumMeshes)
            return pelt__fail(s->err, PELT_ERR_FORMAT, "%s: node '%s' refers to mesh %u of %u", s->path,
                              node->mName.data, mi, s->scene->mNumMeshes);
        const struct aiMesh *mesh = s->scene->mMeshes[mi];
        if (!is_triangle_mesh(mesh)) continue; /* points and lines carry no fur */
        size_t tris = count_triangles(mesh);
        if (tris == 0) continue;
        if (!s->positions) {
            if (s->vertex_count > (size_t)UINT32_MAX - mesh->mNumVertices)
                return pelt__fail(s->err, PELT_ERR_FORMAT, "%s: more than 2^32 vertices in all",
                                  s->path);
            s->vertex_count += mesh->mNumVertices;
            s->triangle_count += tris;
            if (!mesh->mNormals) s->have_normals = 0;
            if (!mesh->mTextureCoords[0]) s->have_uvs = 0;
            if (!mesh->mColors[0]) s->have_colors = 0;
        } else {
            pelt_status st = append_mesh(s, mesh, node, &m);
            if (st) return st;
        }
    }
    for (unsigned k = 0; k < node->mNumChildren; k++) {
        pelt_status st = visit(s, node->mChildren[k], &m, depth + 1);
        if (st) return st;
    }
    return PELT_OK;
}

/* FBX says which axis is up (UpAxis 0, 1, 2 and UpAxisSign +-1); assimp
 * leaves the coordinates as they are. Other formats: +Y. */
static void file_up_axis(const struct aiScene *scene, float up[3])
{
    up[0] = up[2] = 0.0f, up[1] = 1.0f;
    const struct aiMetadata *m = scene->mMetaData;
    int axis = -1, sign = 1;
    for (unsigned i = 0; m && m->mKeys && m->mValues && i < m->mNumProperties; i++) {
        const struct aiMetadataEntry *e = &m->mValues[i];
        if (e->mType != AI_INT32 || !e->mData) continue;
        int value;
        memcpy(&value, e->mData, sizeof value);
        if (!strcmp(m->mKeys[i].data, "UpAxis")) axis = value;
        if (!strcmp(m->mKeys[i].data, "UpAxisSign")) sign = value < 0 ? -1 : 1;
    }
    if (axis < 0 || axis > 2) return;
    up[0] = up[1] = up[2] = 0.0f;
    up[axis] = (float)sign;
}






static pelt_status merge_scene(const struct aiScene *scene, const char *path, pelt_mesh **out,
                               pelt_error *err)
{
    merge_state s = {scene, path, err, 0, 0, 1, 1, 1, NULL, NULL, NULL, NULL, NULL, NULL, 0, 0, {path, err}};
    struct aiMatrix4x4 id = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    pelt_status st = visit(&s, scene->mRootNode, &id, 0);
    if (st) return st;
    if (s.triangle_count == 0)
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: the file holds no triangles", path);
    s.positions = pelt__calloc(s.vertex_count, 3 * sizeof(float));
    s.normals = s.have_normals ? pelt__calloc(s.vertex_count, 3 * sizeof(float)) : NULL;
    s.uvs = s.have_uvs ? pelt__calloc(s.vertex_count, 2 * sizeof(float)) : NULL;
    s.directions = s.have_colors ? pelt__calloc(s.vertex_count, 3 * sizeof(float)) : NULL;
    s.colors = s.have_colors ? pelt__calloc(s.vertex_count, 4 * sizeof(float)) : NULL;
    s.indices = pelt__calloc(s.triangle_count, 3 * sizeof(uint32_t));
    bool skeleton = pelt__skeleton_import_wanted(scene);
    if (!s.positions || !s.indices || (s.have_normals && !s.normals) || (s.have_uvs && !s.uvs) ||
        (s.have_colors && (!s.directions || !s.colors))) {
        st = pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: no memory for %zu vertices", path,
                        s.vertex_count);
    } else {
        if (skeleton) st = pelt__skeleton_import_begin(&s.skeleton, scene, s.vertex_count);
        if (st == PELT_OK) st = visit(&s, scene->mRootNode, &id, 0);
    }
    uint32_t *remap = NULL;
    if (st == PELT_OK) {
        pelt_mesh_data data = {s.positions, s.normals, s.uvs, s.v_at, s.indices, s.t_at, s.directions};
        float up[3];
        file_up_axis(scene, up);
        data.colors = s.colors;
        data.up = up;
        st = pelt__mesh_create_remap(&data, out, skeleton ? &remap : NULL, err);
        if (st != PELT_OK && err) {
            /* Name the file in front of pelt_mesh_create's detail. */
            char detail[sizeof err->message];
            memcpy(detail, err->message, sizeof detail);
            pelt__fail(err, st, "%s: %s", path, detail);
        }
    }
    if (st == PELT_OK && skeleton) {
        st = remap ? pelt__skeleton_import_finish(&s.skeleton, scene, *out, remap, s.v_at)
                   : pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
        if (st != PELT_OK) {
            pelt_mesh_destroy(*out);
            *out = NULL;
        }
    }
    free(remap);
    free(s.positions);
    free(s.normals);
    free(s.uvs);
    free(s.directions);
    free(s.colors);
    free(s.indices);
    pelt__skeleton_import_free(&s.skeleton);
    return st;
}

/* Merges what assimp made of `name` (NULL: assimp's error). */
static pelt_status take_scene(const struct aiScene *scene, const char *name, pelt_mesh **out,
                              pelt_error *err)
{
    if (!scene) {
        const char *why = aiGetErrorString();
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: %s", name,
                          why && *why ? why : "assimp could not read it");
    }
    pelt_status st = scene->mRootNode
                         ? merge_scene(scene, name, out, err)
                         : pelt__fail(err, PELT_ERR_FORMAT, "%s: the file holds no scene", name);
    aiReleaseImport(scene);
    return st;
}

static const unsigned import_flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                     aiProcess_SortByPType | aiProcess_ValidateDataStructure;

pelt_status pelt_mesh_load(const char *path, pelt_mesh **out, pelt_error *err)
{
    if (!out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_mesh_load: out is NULL");
    *out = NULL;
    if (!path || !*path)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_mesh_load: no path given");
    pelt_status st = precheck(path, err);
    if (st) return st;
    return take_scene(aiImportFile(path, import_flags), path, out, err);
}

pelt_status pelt_mesh_load_memory(const void *data, size_t size, const char *name, pelt_mesh **out,
                                  pelt_error *err)
{
    if (!out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_mesh_load_memory: out is NULL");
    *out = NULL;
    if (!name || !strrchr(name, '.'))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "pelt_mesh_load_memory: the name must end in the format's extension");
    if (!data && size > 0)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_mesh_load_memory: data is NULL");
    if (size > UINT32_MAX)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "%s: larger than 4 GiB", name);
    pelt_status st = pelt__mesh_check(name, data, size, (long long)size, err);
    if (st) return st;
    const char *ext = strrchr(name, '.') + 1;
    return take_scene(aiImportFileFromMemory(data, (unsigned)size, import_flags, ext), name, out, err);
}
