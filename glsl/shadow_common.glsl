// Shared by every shadow lookup added to a receiver's fragment shader.
//
// A lookup returns how much of a light reaches the surface point: 1 lit,
// 0 in shadow, and 0 where the visible side of the surface faces away from
// the light. Every kind of map (cube, spot, sun) first turns the fragment
// into a PvsReceiver in its light's space, then compares taps around it.

// Cosine of incidence below which a surface counts as facing away (as
// pvshadows.reference.MIN_INCIDENCE): a light in a surface's plane does not light it.
const float PVS_MIN_INCIDENCE = 1e-4;

struct PvsReceiver
{
  vec3 q;        // lookup point in light space, moved along the normal
  vec3 n;        // geometric normal in light space, on the light's side
  float texel;   // world size of one texel of the map at the point
  float bias;    // depth bias in world units
  float lit;     // 0 when the visible side faces away from the light
};

// A map's texel grid around a receiver. Texel positions t count texels on
// the map (texel k spans [k, k + 1), its centre at k + 0.5) and map back to
// light space as origin + t.x * du + t.y * dv: a direction from the light for
// cube and spot maps (on the plane of the receiver's cube face or of the
// spot's map), a point across the light for sun maps. Every compare reads
// one texel at its centre and tests the receiver's tangent plane along the
// ray through that same centre, so a flat receiver meets exactly the depth
// its own rasterisation stored, with no offset, at any incidence.
struct PvsTexelFrame
{
  vec2 at;       // the receiver's own texel position
  float size;    // texels per side of the map (face)
  vec3 origin;
  vec3 du;
  vec3 dv;
};

// Centre of the texel holding texel position t.
vec2 pvsTexelCentre(vec2 t)
{
  return floor(t) + 0.5;
}

// Build a receiver from a point `p` and normal `n` in light space.
// toLight: unit vector from the point towards the light.
// bias: x normal offset, y constant bias, z slope bias, all in texels.
PvsReceiver pvsReceiver(vec3 p, vec3 n, vec3 toLight, float texel, vec3 bias)
{
  PvsReceiver r;
  float cosTheta = dot(n, toLight);
  r.lit = cosTheta > PVS_MIN_INCIDENCE ? 1.0 : 0.0;
  cosTheta = max(cosTheta, PVS_MIN_INCIDENCE);
  float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
  r.n = n;
  r.texel = texel;
  r.q = p + n * (texel * bias.x * sinTheta);
  r.bias = texel * (bias.y + bias.z * min(sinTheta / cosTheta, 10.0));
  return r;
}

// Unit vectors across an axis (for taps around a light direction).
void pvsAcross(vec3 axis, out vec3 u, out vec3 v)
{
  u = normalize(cross(axis, abs(axis.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0)));
  v = cross(axis, u);
}

// Distance from the light (at the origin) to the receiver's tangent plane along
// `direction`, so that every tap compares against the receiver's own surface.
float pvsPlaneDistance(PvsReceiver r, vec3 direction)
{
  float dist = length(r.q);
  float along = dot(direction, r.n);
  return along < -1e-3 ? clamp(dot(r.q, r.n) / along, 0.5 * dist, 2.0 * dist) : dist;
}

// Receiver of a point or spot light in world axes centred on the light.
// params.y: texel size per unit distance; cone: xyz axis, w cosine of the cone
// (-2 where there is no cone). Outside the cone the light does not reach.
PvsReceiver pvsPositionalReceiver(mat4 viewToLight, vec4 params, vec4 cone, vec3 bias,
                                  vec3 posVC, vec3 normalVC)
{
  vec3 p = (viewToLight * vec4(posVC, 1.0)).xyz;
  float dist = max(length(p), 1e-30);
  PvsReceiver r = pvsReceiver(p, normalize(mat3(viewToLight) * normalVC), -p / dist,
                              dist * params.y, bias);
  if (dot(p / dist, cone.xyz) < cone.w)
  {
    r.lit = 0.0;
  }
  return r;
}

// Direction from a point light to a tap `offset` texels across the lookup direction.
vec3 pvsTapDirection(PvsReceiver r, vec2 offset)
{
  vec3 u, v;
  pvsAcross(normalize(r.q), u, v);
  return normalize(r.q + (offset.x * u + offset.y * v) * r.texel);
}

// PCSS radii in texels for a spherical light of radius params.z whose nearest
// caster is params.w away: the cone from the point to the light's disk, seen
// from the light's centre (blocker search), and the penumbra it casts.
float pvsSphereSearchRadius(vec4 params, PvsReceiver r)
{
  float d = length(r.q);
  float nearest = clamp(params.w, 1e-3 * d, d);
  return params.z * (d - nearest) / (nearest * r.texel);
}

float pvsSpherePenumbraRadius(vec4 params, PvsReceiver r, float blocker)
{
  return params.z * (length(r.q) - blocker) / (max(blocker, 1e-30) * r.texel);
}

// The i-th offset of the jittered disk (unit radius) for this pixel, from the
// 3D offset texture: (x, y) = pixel modulo its size, z = sample pair. The first
// eight offsets are the outer ring, one per sector, for the early exit.
vec2 pvsDiskOffset(sampler3D offsets, int i)
{
  ivec3 size = textureSize(offsets, 0);
  ivec2 cell = ivec2(mod(gl_FragCoord.xy, vec2(size.xy)));
  vec4 pair = texelFetch(offsets, ivec3(cell, i / 2), 0);
  return (i % 2 == 0) ? pair.xy : pair.zw;
}
