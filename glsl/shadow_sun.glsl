// 2D depth map of a directional light: an orthographic view fitted to the
// casters that can shadow a visible receiver, storing depth along the light
// over the depth range. Light space: x and y across the light (in world
// units, the map's centre at the origin), z along it from the map's near plane.
//
// PvsSunMap.params: x depth range, y texel size, z half width of the map,
//                   w tangent of the sun's angular radius (PCSS).

struct PvsSunMap
{
  vec4 params;
};

PvsReceiver pvsSunReceiver(PvsSunMap map, mat4 viewToLight, vec3 bias, vec3 posVC, vec3 normalVC)
{
  vec3 p = (viewToLight * vec4(posVC, 1.0)).xyz;
  return pvsReceiver(p, normalize(mat3(viewToLight) * normalVC), vec3(0.0, 0.0, -1.0),
                     map.params.y, bias);
}

// The map's texel grid in light space: x and y across the light.
PvsTexelFrame pvsSunFrameOfSize(float size, PvsSunMap map, PvsReceiver r)
{
  PvsTexelFrame f;
  f.size = size;
  float width = 2.0 * map.params.z;
  f.at = (r.q.xy / width + 0.5) * f.size;
  f.origin = vec3(-map.params.zz, 0.0);
  f.du = vec3(width / f.size, 0.0, 0.0);
  f.dv = vec3(0.0, width / f.size, 0.0);
  return f;
}

PvsTexelFrame pvsSunFrame(sampler2DShadow depthMap, PvsSunMap map, PvsReceiver r)
{
  return pvsSunFrameOfSize(float(textureSize(depthMap, 0).x), map, r);
}

// A sun map's texels are r.texel wide: taps are offsets on its grid.
vec2 pvsSunTap(PvsSunMap map, PvsReceiver r, PvsTexelFrame f, vec2 offset)
{
  return f.at + offset;
}

// Depth of the receiver's tangent plane under a texel centre.
float pvsSunPlaneDepth(PvsReceiver r, PvsTexelFrame f, vec2 centre)
{
  vec2 across = (f.origin + f.du * centre.x + f.dv * centre.y).xy - r.q.xy;
  return abs(r.n.z) > 1e-3 ? r.q.z - dot(r.n.xy, across) / r.n.z : r.q.z;
}

float pvsSunTexel(sampler2DShadow depthMap, PvsSunMap map, PvsReceiver r, PvsTexelFrame f, vec2 t)
{
  if (any(lessThan(t, vec2(0.0))) || any(greaterThanEqual(t, vec2(f.size))))
  {
    return 1.0;
  }
  vec2 centre = pvsTexelCentre(t);
  float depth = pvsSunPlaneDepth(r, f, centre) - r.bias;
  return texture(depthMap, vec3(centre / f.size, clamp(depth / map.params.x, 0.0, 1.0)));
}

float pvsSunTexelDepth(sampler2D raw, PvsSunMap map, PvsReceiver r, PvsTexelFrame f, vec2 t,
                       out float receiverDepth)
{
  vec2 centre = pvsTexelCentre(t);
  receiverDepth = pvsSunPlaneDepth(r, f, centre) - r.bias;
  return texture(raw, centre / f.size).r * map.params.x;
}

// What the translucent casters let through at the texel holding t, as pvsSpotTransmitted.
float pvsSunTransmitted(sampler2D transmit, PvsSunMap map, PvsReceiver r, PvsTexelFrame f, vec2 t)
{
  if (any(lessThan(t, vec2(0.0))) || any(greaterThanEqual(t, vec2(f.size))))
  {
    return 1.0;
  }
  vec2 centre = pvsTexelCentre(t);
  vec4 stored = texture(transmit, centre / f.size);
  float depth = pvsSunPlaneDepth(r, f, centre) - r.bias;
  return depth > stored.a * map.params.x ? stored.r : 1.0;
}

float pvsSunSearchRadius(PvsSunMap map, PvsReceiver r)
{
  return map.params.w * max(r.q.z, 0.0) / r.texel;
}

float pvsSunPenumbraRadius(PvsSunMap map, PvsReceiver r, float blocker)
{
  return map.params.w * max(r.q.z - blocker, 0.0) / r.texel;
}
