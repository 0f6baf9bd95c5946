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
  vec3 p = (viewToLight * vec4(posVC, 1.0)).xyz;
  float dist = max(length(p), 1e-30);
  PvsReceiver r = pvsReceiver(p, normalize(mat3(viewToLight) * normalVC), -p / dist,
                              dist * map.params.y, bias);
  if (dot(p / dist, map.cone.xyz) < map.cone.w)
  {
    r.lit = 0.0;
  }
  return r;
}

vec3 pvsSpotTap(PvsSpotMap map, PvsReceiver r, vec2 offset, out float planeDistance)
{
  vec3 u, v;
  pvsAcross(normalize(r.q), u, v);
  vec3 direction = normalize(r.q + (offset.x * u + offset.y * v) * r.texel);
  planeDistance = pvsPlaneDistance(r, direction);
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
  float d = length(r.q);
  float nearest = clamp(map.params.w, 1e-3 * d, d);
  return map.params.z * (d - nearest) / (nearest * r.texel);
}

float pvsSpotPenumbraRadius(PvsSpotMap map, PvsReceiver r, float blocker)
{
  return map.params.z * (length(r.q) - blocker) / (max(blocker, 1e-30) * r.texel);
}
