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

// The map's texel grid: the rows x, y and w of lightToClip (a projection
// from the light's position) give the direction through map position (X, Y)
// as cross(x - X w, y - Y w), which is linear in X and Y.
PvsTexelFrame pvsSpotFrameOfSize(float size, PvsSpotMap map, PvsReceiver r)
{
  PvsTexelFrame f;
  f.size = size;
  mat4 m = map.lightToClip;
  vec3 x = vec3(m[0][0], m[1][0], m[2][0]);
  vec3 y = vec3(m[0][1], m[1][1], m[2][1]);
  vec3 w = vec3(m[0][3], m[1][3], m[2][3]);
  vec3 xy = cross(x, y);
  vec3 yw = cross(y, w);
  vec3 wx = cross(w, x);
  float front = dot(xy, w) < 0.0 ? -1.0 : 1.0;
  f.origin = front * (xy - yw - wx);
  f.du = front * yw * (2.0 / f.size);
  f.dv = front * wx * (2.0 / f.size);
  float along = dot(w, r.q);
  f.at = along > 0.0 ? (vec2(dot(x, r.q), dot(y, r.q)) / along * 0.5 + 0.5) * f.size : vec2(-1.0);
  return f;
}

PvsTexelFrame pvsSpotFrame(sampler2DShadow depthMap, PvsSpotMap map, PvsReceiver r)
{
  return pvsSpotFrameOfSize(float(textureSize(depthMap, 0).x), map, r);
}

vec2 pvsSpotTap(PvsSpotMap map, PvsReceiver r, PvsTexelFrame f, vec2 offset)
{
  vec4 clip = map.lightToClip * vec4(pvsTapDirection(r, offset), 1.0);
  return clip.w > 0.0 ? (clip.xy / clip.w * 0.5 + 0.5) * f.size : vec2(-1.0);
}

bool pvsSpotOutside(PvsTexelFrame f, vec2 t)
{
  return any(lessThan(t, vec2(0.0))) || any(greaterThanEqual(t, vec2(f.size)));
}

vec3 pvsSpotTexelDirection(PvsTexelFrame f, vec2 centre)
{
  return normalize(f.origin + f.du * centre.x + f.dv * centre.y);
}

float pvsSpotTexel(sampler2DShadow depthMap, PvsSpotMap map, PvsReceiver r, PvsTexelFrame f, vec2 t)
{
  if (pvsSpotOutside(f, t))
  {
    return 1.0;
  }
  vec2 centre = pvsTexelCentre(t);
  float depth = pvsPlaneDistance(r, pvsSpotTexelDirection(f, centre)) - r.bias;
  return texture(depthMap, vec3(centre / f.size, clamp(depth / map.params.x, 0.0, 1.0)));
}

float pvsSpotTexelDepth(sampler2D raw, PvsSpotMap map, PvsReceiver r, PvsTexelFrame f, vec2 t,
                        out float receiverDepth)
{
  vec2 centre = pvsTexelCentre(t);
  receiverDepth = pvsPlaneDistance(r, pvsSpotTexelDirection(f, centre)) - r.bias;
  return pvsSpotOutside(f, t) ? map.params.x : texture(raw, centre / f.size).r * map.params.x;
}

// What the translucent casters let through at the texel holding t (transmittance.frag
// stored the product of their 1 - opacity and, in alpha, the nearest one's depth):
// the product where the receiver lies beyond the nearest, 1 in front of it.
float pvsSpotTransmitted(sampler2D transmit, PvsSpotMap map, PvsReceiver r, PvsTexelFrame f, vec2 t)
{
  if (pvsSpotOutside(f, t))
  {
    return 1.0;
  }
  vec2 centre = pvsTexelCentre(t);
  vec4 stored = texture(transmit, centre / f.size);
  float depth = pvsPlaneDistance(r, pvsSpotTexelDirection(f, centre)) - r.bias;
  return depth > stored.a * map.params.x ? stored.r : 1.0;
}

float pvsSpotSearchRadius(PvsSpotMap map, PvsReceiver r)
{
  return pvsSphereSearchRadius(map.params, r);
}

float pvsSpotPenumbraRadius(PvsSpotMap map, PvsReceiver r, float blocker)
{
  return pvsSpherePenumbraRadius(map.params, r, blocker);
}
