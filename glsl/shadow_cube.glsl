// Point-light shadow lookups in a depth cube, added to a receiver's fragment
// shader. Each returns how much of the light reaches the surface point:
// 1 lit, 0 in shadow, and 0 where the visible side of the surface faces away
// from the light. Only the filters a receiver's lights use are compiled in
// (PVS_CUBE_HARD, PVS_CUBE_PCF).
//
// Arguments shared by every lookup:
//   cube        distance to the nearest caster over `far`, per direction
//   viewToLight view coordinates -> world axes centred on the light
//   params      x: far, y: texel size per unit distance (2 / resolution),
//               z: normal offset, w: constant bias (both in texels)
//   slopeBias   depth bias per unit of tan(angle of incidence), in texels
//   posVC       the fragment's position in view coordinates
//   normalVC    its geometric normal, facing the camera

// Cosine of incidence below which a surface counts as facing away (as in
// pvshadows.reference.MIN_INCIDENCE): a light in a surface's plane does not light it.
const float PVS_MIN_INCIDENCE = 1e-4;

struct PvsCubePoint
{
  vec3 q;        // lookup position, offset along the normal, relative to the light
  vec3 n;        // normal facing the light side
  float texel;   // world size of one texel at this distance
  float bias;    // depth bias in world units
  float lit;     // 0 when the visible side faces away from the light
};

PvsCubePoint pvsCubePoint(mat4 viewToLight, vec4 params, float slopeBias, vec3 posVC, vec3 normalVC)
{
  PvsCubePoint point;
  vec3 p = (viewToLight * vec4(posVC, 1.0)).xyz;
  vec3 n = normalize(mat3(viewToLight) * normalVC);
  float dist = max(length(p), 1e-30);
  float cosTheta = dot(n, -p / dist);
  point.lit = cosTheta > PVS_MIN_INCIDENCE ? 1.0 : 0.0;
  cosTheta = max(cosTheta, 1e-4);
  float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
  point.texel = dist * params.y;
  point.n = n;
  point.q = p + n * (point.texel * params.z * sinTheta);
  point.bias = point.texel * (params.w + slopeBias * min(sinTheta / cosTheta, 10.0));
  return point;
}

float pvsCubeCompare(samplerCubeShadow cube, vec3 direction, float distance, float far)
{
  return texture(cube, vec4(direction, clamp(distance / far, 0.0, 1.0)));
}

#ifdef PVS_CUBE_HARD
float pvsPointShadowHard(samplerCubeShadow cube, mat4 viewToLight, vec4 params, float slopeBias,
                         vec3 posVC, vec3 normalVC)
{
  PvsCubePoint point = pvsCubePoint(viewToLight, params, slopeBias, posVC, normalVC);
  if (point.lit == 0.0)
  {
    return 0.0;
  }
  return pvsCubeCompare(cube, point.q, length(point.q) - point.bias, params.x);
}
#endif

#ifdef PVS_CUBE_PCF
// Percentage-closer filtering: `side` x `side` taps one texel apart, in the
// plane across the light direction, each a hardware 2x2 compare. Each tap is
// compared with the depth of the receiver's own plane along the tap's
// direction, so the taps do not shadow a flat receiver at any angle.
float pvsPointShadowPcf(samplerCubeShadow cube, mat4 viewToLight, vec4 params, float slopeBias,
                        vec3 posVC, vec3 normalVC, int side)
{
  PvsCubePoint point = pvsCubePoint(viewToLight, params, slopeBias, posVC, normalVC);
  if (point.lit == 0.0)
  {
    return 0.0;
  }
  float dist = length(point.q);
  vec3 axis = point.q / dist;
  vec3 u = normalize(cross(axis, abs(axis.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0)));
  vec3 v = cross(axis, u);
  float plane = dot(point.q, point.n);
  float sum = 0.0;
  for (int i = 0; i < side; ++i)
  {
    for (int j = 0; j < side; ++j)
    {
      vec2 offset = (vec2(float(i), float(j)) - 0.5 * float(side - 1)) * point.texel;
      vec3 direction = normalize(point.q + offset.x * u + offset.y * v);
      float along = dot(direction, point.n);
      float depth = along < -1e-3 ? clamp(plane / along, 0.5 * dist, 2.0 * dist) : dist;
      sum += pvsCubeCompare(cube, direction, depth - point.bias, params.x);
    }
  }
  return sum / float(side * side);
}
#endif
