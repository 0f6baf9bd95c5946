#version 150
// Shadow volumes extruded on the GPU (extrude="gpu"), geometry stage.
//
// Input: GL_TRIANGLES_ADJACENCY from pvshadows' own index buffer (built with
// pvshadows.silhouette.adjacency_indices): corners 0, 2, 4 are the triangle,
// 1, 3, 5 the far corners of the neighbours across edges 0-2, 2-4 and 4-0.
// VTK's mapper draws plain triangles; the volumes are drawn by pvshadows, so
// the adjacency comes from that index buffer, not from VTK's.
//
// A triangle facing the light emits, for every edge whose neighbour faces
// away (a silhouette edge), a quad from the edge to infinity (w = 0) away
// from the light; with caps (z-fail) also itself as the light cap and itself
// projected to infinity, wound the other way, as the dark cap. Every face is
// wound outward, so a stencil counts +1 when entering a volume.
//
// Whether a face faces the light is decided from its smallest-index corner,
// with `precise` arithmetic, so the two triangles of an edge always agree on
// each other's facing and the silhouette has no cracks or double quads.
// `precise` comes with ARB_gpu_shader5 (core in GL 4.0); a driver without it
// compiles the same arithmetic without it, where in rare near-grazing cases
// the two faces of an edge may disagree on their facing.

#extension GL_ARB_gpu_shader5 : enable
#ifdef GL_ARB_gpu_shader5
#define PVS_PRECISE precise
#else
#define PVS_PRECISE
#endif

layout(triangles_adjacency) in;
layout(triangle_strip, max_vertices = 18) out;

in vec3 modelPosition[];
flat in int vertexIndex[];

#ifdef BATCHED
// Many casters' volumes in one draw (pvshadows.gl.volume_batch): the pass sets
// the uniforms of BATCHED rows from rowBase, and main() reads its caster's row
// into the names the one-by-one draw sets as uniforms.
flat in int vertexRow[];
uniform mat4 modelToClips[BATCHED];
uniform vec4 lightModels[BATCHED];
uniform float extrudeTos[BATCHED];
uniform int rowBase;
mat4 modelToClip;
vec4 lightModel;
float extrudeTo;
#else
uniform mat4 modelToClip;
// (x, y, z, 1): a point or spot light; (x, y, z, 0): direction towards a
// directional light. Both in the caster's model frame.
uniform vec4 lightModel;
// 0: extrude to infinity (w = 0). Above 0: extrude this far (model units)
// instead, beyond every receiver, for parallel projections, which cannot
// draw points at infinity.
uniform float extrudeTo;
#endif
// 1: emit the light and dark caps (z-fail); 0: only the sides (z-pass).
uniform int caps;
// Clip-space depth offset (times w) of the light cap; see volume_homogeneous.vert.
uniform float capDepthOffset;

bool pvsFacesLight(vec3 a, vec3 b, vec3 c, int ia, int ib, int ic)
{
  if (ib < ia && ib < ic)
  {
    vec3 t = a; a = b; b = c; c = t;
  }
  else if (ic < ia && ic < ib)
  {
    vec3 t = c; c = b; b = a; a = t;
  }
  if (all(equal(a, b)) || all(equal(b, c)) || all(equal(c, a)))
  {
    return false;  // zero area, e.g. the walls of a two-sided sheet
  }
  PVS_PRECISE vec3 normal = cross(b - a, c - a);
  PVS_PRECISE vec3 toLight = lightModel.xyz - lightModel.w * a;
  PVS_PRECISE float facing = dot(normal, toLight);
  return facing > 0.0;
}

vec4 pvsAtInfinity(vec3 p)
{
  vec3 away = lightModel.w * p - lightModel.xyz;
  if (extrudeTo > 0.0)
  {
    return modelToClip * vec4(p + away * (extrudeTo / length(away)), 1.0);
  }
  return modelToClip * vec4(away, 0.0);
}

void main()
{
#ifdef BATCHED
  int row = vertexRow[0] - rowBase;
  modelToClip = modelToClips[row];
  lightModel = lightModels[row];
  extrudeTo = extrudeTos[row];
#endif
  if (!pvsFacesLight(modelPosition[0], modelPosition[2], modelPosition[4],
                     vertexIndex[0], vertexIndex[2], vertexIndex[4]))
  {
    return;
  }
  if (caps == 1)
  {
    for (int k = 0; k < 6; k += 2)
    {
      vec4 clip = modelToClip * vec4(modelPosition[k], 1.0);
      clip.z += capDepthOffset * clip.w;
      gl_Position = clip;
      EmitVertex();
    }
    EndPrimitive();
    gl_Position = pvsAtInfinity(modelPosition[0]);
    EmitVertex();
    gl_Position = pvsAtInfinity(modelPosition[4]);
    EmitVertex();
    gl_Position = pvsAtInfinity(modelPosition[2]);
    EmitVertex();
    EndPrimitive();
  }
  for (int edge = 0; edge < 3; ++edge)
  {
    int v0 = 2 * edge;
    int across = v0 + 1;
    int v1 = (v0 + 2) % 6;
    // The neighbour, in its own winding, is (v1, v0, across).
    if (!pvsFacesLight(modelPosition[v1], modelPosition[v0], modelPosition[across],
                       vertexIndex[v1], vertexIndex[v0], vertexIndex[across]))
    {
      gl_Position = modelToClip * vec4(modelPosition[v0], 1.0);
      EmitVertex();
      gl_Position = pvsAtInfinity(modelPosition[v0]);
      EmitVertex();
      gl_Position = modelToClip * vec4(modelPosition[v1], 1.0);
      EmitVertex();
      gl_Position = pvsAtInfinity(modelPosition[v1]);
      EmitVertex();
      EndPrimitive();
    }
  }
}
