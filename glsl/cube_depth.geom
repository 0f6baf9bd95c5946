#version 150
// Depth-cube pass, geometry stage: one draw fills all six faces. Each
// triangle is sent to every face whose frustum it can touch, on the layer
// (gl_Layer) of that face; faces left out of `faceMask` hold no caster and
// are not drawn at all. The cube is cube `layerBase / 6` of a cube map array
// (0 for a cube of its own).

layout(triangles) in;
layout(triangle_strip, max_vertices = 18) out;

in vec3 lightToPointVS[];
out vec3 lightToPoint;

uniform mat4 faceProjection[6];
uniform int faceMask;
uniform int layerBase;

bool outsideFrustum(vec4 a, vec4 b, vec4 c)
{
  return (a.x < -a.w && b.x < -b.w && c.x < -c.w) || (a.x > a.w && b.x > b.w && c.x > c.w)
      || (a.y < -a.w && b.y < -b.w && c.y < -c.w) || (a.y > a.w && b.y > b.w && c.y > c.w)
      || (a.w <= 0.0 && b.w <= 0.0 && c.w <= 0.0);
}

void main()
{
  for (int face = 0; face < 6; ++face)
  {
    if ((faceMask & (1 << face)) == 0)
    {
      continue;
    }
    vec4 clip[3];
    for (int i = 0; i < 3; ++i)
    {
      clip[i] = faceProjection[face] * vec4(lightToPointVS[i], 1.0);
    }
    if (outsideFrustum(clip[0], clip[1], clip[2]))
    {
      continue;
    }
    for (int i = 0; i < 3; ++i)
    {
      gl_Layer = layerBase + face;
      lightToPoint = lightToPointVS[i];
      gl_Position = clip[i];
      EmitVertex();
    }
    EndPrimitive();
  }
}
