// Screen-mask lookups, added to a receiver's fragment shader: shadow volumes
// and planar shadows both leave a mask per light, the size of the viewport,
// 1 where the light reaches the surface seen in the pixel and 0 where it is
// shadowed (a stencil count, or a flattened caster on the receiving plane).
// A receiver reads it at its own pixel and multiplies by a facing test: 0
// where the visible side of the surface faces away from the light. Receivers
// a planar light's mask does not cover (every one but the plane) get the
// facing test alone.
//
//   mask      the light's mask (R8)
//   viewport  x, y: the renderer's origin in the window, in pixels; z, w: its size
//   lightVC   the light in view coordinates: (position, 1) for point and spot
//             lights, (direction towards the light, 0) for directional lights
//   posVC     the fragment's position in view coordinates
//   normalVC  its geometric normal, facing the camera

#ifndef PVS_SHADOW_MASK_GLSL
#define PVS_SHADOW_MASK_GLSL

// Cosine of incidence below which a surface counts as facing away (as in
// pvshadows.verify.reference.MIN_INCIDENCE).
const float PVS_MASK_MIN_INCIDENCE = 1e-4;

// 1 where the visible side of the surface faces the light, else 0.
float pvsFacingLight(vec4 lightVC, vec3 posVC, vec3 normalVC)
{
  vec3 toLight = lightVC.w != 0.0 ? lightVC.xyz - posVC : lightVC.xyz;
  float cosTheta = dot(normalize(normalVC), normalize(toLight));
  return cosTheta > PVS_MASK_MIN_INCIDENCE ? 1.0 : 0.0;
}

float pvsMaskShadow(sampler2D mask, vec4 viewport, vec4 lightVC, vec3 posVC, vec3 normalVC)
{
  if (pvsFacingLight(lightVC, posVC, normalVC) == 0.0)
  {
    return 0.0;
  }
  ivec2 texel = clamp(ivec2(gl_FragCoord.xy - viewport.xy), ivec2(0), ivec2(viewport.zw) - 1);
  return texelFetch(mask, texel, 0).r;
}

#endif
