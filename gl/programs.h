/* Building GL programs from the embedded .glsl sources. */
#ifndef PELT_GL_PROGRAMS_H
#define PELT_GL_PROGRAMS_H

#include "pelt/base.h"

#include "gl/gl_api.h"

/* Embedded sources, generated from gl/shaders/NAME.glsl. */
extern const char pelt__shader_bindings[];
extern const char pelt__shader_blocks[];
extern const char pelt__shader_shading[];
extern const char pelt__shader_fur_shape[];
extern const char pelt__shader_clump[];
extern const char pelt__shader_skin_vs[];
extern const char pelt__shader_skin_fs[];
extern const char pelt__shader_shell_vs[];
extern const char pelt__shader_shell_fs[];
extern const char pelt__shader_shell_floor_fs[];
extern const char pelt__shader_shell_plain_vs[];
extern const char pelt__shader_shell_plain_fs[];
extern const char pelt__shader_shell_lod[];
extern const char pelt__shader_fur_light[];
extern const char pelt__shader_own_light[];
extern const char pelt__shader_fin_vs[];
extern const char pelt__shader_fin_fs[];
extern const char pelt__shader_outline_hair[];
extern const char pelt__shader_fin_table[];
extern const char pelt__shader_outline_vs[];
extern const char pelt__shader_outline_fs[];
extern const char pelt__shader_shadow_map[];
extern const char pelt__shader_shadow_depth_vs[];
extern const char pelt__shader_shadow_depth_fs[];
extern const char pelt__shader_ground_vs[];
extern const char pelt__shader_ground_fs[];
extern const char pelt__shader_skin_blend[];
extern const char pelt__shader_strand_vs[];
extern const char pelt__shader_strand_fs[];

/* Compiles and links a program. Each stage is a NULL-terminated list of
 * at most 12 source pieces, concatenated after the version header (GLSL
 * 3.30 core, written so the same pieces compile as GLSL ES 3.00) and the
 * binding table (shaders/bindings.glsl). On failure the error holds the GL
 * info log and `what` names the program. */
pelt_status pelt__program_build(const char *what, const char *const *vertex_parts,
                                const char *const *fragment_parts, GLuint *out,
                                pelt_error *err);

#endif
