// Depth cube of a point light: per direction from the light, the distance to
// the nearest caster over `far`. Light space: world axes centred on the light.
//
// PvsCubeMap.params: x far, y texel size per unit distance (2 / resolution),
//                    z light radius (PCSS), w nearest caster distance (PCSS).
// PvsCubeMap.cone:   xyz spot axis, w cosine of the cone (-2 for a point light).

struct PvsCubeMap
{
  vec4 params;
  vec4 cone;
};

PvsReceiver pvsCubeReceiver(PvsCubeMap map, mat4 viewToLight, vec3 bias, vec3 posVC, vec3 normalVC)
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

vec3 pvsCubeTap(PvsReceiver r, vec2 offset, out float planeDistance)
{
  vec3 u, v;
  pvsAcross(normalize(r.q), u, v);
  vec3 direction = normalize(r.q + (offset.x * u + offset.y * v) * r.texel);
  planeDistance = pvsPlaneDistance(r, direction);
  return direction;
}

float pvsCubeCompare(samplerCubeShadow cube, PvsCubeMap map, PvsReceiver r, vec2 offset)
{
  float planeDistance;
  vec3 direction = pvsCubeTap(r, offset, planeDistance);
  return texture(cube, vec4(direction, clamp((planeDistance - r.bias) / map.params.x, 0.0, 1.0)));
}

float pvsCubeBlocker(samplerCube raw, PvsCubeMap map, PvsReceiver r, vec2 offset, out float receiverDepth)
{
  vec3 direction = pvsCubeTap(r, offset, receiverDepth);
  receiverDepth -= r.bias;
  return texture(raw, direction).r * map.params.x;
}

// Blocker-search and penumbra radii in texels for a spherical light of radius R:
// the cone from the point to the light's disk, seen from the light's centre.
float pvsCubeSearchRadius(PvsCubeMap map, PvsReceiver r)
{
  float d = length(r.q);
  float nearest = clamp(map.params.w, 1e-3 * d, d);
  return map.params.z * (d - nearest) / (nearest * r.texel);
}

float pvsCubePenumbraRadius(PvsCubeMap map, PvsReceiver r, float blocker)
{
  return map.params.z * (length(r.q) - blocker) / (max(blocker, 1e-30) * r.texel);
}
