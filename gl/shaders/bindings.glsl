// The binding table: every number that C and GLSL must agree on, written
// once. The C code #includes this file and the renderer prepends it to
// every shader source, so it holds only #define lines and comments that
// both languages read. Shaders use the names in layout(location = ...);
// samplers and uniform blocks are bound from C (glUniform1i,
// glUniformBlockBinding), since GLSL 3.30 / ES 3.00 have no
// layout(binding = ...).

// Vertex attribute locations (gl/gpu_mesh.c sets the buffers up).
#define PELT_ATTR_POSITION 0 // vec3, mesh-local
#define PELT_ATTR_NORMAL 1   // vec3, unit
#define PELT_ATTR_UV 2       // vec2, surface (atlas) uv: the mask, the colour
#define PELT_ATTR_FUR_UV 3   // vec2, fur-texture coordinates in tiles
#define PELT_ATTR_TANGENT 4  // vec4, unit tangent along +u, w = handedness
#define PELT_ATTR_TIP 5      // vec3, strand tip offset p - p_root (per frame)
#define PELT_ATTR_COMB 6     // vec3, comb direction times its weight
#define PELT_ATTR_GROOM 7    // vec4, groomed lean (u, v), length scale, density
#define PELT_ATTR_HAIR_COLOR 8 // vec4 from 4 normalised bytes: hair colour, its weight
#define PELT_ATTR_BONES 9    // uvec4: a skinned vertex's 4 bones (skinning in the vertex stage)
#define PELT_ATTR_WEIGHTS 10 // vec4: their weights
#define PELT_ATTR_FIT_NORMAL 11 // vec3: the drawn level's fitted normal less the vertex's, in its frame (core/fur/lod_normals.c)

// Texture units (gl/gpu_fur.c owns the textures).
#define PELT_UNIT_FUR 0   // sampler2DArray: the fur volume, one slice a layer
#define PELT_UNIT_COLOR 1 // sampler2D: the colour texture
#define PELT_UNIT_MASK 2  // sampler2D: the wetness mask, nearest
#define PELT_UNIT_FIN 3   // sampler2D: the fin texture (gl/fin_pass.c)
#define PELT_UNIT_LIGHT_TABLE 4 // sampler2D RG32F: Lengyel's hair lighting table
#define PELT_UNIT_FIN_EDGES 5 // usampler2D RGBA32UI: this frame's fins (their ends, start and fade bits)
#define PELT_UNIT_FIN_VERTICES 6 // sampler2D RGBA32F: this frame's fin vertices (core/fur/fur_gpu.h)
#define PELT_UNIT_SHADOW_DEPTH 7 // sampler2D DEPTH_COMPONENT24: the skin's depth from the light (gl/shadow_pass.c)
#define PELT_UNIT_SHADOW_OPACITY 8 // sampler2DArray RGBA16F: the fur's opacity slices, 4 a layer
#define PELT_UNIT_BONES 9 // sampler2D RGBA32F: the bones' matrices, 3 rows a bone (skinning in the vertex stage)
#define PELT_UNIT_STRANDS PELT_UNIT_FIN_VERTICES // samplerBuffer RGBA32F: the strand reference's hairs (gl/strands_pass.c); a strands frame draws no fins
#define PELT_UNIT_COUNT 10 // units 0 .. PELT_UNIT_COUNT - 1 are the renderer's

// Tables: data a pass fetches by index (the fins and their vertices), row
// after row PELT_TABLE_WIDTH texels wide.
#define PELT_TABLE_WIDTH 1020

// A fin is a strip of PELT_FIN_ROWS quads up the strand, 2 (PELT_FIN_ROWS + 1)
// vertices; an instance draws PELT_FIN_CHUNK fins (gl/fin_pass.c).
#define PELT_FIN_ROWS 3
#define PELT_FIN_CHUNK 64
#define PELT_FIN_HEIGHTS 4        // strand points a fin vertex has: core's PELT__FIN_HEIGHTS
#define PELT_FIN_VERTEX_TEXELS 10 // texels a fin vertex has: core's PELT__FIN_VERTEX_TEXELS

// Uniform block binding points (gl/uniform_blocks.c, gl/shaders/blocks.glsl).
#define PELT_BLOCK_FRAME 0 // pelt_frame_block: matrices, eye, light
#define PELT_BLOCK_FUR 1   // pelt_fur_block: how the fur looks
#define PELT_BLOCK_COUNT 2 // points 0 .. PELT_BLOCK_COUNT - 1 are the renderer's
