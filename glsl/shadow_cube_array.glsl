// Depth cubes of several point lights in one cube map array, one layer per
// light: the lookups of all of them run in one loop over one sampler, so the
// receiver's shader holds each filter once, whatever the number of lights.
// The face and texel geometry is the single cube's (shadow_cube.glsl, before
// this file).
//
// PvsCubesMap.params, .cone: as PvsCubeMap's; .layer: the light's cube in the array.

struct PvsCubesMap
{
  vec4 params;
  vec4 cone;
  float layer;
};

PvsReceiver pvsCubesReceiver(PvsCubesMap map, mat4 viewToLight, vec3 bias, vec3 posVC, vec3 normalVC)
{
  return pvsPositionalReceiver(viewToLight, map.params, map.cone, bias, posVC, normalVC);
}

PvsTexelFrame pvsCubesFrame(samplerCubeArrayShadow cubes, PvsCubesMap map, PvsReceiver r)
{
  PvsTexelFrame f;
  f.size = float(textureSize(cubes, 0).x);
  vec3 major, s, t;
  pvsCubeFace(r.q, major, s, t);
  vec3 onFace = r.q / dot(r.q, major);
  f.at = (vec2(dot(onFace, s), dot(onFace, t)) + 1.0) * (0.5 * f.size);
  f.origin = major - s - t;
  f.du = s * (2.0 / f.size);
  f.dv = t * (2.0 / f.size);
  return f;
}

vec2 pvsCubesTap(PvsCubesMap map, PvsReceiver r, PvsTexelFrame f, vec2 offset)
{
  return pvsCubeTap(PvsCubeMap(map.params, map.cone), r, f, offset);
}

float pvsCubesTexel(samplerCubeArrayShadow cubes, PvsCubesMap map, PvsReceiver r, PvsTexelFrame f,
                    vec2 t)
{
  vec3 direction = pvsCubeTexelDirection(f, t);
  float depth = pvsPlaneDistance(r, direction) - r.bias;
  return texture(cubes, vec4(direction, map.layer), clamp(depth / map.params.x, 0.0, 1.0));
}

float pvsCubesTexelDepth(samplerCubeArray raw, PvsCubesMap map, PvsReceiver r, PvsTexelFrame f,
                         vec2 t, out float receiverDepth)
{
  vec3 direction = pvsCubeTexelDirection(f, t);
  receiverDepth = pvsPlaneDistance(r, direction) - r.bias;
  return texture(raw, vec4(direction, map.layer)).r * map.params.x;
}

float pvsCubesSearchRadius(PvsCubesMap map, PvsReceiver r)
{
  return pvsSphereSearchRadius(map.params, r);
}

float pvsCubesPenumbraRadius(PvsCubesMap map, PvsReceiver r, float blocker)
{
  return pvsSpherePenumbraRadius(map.params, r, blocker);
}
