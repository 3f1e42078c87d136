/* Mesh files through assimp's C API, merged into one triangle mesh and then
 * validated by pelt_mesh_create (Lengyel et al. 2001 §2 takes any triangle
 * mesh as input). Corrupt files must end in a clean error, so mesh_check.c
 * reads them before assimp sees them. */
#define _POSIX_C_SOURCE 200809L /* fileno, fstat */
#include "core/mesh/mesh_internal.h"

#include "core/base/error.h"
#include "core/base/hooks.h"

#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* How much of the file the header checks look at. */
#define PELT__HEAD_BYTES 65536u
/* Node trees deeper than this are treated as corrupt (and would risk the stack). */
#define PELT__MAX_NODE_DEPTH 256

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

static void mat_mul(struct aiMatrix4x4 *out, const struct aiMatrix4x4 *a, const struct aiMatrix4x4 *b)
{
    const float *pa = &a->a1, *pb = &b->a1; /* row-major, 16 contiguous floats */
    float r[16];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            float s = 0.0f;
            for (int k = 0; k < 4; k++) s += pa[4 * i + k] * pb[4 * k + j];
            r[4 * i + j] = s;
        }
    memcpy(&out->a1, r, sizeof r);
}

/* The node named `name` under `node` (depth-first), or NULL. */
static const struct aiNode *find_node(const struct aiNode *node, const struct aiString *name, int depth)
{
    if (!node || depth > PELT__MAX_NODE_DEPTH) return NULL;
    if (node->mName.length == name->length && !memcmp(node->mName.data, name->data, name->length)) return node;
    for (unsigned k = 0; k < node->mNumChildren; k++) {
        const struct aiNode *hit = find_node(node->mChildren[k], name, depth + 1);
        if (hit) return hit;
    }
    return NULL;
}

/* A node's transform to the scene root: its own and its parents'. */
static void node_global(const struct aiNode *node, struct aiMatrix4x4 *out)
{
    struct aiMatrix4x4 m = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    for (int depth = 0; node && depth <= PELT__MAX_NODE_DEPTH; node = node->mParent, depth++) {
        struct aiMatrix4x4 t;
        mat_mul(&t, &node->mTransformation, &m);
        m = t;
    }
    *out = m;
}

/* A skinned mesh is placed by its skeleton, as a viewer of the format
 * places it: each vertex goes through its bones' transforms (the bone's
 * node in the file's pose, times the bone's offset from the mesh's bind
 * space) blended by the weights; the node holding the mesh moves it not
 * at all. Writes the blended matrices' rows, 12 floats a vertex, into
 * `skin` (zero where a vertex has no weight: those keep transform m).
 * False when a bone names no node or refers to a vertex out of range. */
static pelt_status skin_matrices(merge_state *s, const struct aiMesh *mesh, float *skin, float *weight)
{
    for (unsigned b = 0; b < mesh->mNumBones; b++) {
        const struct aiBone *bone = mesh->mBones[b];
        if (!bone) continue;
        const struct aiNode *node = find_node(s->scene->mRootNode, &bone->mName, 0);
        if (!node)
            return pelt__fail(s->err, PELT_ERR_FORMAT, "%s: bone '%s' of mesh '%s' names no node", s->path,
                              bone->mName.data, mesh->mName.data);
        struct aiMatrix4x4 g, m;
        node_global(node, &g);
        mat_mul(&m, &g, &bone->mOffsetMatrix);
        const float *x = &m.a1;
        for (unsigned w = 0; w < bone->mNumWeights; w++) {
            const struct aiVertexWeight vw = bone->mWeights[w];
            if (vw.mVertexId >= mesh->mNumVertices)
                return pelt__fail(s->err, PELT_ERR_FORMAT, "%s: bone '%s' weighs vertex %u of %u", s->path,
                                  bone->mName.data, vw.mVertexId, mesh->mNumVertices);
            if (!(vw.mWeight > 0.0f) || !isfinite(vw.mWeight)) continue;
            for (int k = 0; k < 12; k++) skin[12 * (size_t)vw.mVertexId + k] += vw.mWeight * x[k];
            weight[vw.mVertexId] += vw.mWeight;
        }
    }
    return PELT_OK;
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
static pelt_status append_mesh(merge_state *s, const struct aiMesh *mesh, const struct aiMatrix4x4 *node_m)
{
    float *skin = NULL, *weight = NULL;
    if (mesh->mNumBones > 0 && mesh->mBones) {
        skin = pelt__calloc(mesh->mNumVertices, 12 * sizeof(float));
        weight = pelt__calloc(mesh->mNumVertices, sizeof(float));
        pelt_status st = skin && weight ? skin_matrices(s, mesh, skin, weight)
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
    mat_mul(&m, parent, &node->mTransformation);
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
            pelt_status st = append_mesh(s, mesh, &m);
            if (st) return st;
        }
    }
    for (unsigned k = 0; k < node->mNumChildren; k++) {
        pelt_status st = visit(s, node->mChildren[k], &m, depth + 1);
        if (st) return st;
    }
    return PELT_OK;
}

static pelt_status merge_scene(const struct aiScene *scene, const char *path, pelt_mesh **out,
                               pelt_error *err)
{
    merge_state s = {scene, path, err, 0, 0, 1, 1, 1, NULL, NULL, NULL, NULL, NULL, NULL, 0, 0};
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
    if (!s.positions || !s.indices || (s.have_normals && !s.normals) || (s.have_uvs && !s.uvs) ||
        (s.have_colors && (!s.directions || !s.colors))) {
        st = pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: no memory for %zu vertices", path,
                        s.vertex_count);
    } else {
        st = visit(&s, scene->mRootNode, &id, 0);
    }
    if (st == PELT_OK) {
        pelt_mesh_data data = {s.positions, s.normals, s.uvs, s.v_at, s.indices, s.t_at, s.directions};
        data.colors = s.colors;
        st = pelt_mesh_create(&data, out, err);
        if (st != PELT_OK && err) {
            /* Name the file in front of pelt_mesh_create's detail. */
            char detail[sizeof err->message];
            memcpy(detail, err->message, sizeof detail);
            pelt__fail(err, st, "%s: %s", path, detail);
        }
    }
    free(s.positions);
    free(s.normals);
    free(s.uvs);
    free(s.directions);
    free(s.colors);
    free(s.indices);
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
