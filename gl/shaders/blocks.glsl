// The uniform blocks every renderer program shares, std140 so that the C
// structs in gl/gpu.h match them byte for byte (checked there and by
// tests/gl/test_render.c). Members keep their u_ names: a block without an
// instance name puts them in the global scope. Bound to PELT_BLOCK_* from C.

// Per frame: the camera, the mesh placement and the light.
layout(std140) uniform pelt_frame_block {
    mat4 u_model;
    mat4 u_view_proj;
    vec3 u_eye;
    float u_ambient;     // ambient fraction of the hair colour
    vec3 u_light_dir;    // towards the light, not unit
    float u_exposure;    // multiplies the linear colour before the tone curve
    vec3 u_light_color;
    float u_tone;        // the tone curve: 0 filmic, 1 none (clamp only)
    vec3 u_view_dir;     // the camera's forward direction (the infinite viewer)
    // Shadows from the light (shadow_map.glsl, docs/shadows.md).
    mat4 u_light_matrix; // world -> (s, t, depth) on the light's maps
    vec4 u_shadow_map;   // x: on (1) or off (0), y: slices S, z: 1 / map size, w: filter radius, texels
    vec4 u_shadow_slab;  // x: the slab's depth, y: opacity density, z: the fur's bias, w: keep gamma (1)
};

// Per fur, uploaded when it changes: the look (Silva et al. Eq. 4-6).
layout(std140) uniform pelt_fur_block {
    vec3 u_color;            // colours in linear light (decoded from sRGB)
    float u_layers;          // N
    vec3 u_tip_color;
    float u_length;          // L0
    vec3 u_specular;         // Kajiya-Kay K_s
    float u_shininess;       // Kajiya-Kay p
    vec2 u_fur_per_uv;       // fur tiles per uv unit
    float u_shadow;          // K_shadow
    float u_curl_frequency;  // omega
    float u_curl_radius;     // K_alpha
    float u_clump_blend;     // w of Eq. 5
    float u_clump_tightness; // s
    float u_wet_darken;
    float u_color_scale;     // colour texture repeats per uv unit
    float u_slant;           // tan of the comb angle (Lengyel et al. §3)
    float u_wet_gloss;       // wet shine: specular gain of fully wet fur
    float u_wet_sharpness;   // wet shine: exponent multiple of fully wet fur
    vec3 u_skin_color;       // bare skin where grooming thins the hair
    float u_tiling;          // fur tiles per world unit (the fins' texture scale)
    float u_fin_length;      // fin hair height, multiple of the strand length
    float u_inter_shadow;    // Kenwright's shadow opacity, 0 = off
    float u_inter_shadow_step; // its step towards the light, fur tiles
    float u_shading_model;   // 0 Kajiya-Kay, 1 Lengyel's table, 2 Scheuermann-Marschner
    vec2 u_ringlets;         // ringlets: x: the curl's amplitude levels in the
                             // fur volume (1 = none), y: slices between levels
    float u_occlusion;       // the fur's optical depth (fur_occlusion)
    float u_wet_strays;      // the share of hairs that stays out of the tufts
    float u_ringlet_radius;  // the ringlets' radius at the tip, world units (0: none)
    float u_strand_curl_radius; // the fur texture's own curl: its radius over the
    float u_strand_curl_omega;  // fur's length (0: none), 2 pi turns, and
    float u_strand_curl_wave;   // 1 for a wave along u, 0 for a helix
    float u_clump_lean;         // a tuft's lean at its tip, share of its radius (clump_lean)
    float u_hair_width;         // the hair's width at the root, world units (shell_overcount)
    float u_taper;              // its taper towards the tip
    float u_wet_lie;            // wet fur lies down: radians added to the comb at full wetness (wet_slant)
};
