/* The passes of one frame (Lengyel et al. 2001 §2.3, Silva et al. §4), one
 * file each: gl/skin_pass.c, gl/shell_pass.c. renderer.c binds the shared
 * objects of gl/gpu.h (VAO, textures, uniform blocks), runs the passes in
 * order, then resets GL state as pelt/render.h states.
 *
 * To add a pass (fins, shadow maps, level of detail): its shaders as
 * gl/shaders/NAME_vs.glsl and NAME_fs.glsl (listed in PELT_SHADERS of
 * CMakeLists.txt, declared in gl/programs.h), a gl/NAME_pass.c with
 * create / draw / destroy as below (build its program with
 * pelt__gl_program_create, set its own state and its own few uniforms in
 * draw, count its draw calls in the stats), its struct in pelt_renderer
 * and its call in pelt_renderer_draw in frame order. A new attribute,
 * texture unit or uniform block gets its number in shaders/bindings.glsl. */
#ifndef PELT_GL_PASSES_H
#define PELT_GL_PASSES_H

#include "gl/gpu.h"

/* What a pass draws with in one frame; the shared objects are bound. */
typedef struct pelt__pass_frame {
    const pelt__gpu_mesh *mesh;
    unsigned layers;          /* N, the fur's shell count */
    const pelt_draw_desc *draw;
    pelt_render_stats *stats; /* the pass adds its draw calls and triangles */
} pelt__pass_frame;

/* Opaque skin with depth write: the mesh with the innermost fur slice. */
typedef struct pelt__skin_pass {
    GLuint program;
} pelt__skin_pass;

pelt_status pelt__skin_pass_create(pelt__skin_pass *p, const pelt_hooks *hooks, pelt_error *err);
void pelt__skin_pass_draw(const pelt__skin_pass *p, const pelt__pass_frame *f);
void pelt__skin_pass_destroy(pelt__skin_pass *p);

/* All fins in one instanced draw (Lengyel et al. §2.3): one instance per
 * mesh edge, a strip of PELT_FIN_ROWS quads up the displaced strands; the
 * fade collapses fins away from the silhouette in the vertex stage. Owns
 * the fin texture and the per-fin instance buffer. */
typedef struct pelt__fin_pass {
    GLuint program;
    GLuint vao, vbo;    /* per instance: edge (2 uints), start (1 float) */
    GLuint texture;     /* the fin texture, PELT_UNIT_FIN */
    GLint unfaded;      /* uniform location: 1 draws every fin at full opacity */
    size_t count;
} pelt__fin_pass;

pelt_status pelt__fin_pass_create(pelt__fin_pass *p, pelt_fur *fur, const pelt_hooks *hooks,
                                  pelt_error *err);
void pelt__fin_pass_draw(const pelt__fin_pass *p, const pelt__pass_frame *f);
void pelt__fin_pass_destroy(pelt__fin_pass *p);

/* All shells in one instanced draw, blended inner to outer, depth tested
 * without depth write. */
typedef struct pelt__shell_pass {
    GLuint program;
    GLint first_layer; /* uniform location */
    GLint no_inter_shadow; /* uniform location */
} pelt__shell_pass;

pelt_status pelt__shell_pass_create(pelt__shell_pass *p, const pelt_hooks *hooks, pelt_error *err);
void pelt__shell_pass_draw(const pelt__shell_pass *p, const pelt__pass_frame *f);
void pelt__shell_pass_destroy(pelt__shell_pass *p);

#endif
