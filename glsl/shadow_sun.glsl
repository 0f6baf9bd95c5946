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

// Where a tap lands on the map (uv) and the receiver plane's depth there.
vec2 pvsSunTap(PvsSunMap map, PvsReceiver r, vec2 offset, out float planeDepth)
{
  vec2 across = offset * r.texel;
  planeDepth = r.q.z;
  if (abs(r.n.z) > 1e-3)
  {
    planeDepth -= dot(r.n.xy, across) / r.n.z;
  }
  return (r.q.xy + across) / (2.0 * map.params.z) + 0.5;
}

float pvsSunCompare(sampler2DShadow depthMap, PvsSunMap map, PvsReceiver r, vec2 offset)
{
  float planeDepth;
  vec2 uv = pvsSunTap(map, r, offset, planeDepth);
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))))
  {
    return 1.0;
  }
  return texture(depthMap, vec3(uv, clamp((planeDepth - r.bias) / map.params.x, 0.0, 1.0)));
}

float pvsSunBlocker(sampler2D raw, PvsSunMap map, PvsReceiver r, vec2 offset, out float receiverDepth)
{
  vec2 uv = pvsSunTap(map, r, offset, receiverDepth);
  receiverDepth -= r.bias;
  return texture(raw, uv).r * map.params.x;
}

float pvsSunSearchRadius(PvsSunMap map, PvsReceiver r)
{
  return map.params.w * max(r.q.z, 0.0) / r.texel;
}

float pvsSunPenumbraRadius(PvsSunMap map, PvsReceiver r, float blocker)
{
  return map.params.w * max(r.q.z - blocker, 0.0) / r.texel;
}
