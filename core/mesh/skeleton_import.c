/* Skeleton import from assimp's node tree, bones and animations (see
 * skeleton_import.h). */
#include "core/mesh/skeleton_import.h"
#include "core/mesh/mesh_internal.h"
#include "core/mesh/skeleton.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/vec.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* assimp's matrices are row-major: the same 16 floats read column-major
 * are the transposes, so this is pelt's one product with the factors
 * swapped. */
void pelt__ai_mat_mul(struct aiMatrix4x4 *out, const struct aiMatrix4x4 *a, const struct aiMatrix4x4 *b)
{
    _Static_assert(sizeof *out == 16 * sizeof(float), "assimp built with single-precision ai_real");
    float fa[16], fb[16], r[16];
    memcpy(fa, a, sizeof fa);
    memcpy(fb, b, sizeof fb);
    pelt__mat4_mul(r, fb, fa);
    memcpy(out, r, sizeof r);
}

/* A node's transform to the scene root: its own and its parents'. */
static void node_global(const struct aiNode *node, struct aiMatrix4x4 *out)
{
    struct aiMatrix4x4 m = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    for (int depth = 0; node && depth <= PELT__MAX_NODE_DEPTH; node = node->mParent, depth++) {
        struct aiMatrix4x4 t;
        pelt__ai_mat_mul(&t, &node->mTransformation, &m);
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

static pelt_status collect_nodes(pelt__skeleton_import *s, const struct aiNode *node, int32_t parent, int depth)
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

static int32_t node_index(const pelt__skeleton_import *s, const struct aiNode *node)
{
    for (uint32_t i = 0; i < s->node_count; i++)
        if (s->nodes[i] == node) return (int32_t)i;
    return -1;
}

static int32_t node_named(const pelt__skeleton_import *s, const struct aiString *name)
{
    for (uint32_t i = 0; i < s->node_count; i++)
        if (s->nodes[i]->mName.length == name->length && !memcmp(s->nodes[i]->mName.data, name->data, name->length))
            return (int32_t)i;
    return -1;
}

/* A new bone: `node` with `offset` (column-major, NULL: identity). */
static pelt_status add_bone(pelt__skeleton_import *s, uint32_t node, const float *offset, uint32_t *out)
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
static void weigh(pelt__skeleton_import *s, size_t v, uint32_t bone, float w)
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

pelt_status pelt__skeleton_import_weigh(pelt__skeleton_import *s, const struct aiMesh *mesh, const struct aiNode *node,
                                        size_t base)
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

pelt_status pelt__skeleton_import_skin(const pelt__skeleton_import *s, const struct aiMesh *mesh, float *skin, float *weight)
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
        pelt__ai_mat_mul(&m, &g, &bone->mOffsetMatrix);
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

bool pelt__skeleton_import_wanted(const struct aiScene *scene)
{
    if (scene->mNumAnimations > 0 && scene->mAnimations) return true;
    for (unsigned i = 0; i < scene->mNumMeshes; i++)
        if (scene->mMeshes[i] && scene->mMeshes[i]->mNumBones > 0) return true;
    return false;
}

/* Keys of one track into seconds; non-finite or unsorted keys are refused. */
static pelt_status take_vec_keys(const pelt__skeleton_import *s, const char *anim, const char *node, const char *what,
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

static pelt_status take_quat_keys(const pelt__skeleton_import *s, const char *anim, const char *node,
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

static pelt_status take_animation(const pelt__skeleton_import *s, const struct aiAnimation *in, pelt__animation *a)
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
static pelt_status build_skeleton(pelt__skeleton_import *s, pelt_mesh *m, const uint32_t *remap, size_t merged)
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
    for (size_t i = 0; i < merged; i++) {
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

pelt_status pelt__skeleton_import_begin(pelt__skeleton_import *s, const struct aiScene *scene, size_t vertex_count)
{
    s->bone_room = PELT_MAX_BONES + PELT__MAX_SKELETON_NODES;
    s->nodes = pelt__calloc(PELT__MAX_SKELETON_NODES, sizeof *s->nodes);
    s->node_parent = pelt__calloc(PELT__MAX_SKELETON_NODES, sizeof *s->node_parent);
    s->node_bone = pelt__calloc(PELT__MAX_SKELETON_NODES, sizeof *s->node_bone);
    s->bone_node = pelt__calloc(s->bone_room, sizeof *s->bone_node);
    s->bone_offset = pelt__calloc(s->bone_room, 16 * sizeof(float));
    s->bone_real = pelt__calloc(s->bone_room, 1);
    s->vbones = pelt__calloc(vertex_count, PELT__BONES_PER_VERTEX * sizeof *s->vbones);
    s->vweights = pelt__calloc(vertex_count, PELT__BONES_PER_VERTEX * sizeof *s->vweights);
    if (!s->nodes || !s->node_parent || !s->node_bone || !s->bone_node || !s->bone_offset || !s->bone_real ||
        !s->vbones || !s->vweights)
        return pelt__fail(s->err, PELT_ERR_OUT_OF_MEMORY, "%s: no memory for %zu vertices", s->path, vertex_count);
    return collect_nodes(s, scene->mRootNode, -1, 0);
}

pelt_status pelt__skeleton_import_finish(pelt__skeleton_import *s, const struct aiScene *scene, pelt_mesh *m,
                                         const uint32_t *remap, size_t merged)
{
    pelt_status st = build_skeleton(s, m, remap, merged);
    pelt__skeleton *k = st == PELT_OK ? m->skeleton : NULL;
    if (k && scene->mNumAnimations && scene->mAnimations) {
        k->animations = pelt__calloc(scene->mNumAnimations, sizeof *k->animations);
        if (!k->animations) st = pelt__fail(s->err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory", s->path);
        for (unsigned a = 0; st == PELT_OK && a < scene->mNumAnimations; a++) {
            if (!scene->mAnimations[a]) continue;
            st = take_animation(s, scene->mAnimations[a], &k->animations[k->animation_count++]);
        }
    }
    if (k && st == PELT_OK && !pelt__skeleton_bind(k, m->positions, m->normals, m->tangents))
        st = pelt__fail(s->err, PELT_ERR_FORMAT, "%s: a vertex's bones have a singular transform", s->path);
    return st;
}

void pelt__skeleton_import_free(pelt__skeleton_import *s)
{
    free(s->nodes);
    free(s->node_parent);
    free(s->node_bone);
    free(s->bone_node);
    free(s->bone_offset);
    free(s->bone_real);
    free(s->vbones);
    free(s->vweights);
}
