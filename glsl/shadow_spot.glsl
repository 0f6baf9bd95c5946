// 2D depth map of a spot light: a perspective view along the spot's axis
// covering its cone, storing the distance to the light over `far`. Light
// space: world axes centred on the light; `lightToClip` projects it.
//
// PvsSpotMap.params: x far, y texel size per unit distance at the centre,
//                    z light radius (PCSS), w nearest caster distance (PCSS).
// PvsSpotMap.cone:   xyz spot axis, w cosine of the cone.

struct PvsSpotMap
{
  mat4 lightToClip;
  vec4 params;
  vec4 cone;
};

PvsReceiver pvsSpotReceiver(PvsSpotMap map, mat4 viewToLight, vec3 bias, vec3 posVC, vec3 normalVC)
{
  return pvsPositionalReceiver(viewToLight, map.params, map.cone, bias, posVC, normalVC);
}

vec3 pvsSpotTap(PvsSpotMap map, PvsReceiver r, vec2 offset, out float planeDistance)
{
  vec3 direction = pvsTapDirection(r, offset, planeDistance);
  vec4 clip = map.lightToClip * vec4(direction, 1.0);
  return vec3(clip.xy / clip.w * 0.5 + 0.5, clip.w);
}

float pvsSpotCompare(sampler2DShadow depthMap, PvsSpotMap map, PvsReceiver r, vec2 offset)
{
  float planeDistance;
  vec3 uv = pvsSpotTap(map, r, offset, planeDistance);
  if (uv.z <= 0.0)
  {
    return 1.0;
  }
  return texture(depthMap, vec3(uv.xy, clamp((planeDistance - r.bias) / map.params.x, 0.0, 1.0)));
}

float pvsSpotBlocker(sampler2D raw, PvsSpotMap map, PvsReceiver r, vec2 offset, out float receiverDepth)
{
  vec3 uv = pvsSpotTap(map, r, offset, receiverDepth);
  receiverDepth -= r.bias;
  return uv.z <= 0.0 ? map.params.x : texture(raw, uv.xy).r * map.params.x;
}

float pvsSpotSearchRadius(PvsSpotMap map, PvsReceiver r)
{
  return pvsSphereSearchRadius(map.params, r);
}

float pvsSpotPenumbraRadius(PvsSpotMap map, PvsReceiver r, float blocker)
{
  return pvsSpherePenumbraRadius(map.params, r, blocker);
}
