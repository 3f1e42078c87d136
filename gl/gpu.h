/* The GPU objects every pass shares: vertex and index buffers, the fur
 * textures, the uniform blocks, program building, the GL state contract
 * and the hooks. Private to gl/ (pelt__ prefix). Numbers that GLSL also
 * needs come from gl/shaders/bindings.glsl. */
#ifndef PELT_GL_GPU_H
#define PELT_GL_GPU_H

#include "pelt/render.h"

#include "core/base/hooks.h"
#include "core/fur/frame_plan.h"
#include "core/fur/fur_gpu.h" /* core/fur/lod.h: the levels of detail; core/wet/wet_split.h */

#include "gl/shaders/bindings.glsl"

#include "gl/gl_api.h"
#include <stddef.h>

/* ---- the GL state contract of pelt/render.h (gl/gl_state.c) ------------ */

/* Pixel unpack state at GL's initial values and no unpack buffer: what
 * every texture upload here assumes. */
void pelt__gl_unpack_defaults(void);
/* Returns everything the renderer touches to GL's initial values, as
 * pelt/render.h states. */
void pelt__gl_state_reset(void);
/* The state of the blended hair passes (fins, shells): depth tested
 * without depth write, no culling, blended over what is there. */
void pelt__gl_blended_hair_state(void);

/* ---- programs (gl/programs.c) ------------------------------------------ */

/* Builds a renderer program: the uniform blocks (shaders/blocks.glsl) go
 * before each stage's pieces (NULL-terminated), the blocks are bound to
 * PELT_BLOCK_* and the samplers u_fur, u_color_tex, u_mask to PELT_UNIT_*.
 * A compile or link error also goes to hooks->logger. Leaves the program
 * current. */
pelt_status pelt__gl_program_create(const char *what, const char *const *vertex_parts,
                                    const char *const *fragment_parts, const pelt_hooks *hooks,
                                    GLuint *out, pelt_error *err);

/* ---- vertex and index buffers (gl/gpu_mesh.c) -------------------------- */

typedef struct pelt__gpu_mesh {
    GLuint vao;
    GLuint vbo_static; /* interleaved: uv, fur uv, comb */
    GLuint vbo_pose;   /* interleaved: position, normal, tangent (the fur's pose) */
    GLuint vbo_tips;   /* PELT_ATTR_TIP, rewritten when the strands move */
    GLuint vbo_groom;  /* PELT_ATTR_GROOM and PELT_ATTR_HAIR_COLOR, the
                          changed range rewritten after a brush or a map */
    GLuint ebo;           /* the mesh's triangles, then each level of detail's */
    size_t vertex_count;
    size_t triangle_count;
    size_t level_offset[PELT__LOD_MAX_LEVELS];    /* bytes into ebo */
    size_t level_triangles[PELT__LOD_MAX_LEVELS];
    unsigned level_count;
    /* PELT_ATTR_FIT_NORMAL: a slice of vertex_count vec3 for each level,
     * zeros for the full mesh and the levels whose normals are not fitted
     * (slice 0), then levels 1 .. fit_levels (lod.h's fit_normals). */
    GLuint vbo_fit;
    unsigned fit_levels;
    /* The mesh's triangles again, dry ones first (core/wet/wet_split.h),
     * after the levels in ebo: the shells draw the dry part with the dry
     * shader. split_ok false: out of memory, every triangle draws wet. */
    pelt__wet_split split;
    size_t split_offset; /* bytes into ebo */
    bool split_ok;
    /* The drawn level's triangles again, those whose shells never read the
     * gap first (pelt__fur_gpu_view_split), after the wet split in ebo:
     * rewritten when the view moves them. view_ok false: out of memory. */
    uint32_t *view_indices; /* the last split, room for the full mesh */
    uint32_t *view_staging; /* this frame's, compared with it */
    uint8_t *view_side;     /* per vertex, the split's scratch */
    size_t view_offset;     /* bytes into ebo */
    size_t view_face, view_total;
    /* A wet frame's: the wet split's dry part split so (view_face of its
     * view_total), then its wet part (view_wet_face of view_wet_total). */
    bool view_wet;
    size_t view_wet_face, view_wet_total;
    bool view_ok;
    unsigned tips_version;
    unsigned pose_version;
    /* A skinned mesh, skinned in the vertex stage (for measuring): */
    bool skinned;
    GLuint vao_skin;
    GLuint vbo_bind;     /* bind-space position, normal, tangent; weights */
    GLuint vbo_bones;    /* 4 bones a vertex, u16 */
    GLuint bone_texture; /* PELT_UNIT_BONES */
    unsigned bone_rows;
    float *bone_staging; /* allocated once */
    pelt_allocator alloc;
} pelt__gpu_mesh;

/* Uploads the mesh's attributes with the fur's uvs and strand tips. The
 * interleaved array is allocated through hooks and freed before return.
 * On failure *g holds what was made (free it with pelt__gpu_mesh_destroy). */
pelt_status pelt__gpu_mesh_create(pelt__gpu_mesh *g, const pelt_mesh *mesh, pelt_fur *fur,
                                  const pelt_hooks *hooks, pelt_error *err);
/* Rewrites the tip buffer when the strands moved and the changed range of
 * the groom buffer; returns bytes sent. */
size_t pelt__gpu_mesh_upload(pelt__gpu_mesh *g, pelt_fur *fur, const pelt__fur_snapshot *fs);
/* Skinning in the vertex stage: the bones' matrices of the last pose into
 * their texture; returns bytes sent (0 for a mesh without a skeleton). */
size_t pelt__gpu_mesh_upload_bones(pelt__gpu_mesh *g, pelt_fur *fur);
/* The mask's texels in rect changed: triangles that turned wet or dry move
 * between the split's parts; returns bytes sent. */
size_t pelt__gpu_mesh_update_split(pelt__gpu_mesh *g, const pelt__fur_snapshot *fs, const unsigned rect[4]);
/* Splits the drawn triangles by the view (pelt__fur_gpu_view_split) and
 * rewrites the split's part of ebo when it changed (binding g->vao);
 * returns bytes sent. view_face and view_total say what it holds. */
size_t pelt__gpu_mesh_update_view(pelt__gpu_mesh *g, const pelt_fur *fur, const pelt__view_split_desc *d);
/* The same for a wet frame drawn apart (the full mesh): the wet split's
 * dry part and its wet part each split by the view, one after the other
 * (view_wet). Returns bytes sent. */
size_t pelt__gpu_mesh_update_view_wet(pelt__gpu_mesh *g, const pelt_fur *fur, const pelt__view_split_desc *d);
void pelt__gpu_mesh_destroy(pelt__gpu_mesh *g);
/* Points the bound VAO's PELT_ATTR_FIT_NORMAL at the slice of the level
 * the shells are drawn on (the full mesh: zeros). */
void pelt__gpu_mesh_point_fit(const pelt__gpu_mesh *g, bool full_mesh, unsigned level);

/* ---- fur textures (gl/gpu_fur.c) --------------------------------------- */

typedef struct pelt__gpu_fur {
    GLuint volume; /* 2D array, one slice a layer (Lengyel et al. §2.2) */
    GLuint color;  /* RGBA8, white 1x1 until the fur has a colour texture */
    GLuint mask;   /* RGBA32F wetness mask, nearest (Silva et al. §3.1) */
    GLuint light_table; /* RG32F 32x32, Lengyel et al. §2.4 */
    unsigned color_version;
} pelt__gpu_fur;

/* A hair texture (the fur volume, the fin texture) as a 2D array with
 * every mip level, made by pelt__fur_gpu_mip_down: each level's id is its
 * block's most covering hair's, where glGenerateMipmap would average ids.
 * _create allocates the levels of the bound GL_TEXTURE_2D_ARRAY and
 * filters it from the nearest level, bilinear within it (the shells
 * and fins pick it, fur_texture_lod), _slice
 * uploads slice z and its chain through `chain`, a scratch of
 * pelt__gpu_hair_chain_bytes(w, h). */
size_t pelt__gpu_hair_chain_bytes(unsigned w, unsigned h);
void pelt__gpu_hair_array_create(unsigned w, unsigned h, unsigned depth);
void pelt__gpu_hair_array_slice(unsigned z, const uint8_t *texels, unsigned w, unsigned h, uint8_t *chain);

pelt_status pelt__gpu_fur_create(pelt__gpu_fur *g, pelt_fur *fur, const pelt__fur_snapshot *fs,
                                 const pelt_hooks *hooks, pelt_error *err);
/* Uploads a new colour texture and the changed rectangle of the mask (in
 * mask_rect; empty when none); returns bytes sent. */
size_t pelt__gpu_fur_upload(pelt__gpu_fur *g, pelt_fur *fur, const pelt__fur_snapshot *fs, unsigned mask_rect[4]);
/* Binds the textures to their PELT_UNIT_* units. */
void pelt__gpu_fur_bind(const pelt__gpu_fur *g);
void pelt__gpu_fur_destroy(pelt__gpu_fur *g);

/* ---- uniform blocks (gl/uniform_blocks.c) ------------------------------ */

/* std140 images of the blocks in shaders/blocks.glsl: a vec3 takes 16
 * bytes unless a float follows it; offsets are asserted in
 * gl/uniform_blocks.c. */
typedef struct pelt__frame_block {
    float model[16], view_proj[16];
    float eye[3], ambient;
    float light_dir[3], exposure;
    float light_color[3], tone; /* pelt_tone */
    float view_dir[3], pad2_;
    float light_matrix[16];
    float shadow_map[4];  /* on, slices, 1 / size, filter radius in texels */
    float shadow_slab[4]; /* slab depth, density, fur bias, keep gamma */
} pelt__frame_block;

typedef struct pelt__fur_block {
    float color[3], layers;
    float tip_color[3], length;
    float specular[3], shininess;
    float fur_per_uv[2], shadow, curl_frequency;
    float curl_radius, clump_blend, clump_tightness, wet_darken;
    float color_scale, slant, wet_gloss, wet_sharpness;
    float skin_color[3], tiling;
    float fin_length, inter_shadow, inter_shadow_step, shading_model;
    float ringlets[2], occlusion, wet_strays;
    float ringlet_radius, strand_curl_radius, strand_curl_omega, strand_curl_wave;
    float clump_lean, hair_width, taper, wet_lie;
} pelt__fur_block;


typedef struct pelt__gpu_blocks {
    GLuint frame, fur;        /* uniform buffers */
    pelt__fur_block fur_sent; /* what the fur buffer holds, once fur_valid */
    bool fur_valid;
} pelt__gpu_blocks;

void pelt__gpu_blocks_create(pelt__gpu_blocks *b);
/* Uploads the per-frame block; returns bytes sent. */
size_t pelt__gpu_blocks_set_frame(pelt__gpu_blocks *b, const pelt_view *view, const pelt_draw_desc *draw,
                                  const pelt__frame_shadow *shadow);
/* Uploads the fur block when the fur's look differs from what was sent;
 * returns bytes sent. */
size_t pelt__gpu_blocks_set_fur(pelt__gpu_blocks *b, const pelt_fur *fur, const pelt__fur_snapshot *fs);
/* Binds the buffers to their PELT_BLOCK_* binding points. */
void pelt__gpu_blocks_bind(const pelt__gpu_blocks *b);
void pelt__gpu_blocks_destroy(pelt__gpu_blocks *b);

#endif
