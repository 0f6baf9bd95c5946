#version 150
// Planar shadows: every flattened caster writes "in shadow" (0) into the
// light's mask, which was cleared to "lit" (1). Writing the same value
// however many triangles cover a pixel keeps the shadow the same darkness
// where flattened casters overlap.

out vec4 fragOutput0;

void main()
{
  fragOutput0 = vec4(0.0);
}
