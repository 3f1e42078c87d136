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

// Texture units (gl/gpu_fur.c owns the textures).
#define PELT_UNIT_FUR 0   // sampler2DArray: the fur volume, one slice a layer
#define PELT_UNIT_COLOR 1 // sampler2D: the colour texture
#define PELT_UNIT_MASK 2  // sampler2D: the wetness mask, nearest
#define PELT_UNIT_FIN 3   // sampler2D: the fin texture (gl/fin_pass.c)
#define PELT_UNIT_VERTICES 4 // sampler2D RGBA32F: the vertex table, PELT_TABLE_TEXELS per vertex
#define PELT_UNIT_TIPS 5  // sampler2D RGBA32F: strand tips, one texel per vertex
#define PELT_UNIT_GROOM 6 // usampler2D R32UI: the groom, PELT_GROOM_WORDS per vertex
#define PELT_UNIT_LIGHT_TABLE 7 // sampler2D RG32F: Lengyel's hair lighting table
#define PELT_UNIT_FIN_EDGES 8 // usampler2D RGBA32UI: this frame's fins (a, b, start bits, 0), a table
#define PELT_UNIT_COUNT 9 // units 0 .. PELT_UNIT_COUNT - 1 are the renderer's

// Vertex tables: per-vertex data a pass fetches by vertex index (the fins
// read both ends of an edge), row after row PELT_TABLE_WIDTH texels wide.
#define PELT_TABLE_WIDTH 1020
#define PELT_TABLE_TEXELS 5 // position + tangent w, normal, tangent, uv + fur uv, comb
#define PELT_GROOM_WORDS 5  // core/fur/groom.h: lean u, lean v, length, density, colour bytes

// A fin is a strip of PELT_FIN_ROWS quads up the strand, 2 (PELT_FIN_ROWS + 1)
// vertices; an instance draws PELT_FIN_CHUNK fins (gl/fin_pass.c).
#define PELT_FIN_ROWS 3
#define PELT_FIN_CHUNK 64

// Uniform block binding points (gl/uniform_blocks.c, gl/shaders/blocks.glsl).
#define PELT_BLOCK_FRAME 0 // pelt_frame_block: matrices, eye, light
#define PELT_BLOCK_FUR 1   // pelt_fur_block: how the fur looks
#define PELT_BLOCK_COUNT 2 // points 0 .. PELT_BLOCK_COUNT - 1 are the renderer's
