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

// The cube face a direction falls on: its major axis (signed) and the two
// axes across it.
void pvsCubeFace(vec3 d, out vec3 major, out vec3 s, out vec3 t)
{
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z)
  {
    major = vec3(sign(d.x), 0.0, 0.0);
    s = vec3(0.0, 1.0, 0.0);
    t = vec3(0.0, 0.0, 1.0);
  }
  else if (a.y >= a.z)
  {
    major = vec3(0.0, sign(d.y), 0.0);
    s = vec3(1.0, 0.0, 0.0);
    t = vec3(0.0, 0.0, 1.0);
  }
  else
  {
    major = vec3(0.0, 0.0, sign(d.z));
    s = vec3(1.0, 0.0, 0.0);
    t = vec3(0.0, 1.0, 0.0);
  }
}

// The texel grid of the receiver's face, on the plane one unit along its major axis.
PvsTexelFrame pvsCubeFrameOfSize(float size, PvsCubeMap map, PvsReceiver r)
{
  PvsTexelFrame f;
  f.size = size;
  vec3 major, s, t;
  pvsCubeFace(r.q, major, s, t);
  vec3 onFace = r.q / dot(r.q, major);
  f.at = (vec2(dot(onFace, s), dot(onFace, t)) + 1.0) * (0.5 * f.size);
  f.origin = major - s - t;
  f.du = s * (2.0 / f.size);
  f.dv = t * (2.0 / f.size);
  return f;
}

PvsTexelFrame pvsCubeFrame(samplerCubeShadow cube, PvsCubeMap map, PvsReceiver r)
{
  return pvsCubeFrameOfSize(float(textureSize(cube, 0).x), map, r);
}

vec2 pvsCubeTap(PvsCubeMap map, PvsReceiver r, PvsTexelFrame f, vec2 offset)
{
  vec3 direction = pvsTapDirection(r, offset);
  vec3 major = f.origin + (f.du + f.dv) * (0.5 * f.size);
  vec3 onFace = direction / max(dot(direction, major), 1e-6) - f.origin;
  return vec2(dot(onFace, f.du), dot(onFace, f.dv)) / dot(f.du, f.du);
}

// Direction through the centre of the texel holding t, on whichever face
// the direction to t falls (taps may cross an edge of the receiver's face).
vec3 pvsCubeTexelDirection(PvsTexelFrame f, vec2 t)
{
  vec3 major, s, u;
  vec3 d = f.origin + f.du * t.x + f.dv * t.y;
  pvsCubeFace(d, major, s, u);
  vec2 onFace = vec2(dot(d, s), dot(d, u)) / dot(d, major);
  vec2 texel = min(floor((onFace + 1.0) * (0.5 * f.size)), f.size - 1.0) + 0.5;
  onFace = texel * (2.0 / f.size) - 1.0;
  return normalize(major + s * onFace.x + u * onFace.y);
}

float pvsCubeTexel(samplerCubeShadow cube, PvsCubeMap map, PvsReceiver r, PvsTexelFrame f, vec2 t)
{
  vec3 direction = pvsCubeTexelDirection(f, t);
  float depth = pvsPlaneDistance(r, direction) - r.bias;
  return texture(cube, vec4(direction, clamp(depth / map.params.x, 0.0, 1.0)));
}

float pvsCubeTexelDepth(samplerCube raw, PvsCubeMap map, PvsReceiver r, PvsTexelFrame f, vec2 t,
                        out float receiverDepth)
{
  vec3 direction = pvsCubeTexelDirection(f, t);
  receiverDepth = pvsPlaneDistance(r, direction) - r.bias;
  return texture(raw, direction).r * map.params.x;
}

// What the translucent casters let through at the texel holding t, as pvsSpotTransmitted.
float pvsCubeTransmitted(samplerCube transmit, PvsCubeMap map, PvsReceiver r, PvsTexelFrame f, vec2 t)
{
  vec3 direction = pvsCubeTexelDirection(f, t);
  vec4 stored = texture(transmit, direction);
  float depth = pvsPlaneDistance(r, direction) - r.bias;
  return depth > stored.a * map.params.x ? stored.r : 1.0;
}

float pvsCubeSearchRadius(PvsCubeMap map, PvsReceiver r)
{
  return pvsSphereSearchRadius(map.params, r);
}

float pvsCubePenumbraRadius(PvsCubeMap map, PvsReceiver r, float blocker)
{
  return pvsSpherePenumbraRadius(map.params, r, blocker);
}
