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
  return pvsPositionalReceiver(viewToLight, map.params, map.cone, bias, posVC, normalVC);
}

float pvsCubeCompare(samplerCubeShadow cube, PvsCubeMap map, PvsReceiver r, vec2 offset)
{
  float planeDistance;
  vec3 direction = pvsTapDirection(r, offset, planeDistance);
  return texture(cube, vec4(direction, clamp((planeDistance - r.bias) / map.params.x, 0.0, 1.0)));
}

float pvsCubeBlocker(samplerCube raw, PvsCubeMap map, PvsReceiver r, vec2 offset, out float receiverDepth)
{
  vec3 direction = pvsTapDirection(r, offset, receiverDepth);
  receiverDepth -= r.bias;
  return texture(raw, direction).r * map.params.x;
}

float pvsCubeSearchRadius(PvsCubeMap map, PvsReceiver r)
{
  return pvsSphereSearchRadius(map.params, r);
}

float pvsCubePenumbraRadius(PvsCubeMap map, PvsReceiver r, float blocker)
{
  return pvsSpherePenumbraRadius(map.params, r, blocker);
}
