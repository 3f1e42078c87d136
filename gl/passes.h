/* The passes of one frame (Lengyel et al. 2001 §2.3, Silva et al. §4), one
 * file each: gl/skin_pass.c, gl/shell_pass.c, ... renderer.c plans the
 * frame (core/fur/frame_plan.c), binds the shared objects of gl/gpu.h (VAO,
 * textures, uniform blocks), runs its table of passes in order, then resets
 * GL state as pelt/render.h states.
 *
 * To add a pass: its shaders as gl/shaders/NAME_vs.glsl and NAME_fs.glsl
 * (listed in PELT_SHADERS of CMakeLists.txt, declared in gl/programs.h), a
 * gl/NAME_pass.c with create / draw / destroy as below (build its program
 * with pelt__gl_program_create, set its own state and its own few uniforms
 * in draw, count its draw calls in the stats), its state in pelt_renderer
 * and a row in renderer.c's pass table, run when the frame plan says so. A
 * new attribute, texture unit or uniform block gets its number in
 * shaders/bindings.glsl. */
#ifndef PELT_GL_PASSES_H
#define PELT_GL_PASSES_H

#include "core/fur/frame_plan.h"
#include "gl/gpu.h"

/* What a pass draws with in one frame; the shared objects are bound. */
typedef struct pelt__pass_frame {
    const pelt__gpu_mesh *mesh;
    unsigned layers;          /* N, the fur's shell count */
    const pelt_draw_desc *draw;
    pelt_render_stats *stats; /* the pass adds its draw calls and triangles */
    pelt__frame_lod lod;
    const pelt_view *view;
    unsigned shell_features;  /* PELT__SHELL_* the shells need this frame */
    bool view_split;          /* the mesh's view split holds the drawn triangles */
} pelt__pass_frame;

/* The #define lines of `features` (PELT_WET, ...), for a program's sources. */
#define PELT__FEATURE_DEFINES_MAX 448
void pelt__shell_feature_defines(unsigned features, char out[PELT__FEATURE_DEFINES_MAX]);

/* The fins use the features that concern them. */
#define PELT__FIN_FEATURES                                                                                \
    (PELT__SHELL_WET | PELT__SHELL_COLOR_TEXTURE | PELT__SHELL_KAJIYA_KAY | PELT__SHELL_LIGHT_TABLE |    \
     PELT__SHELL_SHADOW_MAP | PELT__SHELL_RINGLETS)
#define PELT__FIN_VARIANTS (PELT__FIN_FEATURES + 1)

/* The outline's hairs, lit per vertex, use the light's. */
#define PELT__OUTLINE_FEATURES (PELT__SHELL_KAJIYA_KAY | PELT__SHELL_LIGHT_TABLE | PELT__SHELL_SHADOW_MAP)

/* The skin uses these: a branch it never takes still costs llvmpipe every
 * fragment (docs/lod.md), so the shadow-map taps are compiled in only
 * when the light's maps are on. */
#define PELT__SKIN_FEATURES (PELT__SHELL_WET | PELT__SHELL_COLOR_TEXTURE | PELT__SHELL_SHADOW_MAP)

/* Opaque skin with depth write: the mesh with the innermost fur slice, in
 * variants by the PELT__SKIN_FEATURES bits (the generic one, all of them,
 * built at creation; the others on first use). */
typedef struct pelt__skin_pass {
    GLuint variants[PELT__SKIN_FEATURES + 1];
    bool failed[PELT__SKIN_FEATURES + 1];
    pelt_hooks hooks;
} pelt__skin_pass;

pelt_status pelt__skin_pass_create(pelt__skin_pass *p, const pelt_hooks *hooks, pelt_error *err);
void pelt__skin_pass_draw(pelt__skin_pass *p, const pelt__pass_frame *f);
void pelt__skin_pass_destroy(pelt__skin_pass *p);

/* All fins in one instanced draw (Lengyel et al. §2.3): the fins the view
 * shows and the strands of their vertices, worked out each frame by
 * core/fur/fin_frame.c into two table textures (staging allocated once),
 * PELT_FIN_CHUNK strips of up to PELT_FIN_ROWS quads per instance. Owns
 * the fin texture, the tables and the chunks' index buffer. */
typedef struct pelt__fin_pass {
    GLuint variants[PELT__FIN_VARIANTS]; /* by the PELT__FIN_FEATURES bits */
    bool failed[PELT__FIN_VARIANTS];
    GLint fin_count[PELT__FIN_VARIANTS]; /* u_fin_count */
    GLint fin_rows[PELT__FIN_VARIANTS];  /* u_fin_rows */
    GLint fin_first[PELT__FIN_VARIANTS]; /* u_fin_first */
    GLint fin_hairs[PELT__FIN_VARIANTS]; /* u_outline_on: the outline's hairs take over from the quads */
    GLint fin_viewport[PELT__FIN_VARIANTS]; /* u_viewport */
    /* The outline's hairs (outline_vs.glsl), by the PELT__OUTLINE_FEATURES bits. */
    GLuint outline[PELT__OUTLINE_FEATURES + 1];
    bool outline_failed[PELT__OUTLINE_FEATURES + 1];
    GLint outline_count[PELT__OUTLINE_FEATURES + 1];
    GLint outline_rows[PELT__OUTLINE_FEATURES + 1], outline_hairs[PELT__OUTLINE_FEATURES + 1];
    GLint outline_viewport[PELT__OUTLINE_FEATURES + 1];
    size_t frame_fins;   /* the fins the last fin pass wrote into `fins` */
    unsigned frame_rows; /* and their rows */
    pelt_hooks hooks;
    GLuint vao, ebo;    /* the chunk's triangles */
    GLuint texture;     /* the fin texture, PELT_UNIT_FIN */
    GLuint edges;        /* this frame's fins, PELT_UNIT_FIN_EDGES (RGBA32UI) */
    GLuint vertex_table; /* their vertices, PELT_UNIT_FIN_VERTICES (RGBA32F) */
    const pelt_fur *fur;
    const pelt__lod_chain *lod;
    uint32_t *fins;      /* staging, allocated once (core/fur/fur_gpu.h) */
    float *vertices;
    float hairs_per_tile; /* the outline's hairs a fur tile of a fin's edge holds */
    float tiling;        /* the fur's tiles a mesh unit */
    float slab;          /* the fin texture's slab, fur tiles */
    float viewport[2];   /* this frame's, pixels */
    bool curled;         /* the fur curls in its texture: the quads alone */
    bool hairs_on;       /* this frame draws the outline's hairs */
    uint32_t *hairs;     /* the outline's hairs, staging, allocated once */
    GLuint hair_table;   /* and their table, bound to PELT_UNIT_FIN_EDGES to draw */
    pelt_allocator alloc;
} pelt__fin_pass;

pelt_status pelt__fin_pass_create(pelt__fin_pass *p, pelt_fur *fur, const pelt__fur_snapshot *fs,
                                  const pelt_hooks *hooks, pelt_error *err);
void pelt__fin_pass_draw(pelt__fin_pass *p, const pelt__pass_frame *f);
/* The outline's hairs (outline_vs.glsl) of the fins the frame's fin pass
 * wrote, after the shells: nothing where pelt_draw_desc.no_outline_hairs
 * or fins_unfaded is set or the fur curls in its texture. */
void pelt__fin_pass_draw_outline(pelt__fin_pass *p, const pelt__pass_frame *f);
void pelt__fin_pass_destroy(pelt__fin_pass *p);

/* The strand reference (core/fur/strand_ref.h, docs/reference.md): every
 * hair of the fur texture's tile over the surface as an opaque,
 * camera-facing ribbon, ONE draw from a buffer texture the CPU fills each
 * frame. Its storage is made the first time a frame draws strands (as the
 * shells' variants build on first use), never for a frame of shells. */
#define PELT__STRAND_FEATURES (PELT__SHELL_KAJIYA_KAY | PELT__SHELL_LIGHT_TABLE | PELT__SHELL_SHADOW_MAP)
typedef struct pelt__strands_pass {
    GLuint variants[PELT__STRAND_FEATURES + 1];
    GLint segments_uniform[PELT__STRAND_FEATURES + 1]; /* u_strand_segments of each */
    bool failed[PELT__STRAND_FEATURES + 1];
    GLuint light_program; /* the hairs into the light's maps (PELT_LIGHT_PASS) */
    GLint light_segments;
    bool light_failed;
    size_t light_hairs;   /* hairs the light pass uploaded for this frame's draw, or 0 */
    GLuint buffer, texture; /* the hairs (RGBA32F buffer texture, PELT_UNIT_STRANDS) */
    pelt_hooks hooks;
    const pelt_fur *fur;
    void *tile;    /* the tile's strands (pelt__furtex_strand) */
    size_t tile_count;
    float *hairs;  /* staging, PELT__STRAND_TEXELS(segments) * 4 floats a hair */
    size_t capacity; /* hairs with every strand kept */
    unsigned segments; /* a hair's pieces the storage has room for */
    bool made, broken;
} pelt__strands_pass;

void pelt__strands_pass_create(pelt__strands_pass *p, const pelt_fur *fur, const pelt_hooks *hooks);
/* Draws every hair; depth tested and written, opaque. */
void pelt__strands_pass_draw(pelt__strands_pass *p, const pelt__pass_frame *f);
/* Draws every hair from the light into the bound opacity slices, each
 * adding its coverage (the light pass's state, gl/shadow_pass.c); the
 * frame's pelt__strands_pass_draw then draws the same hairs, not built again. */
void pelt__strands_pass_draw_light(pelt__strands_pass *p, const pelt__pass_frame *f);
void pelt__strands_pass_destroy(pelt__strands_pass *p);

typedef struct pelt__shell_program {
    GLuint program;
    GLint shells, shells_next, shell_view, back_reach, instance_base; /* uniform locations (shell_vs.glsl) */
    GLint no_inter_shadow, sub_shells, sub_view, no_overcount, fur_taps, fur_aniso, edge_depth;
    bool failed;               /* did not build: the generic one stands in */
} pelt__shell_program;

/* All shells in one instanced draw, blended inner to outer, depth tested
 * without depth write. Variants build the first time a frame needs them
 * (tens of milliseconds on llvmpipe, once); the generic one and the floor
 * (pelt_draw_desc.debug.floor_shader) at creation, the plain renderer
 * (debug.plain_shells) the first time it draws. */
typedef struct pelt__shell_pass {
    pelt__shell_program variants[PELT__SHELL_VARIANTS];
    pelt__shell_program floor;
    pelt__shell_program plain;
    pelt_hooks hooks;
} pelt__shell_pass;

pelt_status pelt__shell_pass_create(pelt__shell_pass *p, const pelt_hooks *hooks, pelt_error *err);
/* The program with `features`, built on first use; the generic one when
 * it does not build (a light-pass variant that does not build: NULL). */
const pelt__shell_program *pelt__shell_pass_program(pelt__shell_pass *p, unsigned features);
void pelt__shell_pass_draw(pelt__shell_pass *p, const pelt__pass_frame *f);
/* Whether a wet frame's shells draw wet and dry apart (the wet split):
 * the full mesh, at least a third of it dry. */
bool pelt__shell_pass_wet_apart(const pelt__pass_frame *f);
void pelt__shell_pass_destroy(pelt__shell_pass *p);

/* The light's maps (Yuksel and Keyser's deep opacity maps, docs/shadows.md):
 * the skin's depth, then the fur's opacity in slices of a slab in front of
 * it, both drawn from the light into textures of its own framebuffers
 * (made by pelt__shadow_pass_resize, never in a frame). Binds them to
 * PELT_UNIT_SHADOW_* for the passes that receive. */
typedef struct pelt__shadow_pass {
    GLuint depth_program;
    GLuint depth_fbo, opacity_fbo;
    GLuint depth, opacity; /* DEPTH_COMPONENT24; RGBA16F array, 2 layers */
    unsigned size;         /* texels a side, 0 before the first resize */
} pelt__shadow_pass;


pelt_status pelt__shadow_pass_create(pelt__shadow_pass *p, const pelt_hooks *hooks, pelt_error *err);
/* (Re)makes the maps at size x size; PELT_ERR_GL when the framebuffers are
 * incomplete. */
pelt_status pelt__shadow_pass_resize(pelt__shadow_pass *p, unsigned size, pelt_error *err);
/* Draws the maps; restores the caller's framebuffers, viewport, scissor
 * test and colour mask. */
void pelt__shadow_pass_draw(const pelt__shadow_pass *p, pelt__shell_pass *shells, const pelt__pass_frame *f,
                            const pelt__shadow_frame *sf);
/* The same maps for the strand reference: its hairs' opacity in place of
 * the shells', so that the reference shades itself by its own hairs. */
void pelt__shadow_pass_draw_strands(const pelt__shadow_pass *p, pelt__strands_pass *strands,
                                    const pelt__pass_frame *f, const pelt__shadow_frame *sf);
/* Binds the maps to their units (after the draw, for the receivers). */
void pelt__shadow_pass_bind(const pelt__shadow_pass *p);
void pelt__shadow_pass_destroy(pelt__shadow_pass *p);

/* The ground disc (pelt/shadow.h), opaque but for its faded rim, drawn
 * first with depth write. */
typedef struct pelt__ground_pass {
    GLuint program;
    GLint ground, color; /* uniform locations */
} pelt__ground_pass;

pelt_status pelt__ground_pass_create(pelt__ground_pass *p, const pelt_hooks *hooks, pelt_error *err);
/* disc: centre x, plane height, centre z, radius (world). */
void pelt__ground_pass_draw(const pelt__ground_pass *p, const pelt__pass_frame *f, const float disc[4],
                            const float color[3]);
void pelt__ground_pass_destroy(pelt__ground_pass *p);

#endif
