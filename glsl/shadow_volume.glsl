// Shadow-volume lookup, added to a receiver's fragment shader. The stencil
// pass left a mask per light, the size of the viewport: 1 where the light
// reaches the surface seen in the pixel, 0 where a shadow volume holds it.
// The receiver reads it at its own pixel, and multiplies by a facing test:
// 0 where the visible side of the surface faces away from the light.
//
//   mask      the light's mask (R8)
//   viewport  x, y: the renderer's origin in the window, in pixels; z, w: its size
//   lightVC   the light in view coordinates: (position, 1) for point and spot
//             lights, (direction towards the light, 0) for directional lights
//   posVC     the fragment's position in view coordinates
//   normalVC  its geometric normal, facing the camera

#ifndef PVS_SHADOW_VOLUME_GLSL
#define PVS_SHADOW_VOLUME_GLSL

// Cosine of incidence below which a surface counts as facing away (as in
// pvshadows.reference.MIN_INCIDENCE).
const float PVS_VOLUME_MIN_INCIDENCE = 1e-4;

float pvsVolumeShadow(sampler2D mask, vec4 viewport, vec4 lightVC, vec3 posVC, vec3 normalVC)
{
  vec3 toLight = lightVC.w != 0.0 ? lightVC.xyz - posVC : lightVC.xyz;
  float cosTheta = dot(normalize(normalVC), normalize(toLight));
  if (!(cosTheta > PVS_VOLUME_MIN_INCIDENCE))
  {
    return 0.0;
  }
  ivec2 texel = clamp(ivec2(gl_FragCoord.xy - viewport.xy), ivec2(0), ivec2(viewport.zw) - 1);
  return texelFetch(mask, texel, 0).r;
}

#endif
