/* Mesh files through assimp's C API, merged into one triangle mesh and then
 * validated by pelt_mesh_create (Lengyel et al. 2001 §2 takes any triangle
 * mesh as input). Corrupt files must end in a clean error, so mesh_check.c
 * reads them before assimp sees them. */
#define _POSIX_C_SOURCE 200809L /* fileno, fstat */
#include "core/mesh/mesh_internal.h"
#include "core/mesh/skeleton.h"

#include "core/base/error.h"
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
    /* The skeleton in the making (files with bones or animations). */
    const struct aiNode **nodes; /* parents first */
    int32_t *node_parent;
    int32_t *node_bone;          /* a node's rigid-part bone, -1 until needed */
    uint32_t node_count;
    uint32_t *bone_node;
    float *bone_offset;          /* 16 per bone */
    uint32_t bone_count, real_bones, bone_room;
    unsigned char *bone_real;    /* 1: a bone of the file, 0: a rigid part's node */
    uint16_t *vbones;            /* PELT__BONES_PER_VERTEX per merged vertex, */
    float *vweights;             /* heaviest first */
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

/* Column-major copy of assimp's row-major matrix. */
static void to_column_major(const struct aiMatrix4x4 *m, float out[16])
{
    const float *x = &m->a1;
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) out[4 * c + r] = x[4 * r + c];
}

static pelt_status collect_nodes(merge_state *s, const struct aiNode *node, int32_t parent, int depth)
{
    if (!node) return PELT_OK;
    if (depth > PELT__MAX_NODE_DEPTH)
        return pelt__fail(s->err, PELT_ERR_FORMAT, "%s: node tree deeper than %d levels", s->path,
                          PELT__MAX_NODE_DEPTH);
    if (s->node_count >= PELT__MAX_SKELETON_NODES)
        return pelt__fail(s->err, PELT_ERR_FORMAT, "%s: more than %u nodes", s->path, PELT__MAX_SKELETON_NODES);
    uint32_t me = s->node_count++;
    s->nodes[me] = node;
    s->node_parent[me] = parent;
    s->node_bone[me] = -1;
    for (unsigned k = 0; k < node->mNumChildren; k++) {
        pelt_status st = collect_nodes(s, node->mChildren[k], (int32_t)me, depth + 1);
        if (st) return st;
    }
    return PELT_OK;
}

static int32_t node_index(const merge_state *s, const struct aiNode *node)
{
    for (uint32_t i = 0; i < s->node_count; i++)
        if (s->nodes[i] == node) return (int32_t)i;
    return -1;
}

static int32_t node_named(const merge_state *s, const struct aiString *name)
{
    for (uint32_t i = 0; i < s->node_count; i++)
        if (s->nodes[i]->mName.length == name->length && !memcmp(s->nodes[i]->mName.data, name->data, name->length))
            return (int32_t)i;
    return -1;
}

/* A new bone: `node` with `offset` (column-major, NULL: identity). */
static pelt_status add_bone(merge_state *s, uint32_t node, const float *offset, uint32_t *out)
{
    if (s->bone_count >= s->bone_room || (offset && s->real_bones >= PELT_MAX_BONES))
        return pelt__fail(s->err, PELT_ERR_FORMAT, "%s: more than %u bones", s->path, PELT_MAX_BONES);
    uint32_t b = s->bone_count++;
    s->bone_node[b] = node;
    static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    memcpy(s->bone_offset + 16 * b, offset ? offset : identity, 16 * sizeof(float));
    *out = b;
    return PELT_OK;
}

/* Adds (bone, weight) to merged vertex v's heaviest four. */
static void weigh(merge_state *s, size_t v, uint32_t bone, float w)
{
    uint16_t *b = s->vbones + PELT__BONES_PER_VERTEX * v;
    float *ws = s->vweights + PELT__BONES_PER_VERTEX * v;
    int at = PELT__BONES_PER_VERTEX;
    while (at > 0 && ws[at - 1] < w) at--;
    if (at == PELT__BONES_PER_VERTEX) return; /* lighter than all four */
    for (int k = PELT__BONES_PER_VERTEX - 1; k > at; k--) ws[k] = ws[k - 1], b[k] = b[k - 1];
    ws[at] = w;
    b[at] = (uint16_t)bone;
}

/* The skeleton's part of one mesh instance under `node`: a skinned mesh's
 * bones weigh its vertices (merged from `base` on), every one of them; an
 * unskinned mesh is a rigid part of its node. */
static pelt_status weigh_mesh(merge_state *s, const struct aiMesh *mesh, const struct aiNode *node, size_t base)
{
    if (!s->nodes) return PELT_OK;
    for (unsigned bi = 0; bi < mesh->mNumBones && mesh->mBones; bi++) {
        const struct aiBone *bone = mesh->mBones[bi];
        if (!bone) continue;
        int32_t n = node_named(s, &bone->mName); /* skin_matrices refused a bone naming no node */
        float offset[16];
        to_column_major(&bone->mOffsetMatrix, offset);
        for (int k = 0; k < 16; k++)
            if (!isfinite(offset[k]))
                return pelt__fail(s->err, PELT_ERR_FORMAT, "%s: bone '%s' has a non-finite offset matrix", s->path,
                                  bone->mName.data);
        uint32_t b = 0;
        pelt_status st = add_bone(s, (uint32_t)n, offset, &b);
        if (st) return st;
        s->real_bones++;
        s->bone_real[b] = 1;
        for (unsigned w = 0; w < bone->mNumWeights; w++) {
            const struct aiVertexWeight vw = bone->mWeights[w]; /* in range: skin_matrices checked */
            if (!isfinite(vw.mWeight) || vw.mWeight < 0.0f)
                return pelt__fail(s->err, PELT_ERR_FORMAT, "%s: bone '%s' gives vertex %u the weight %g", s->path,
                                  bone->mName.data, vw.mVertexId, (double)vw.mWeight);
            if (vw.mWeight > 0.0f) weigh(s, base + vw.mVertexId, b, vw.mWeight);
        }
    }
    int32_t own = node_index(s, node);
    for (unsigned v = 0; v < mesh->mNumVertices; v++) {
        float *ws = s->vweights + PELT__BONES_PER_VERTEX * (base + v);
        if (ws[0] > 0.0f) continue;
        /* A skinned mesh's vertex that no bone weighs would stay behind
           while the rest of the mesh moves: the file is broken there. */
        if (mesh->mNumBones > 0 && mesh->mBones)
            return pelt__fail(s->err, PELT_ERR_FORMAT, "%s: vertex %u of mesh '%s' has bone weights summing to 0",
                              s->path, v, mesh->mName.data);
        if (own < 0) continue;
        if (s->node_bone[own] < 0) {
            uint32_t b = 0;
            pelt_status st = add_bone(s, (uint32_t)own, NULL, &b);
            if (st) return st;
            s->node_bone[own] = (int32_t)b;
        }
        weigh(s, base + v, (uint32_t)s->node_bone[own], 1.0f);
    }
    return PELT_OK;
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
        int32_t n = node_named(s, &bone->mName);
        if (n < 0)
            return pelt__fail(s->err, PELT_ERR_FORMAT, "%s: bone '%s' of mesh '%s' names no node", s->path,
                              bone->mName.data, mesh->mName.data);
        struct aiMatrix4x4 g, m;
        node_global(s->nodes[n], &g);
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
static pelt_status append_mesh(merge_state *s, const struct aiMesh *mesh, const struct aiNode *node,
                               const struct aiMatrix4x4 *node_m)
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
    if (st == PELT_OK) st = weigh_mesh(s, mesh, node, base);
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

static bool has_skeleton(const struct aiScene *scene)
{
    if (scene->mNumAnimations > 0 && scene->mAnimations) return true;
    for (unsigned i = 0; i < scene->mNumMeshes; i++)
        if (scene->mMeshes[i] && scene->mMeshes[i]->mNumBones > 0) return true;
    return false;
}

/* Keys of one track into seconds; non-finite or unsorted keys are refused. */
static pelt_status take_vec_keys(const merge_state *s, const char *anim, const char *node, const char *what,
                                 const struct aiVectorKey *in, unsigned n, double tps, pelt__vec_key **out)
{
    *out = NULL;
    if (n == 0 || !in) return PELT_OK;
    *out = pelt__calloc(n, sizeof **out);
    if (!*out) return pelt__fail(s->err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory", s->path);
    for (unsigned k = 0; k < n; k++) {
        double t = in[k].mTime / tps;
        const float v[3] = {in[k].mValue.x, in[k].mValue.y, in[k].mValue.z};
        if (!isfinite(t) || !isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2]))
            return pelt__fail(s->err, PELT_ERR_FORMAT, "%s: animation '%s', node '%s': %s key %u is not finite",
                              s->path, anim, node, what, k);
        if (k > 0 && t < (*out)[k - 1].time)
            return pelt__fail(s->err, PELT_ERR_FORMAT, "%s: animation '%s', node '%s': %s keys go back in time",
                              s->path, anim, node, what);
        (*out)[k].time = (float)t;
        memcpy((*out)[k].v, v, sizeof v);
    }
    return PELT_OK;
}

static pelt_status take_quat_keys(const merge_state *s, const char *anim, const char *node,
                                  const struct aiQuatKey *in, unsigned n, double tps, pelt__quat_key **out)
{
    *out = NULL;
    if (n == 0 || !in) return PELT_OK;
    *out = pelt__calloc(n, sizeof **out);
    if (!*out) return pelt__fail(s->err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory", s->path);
    for (unsigned k = 0; k < n; k++) {
        double t = in[k].mTime / tps;
        float q[4] = {in[k].mValue.x, in[k].mValue.y, in[k].mValue.z, in[k].mValue.w};
        float l = sqrtf(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        if (!isfinite(t) || !isfinite(l) || !(l > 0.0f))
            return pelt__fail(s->err, PELT_ERR_FORMAT,
                              "%s: animation '%s', node '%s': rotation key %u is not a finite rotation", s->path,
                              anim, node, k);
        if (k > 0 && t < (*out)[k - 1].time)
            return pelt__fail(s->err, PELT_ERR_FORMAT, "%s: animation '%s', node '%s': rotation keys go back in time",
                              s->path, anim, node);
        (*out)[k].time = (float)t;
        for (int c = 0; c < 4; c++) (*out)[k].q[c] = q[c] / l;
    }
    return PELT_OK;
}

static pelt_status take_animation(const merge_state *s, const struct aiAnimation *in, pelt__animation *a)
{
    size_t len = strnlen(in->mName.data, sizeof a->name - 1);
    memcpy(a->name, in->mName.data, len);
    a->name[len] = '\0';
    double tps = in->mTicksPerSecond > 0.0 && isfinite(in->mTicksPerSecond) ? in->mTicksPerSecond : 25.0;
    double last = 0.0;
    a->channels = in->mNumChannels ? pelt__calloc(in->mNumChannels, sizeof *a->channels) : NULL;
    if (in->mNumChannels && !a->channels) return pelt__fail(s->err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory", s->path);
    for (unsigned c = 0; c < in->mNumChannels && in->mChannels; c++) {
        const struct aiNodeAnim *na = in->mChannels[c];
        if (!na) continue;
        int32_t node = node_named(s, &na->mNodeName);
        if (node < 0) continue; /* animates nothing that is drawn */
        pelt__channel *ch = &a->channels[a->channel_count++];
        ch->node = (uint32_t)node;
        const char *nn = na->mNodeName.data;
        pelt_status st = take_vec_keys(s, a->name, nn, "position", na->mPositionKeys, na->mNumPositionKeys, tps, &ch->pos);
        if (st == PELT_OK) st = take_quat_keys(s, a->name, nn, na->mRotationKeys, na->mNumRotationKeys, tps, &ch->rot);
        if (st == PELT_OK)
            st = take_vec_keys(s, a->name, nn, "scaling", na->mScalingKeys, na->mNumScalingKeys, tps, &ch->scale);
        if (st) return st;
        ch->pos_count = ch->pos ? na->mNumPositionKeys : 0;
        ch->rot_count = ch->rot ? na->mNumRotationKeys : 0;
        ch->scale_count = ch->scale ? na->mNumScalingKeys : 0;
        if (ch->pos_count) last = fmax(last, ch->pos[ch->pos_count - 1].time);
        if (ch->rot_count) last = fmax(last, ch->rot[ch->rot_count - 1].time);
        if (ch->scale_count) last = fmax(last, ch->scale[ch->scale_count - 1].time);
    }
    double duration = in->mDuration / tps;
    if (!(duration > 0.0) || !isfinite(duration)) duration = last;
    a->duration = (float)fmax(duration, 1e-3);
    return PELT_OK;
}

/* The mesh's skeleton from the nodes, bones and weights gathered while
 * merging, its vertices renumbered by `remap` (pelt__mesh_create_remap). */
static pelt_status build_skeleton(merge_state *s, pelt_mesh *m, const uint32_t *remap)
{
    pelt__skeleton *k = pelt__calloc(1, sizeof *k);
    if (!k) return pelt__fail(s->err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory", s->path);
    m->skeleton = k;
    size_t nv = m->vertex_count;
    k->node_count = s->node_count;
    k->parent = pelt__calloc(s->node_count, sizeof *k->parent);
    k->rest = pelt__calloc(s->node_count, 16 * sizeof(float));
    k->rest_trs = pelt__calloc(s->node_count, 10 * sizeof(float));
    k->bone_count = s->bone_count;
    k->real_bones = s->real_bones;
    k->bone_node = pelt__calloc(s->bone_count ? s->bone_count : 1, sizeof *k->bone_node);
    k->bone_offset = pelt__calloc(s->bone_count ? s->bone_count : 1, 16 * sizeof(float));
    k->vertex_count = nv;
    k->bones = pelt__calloc(nv, PELT__BONES_PER_VERTEX * sizeof *k->bones);
    k->weights = pelt__calloc(nv, PELT__BONES_PER_VERTEX * sizeof *k->weights);
    k->bind = pelt__calloc(nv, 10 * sizeof(float));
    k->scratch_globals = pelt__calloc(s->node_count, 16 * sizeof(float));
    k->scratch_skin = pelt__calloc(s->bone_count ? s->bone_count : 1, 16 * sizeof(float));
    if (!k->parent || !k->rest || !k->rest_trs || !k->bone_node || !k->bone_offset || !k->bones || !k->weights ||
        !k->bind || !k->scratch_globals || !k->scratch_skin)
        return pelt__fail(s->err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory for the skeleton", s->path);
    for (uint32_t i = 0; i < s->node_count; i++) {
        k->parent[i] = s->node_parent[i];
        to_column_major(&s->nodes[i]->mTransformation, k->rest + 16 * i);
        float *trs = k->rest_trs + 10 * i;
        if (!pelt__matrix_trs(k->rest + 16 * i, trs, trs + 3, trs + 7))
            return pelt__fail(s->err, PELT_ERR_FORMAT, "%s: node '%s' has a transform of zero scale", s->path,
                              s->nodes[i]->mName.data);
    }
    memcpy(k->bone_node, s->bone_node, s->bone_count * sizeof *k->bone_node);
    memcpy(k->bone_offset, s->bone_offset, s->bone_count * 16 * sizeof(float));
    for (size_t i = 0; i < s->v_at; i++) {
        if (!remap[i]) continue;
        size_t o = remap[i] - 1;
        const float *w = s->vweights + PELT__BONES_PER_VERTEX * i;
        const uint16_t *b = s->vbones + PELT__BONES_PER_VERTEX * i;
        float sum = 0.0f;
        for (int j = 0; j < PELT__BONES_PER_VERTEX; j++) sum += w[j] > 0.0f ? w[j] : 0.0f;
        bool real = false;
        for (int j = 0; j < PELT__BONES_PER_VERTEX; j++) {
            float wj = w[j] > 0.0f && sum > 0.0f ? w[j] / sum : 0.0f;
            k->weights[PELT__BONES_PER_VERTEX * o + j] = wj;
            k->bones[PELT__BONES_PER_VERTEX * o + j] = wj > 0.0f ? b[j] : 0;
            if (wj > 0.0f && b[j] < s->bone_count && s->bone_real[b[j]]) real = true;
        }
        if (real) k->skinned++;
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
    bool skeleton = has_skeleton(scene);
    if (skeleton) {
        s.bone_room = PELT_MAX_BONES + PELT__MAX_SKELETON_NODES;
        s.nodes = pelt__calloc(PELT__MAX_SKELETON_NODES, sizeof *s.nodes);
        s.node_parent = pelt__calloc(PELT__MAX_SKELETON_NODES, sizeof *s.node_parent);
        s.node_bone = pelt__calloc(PELT__MAX_SKELETON_NODES, sizeof *s.node_bone);
        s.bone_node = pelt__calloc(s.bone_room, sizeof *s.bone_node);
        s.bone_offset = pelt__calloc(s.bone_room, 16 * sizeof(float));
        s.bone_real = pelt__calloc(s.bone_room, 1);
        s.vbones = pelt__calloc(s.vertex_count, PELT__BONES_PER_VERTEX * sizeof *s.vbones);
        s.vweights = pelt__calloc(s.vertex_count, PELT__BONES_PER_VERTEX * sizeof *s.vweights);
    }
    if (!s.positions || !s.indices || (s.have_normals && !s.normals) || (s.have_uvs && !s.uvs) ||
        (s.have_colors && (!s.directions || !s.colors)) ||
        (skeleton && (!s.nodes || !s.node_parent || !s.node_bone || !s.bone_node || !s.bone_offset ||
                      !s.bone_real || !s.vbones || !s.vweights))) {
        st = pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: no memory for %zu vertices", path,
                        s.vertex_count);
    } else {
        if (skeleton) st = collect_nodes(&s, scene->mRootNode, -1, 0);
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
        st = remap ? build_skeleton(&s, *out, remap) : pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
        pelt__skeleton *k = st == PELT_OK ? (*out)->skeleton : NULL;
        if (k && scene->mNumAnimations && scene->mAnimations) {
            k->animations = pelt__calloc(scene->mNumAnimations, sizeof *k->animations);
            if (!k->animations) st = pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
            for (unsigned a = 0; st == PELT_OK && a < scene->mNumAnimations; a++) {
                if (!scene->mAnimations[a]) continue;
                st = take_animation(&s, scene->mAnimations[a], &k->animations[k->animation_count++]);
            }
        }
        if (k && st == PELT_OK && !pelt__skeleton_bind(k, (*out)->positions, (*out)->normals, (*out)->tangents))
            st = pelt__fail(err, PELT_ERR_FORMAT, "%s: a vertex's bones have a singular transform", path);
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
    free(s.nodes);
    free(s.node_parent);
    free(s.node_bone);
    free(s.bone_node);
    free(s.bone_offset);
    free(s.bone_real);
    free(s.vbones);
    free(s.vweights);
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
