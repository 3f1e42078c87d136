// Fin fragments: the fin texture (the same hair seen from the side), faded
// in near the silhouette, lit like the shells (fur_light.glsl): ringlets
// along their curl (own_light.glsl); wet fins darken like the shells and
// show the tufts the shells draw, from the side (docs/wetness.md).
in vec2 v_uv;
in vec2 v_fin_uv;
in float v_density;
in float v_fade;
in vec3 v_root; // lit
in vec3 v_tip;
in float v_spec;
#ifdef PELT_RINGLETS
in vec2 v_light;  // the ringlet's own light (fin_vs.glsl)
in vec3 v_ring_l;
in vec3 v_ring_e;
in vec3 v_ring_g;
#endif
#ifdef PELT_WET
flat in vec2 v_clump_dir; // mask uv per fin-texture u (fin_vs.glsl)
#endif

uniform highp sampler2DArray u_fin_tex; // PELT_UNIT_FIN: a layer a ringlet level
uniform sampler2D u_color_tex; // PELT_UNIT_COLOR
uniform sampler2D u_mask;      // PELT_UNIT_MASK

out vec4 o_color;

// The fin texture's mip level for this fragment: set first in main.
float fin_lod = 0.0;

// The fin's hair at uv under wetness rho: with ringlets, water takes the
// curl out between the levels the fin texture holds, as on the shells
// (shell_fs.glsl's wet_hair). Dry fins read the full-curl level alone.
vec4 fin_hair(vec2 uv, float rho)
{
#if defined(PELT_RINGLETS) && defined(PELT_WET)
    vec3 level = ringlet_levels(rho, u_ringlets.x, 1.0);
    return mix(textureLod(u_fin_tex, vec3(uv, level.x), fin_lod), textureLod(u_fin_tex, vec3(uv, level.y), fin_lod),
               level.z);
#else
    return textureLod(u_fin_tex, vec3(uv, 0.0), fin_lod);
#endif
}

void main()
{
    // A fin stands across the outline: its hair is seen along the fin and
    // foreshortened up it, so a texture read's level (from the long side)
    // blurred the tips into a soft band. Read it at the short side's level,
    // up to FIN_TEXTURE_ANISO texels of the long side to a pixel (as the
    // shells read theirs, shell_lod.glsl; docs/shading.md), where the short
    // side is a texel or less: seen from further, the fin's hair is finer
    // than a pixel both ways and a sharper read only aliases it.
    vec2 fin_texels = vec2(textureSize(u_fin_tex, 0).xy);
    vec2 fin_dx = dFdx(v_fin_uv) * fin_texels, fin_dy = dFdy(v_fin_uv) * fin_texels;
    fin_lod = fur_texture_lod(fin_dx, fin_dy, 1.0, fin_texture_aniso(fin_dx, fin_dy));
    vec2 fin_uv = v_fin_uv;
    float rho = 0.0;
#ifdef PELT_WET
    // Tufts on the outline (Silva Eq. 5, Alg. 2 as on the shells): the fin
    // shows the hair that the tuft at this point of its edge pulls in from
    // q, moved along the fin by the pull's share along the edge; between
    // the tufts, above their base, the gaps open.
    vec2 q;
    vec4 t = clump_texel(u_mask, v_uv);
    rho = t.a;
    float profile = clump_tuft_profile(v_fin_uv.y * u_fin_length, u_clump_blend, u_layers);
    int clump = clump_lookup_texel(u_mask, t, v_uv, profile, u_clump_tightness, clump_lean(t, u_clump_lean), q);
    if (clump == CLUMP_DISPLACED) fin_uv.x += clump_fin_shift(q - v_uv, v_clump_dir);
#endif
    vec4 hair = fin_hair(fin_uv, rho);
#ifdef PELT_WET
    if (clump != CLUMP_KEEP) {
        // Strays stay out of the tufts and stand where they grew. Between
        // the tufts the read above was already the hair growing here.
        vec4 own = clump == CLUMP_DISPLACED ? fin_hair(v_fin_uv, rho) : hair;
        if (clump_stray_hair(clump, hair, own, u_wet_strays)) clump = CLUMP_KEEP;
        if (!(hair.a > 0.0)) discard;
    }
#endif
    hair.rgb /= max(hair.a, 1e-3); // premultiplied
    if (!groom_keeps(hair.b, v_density)) discard;
#ifdef PELT_WET
    // The tuft's hair squeezed together is denser, as on the shells.
    if (clump == CLUMP_DISPLACED)
        hair.a = clump_coverage(hair.a, 1.0 - min(u_clump_tightness * rho * profile, CLUMP_MAX_PULL));
#endif
    if (hair.a < 0.05) discard;
    float a = hair.a * v_fade;
    vec3 base = mix(v_root, v_tip, hair.g) * shade_decode(hair.r); // linear light
    // Variants as the shells' (gl/fin_pass.c): only what the frame needs.
#ifdef PELT_COLOR_TEXTURE
    base *= texture(u_color_tex, v_uv * u_color_scale).rgb;
#endif
    float spec = v_spec;
#ifdef PELT_WET
    base = wet_color(base, rho, u_wet_darken);
#endif
#ifdef PELT_RINGLETS
    // The hair the fin shows curls: lit along its ringlet, as the shells'
    // (own_light.glsl); the fin texture's id gives its phase.
    ringlet_light(hair.b, rho, v_fin_uv.y, v_light, v_ring_l, v_ring_e, v_ring_g, base, spec);
#endif
    o_color = vec4(display_color(base + spec * (u_specular * u_light_color), u_exposure, u_tone), a);
}
