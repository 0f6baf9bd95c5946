#version 150
// Planar shadows: every flattened caster writes the share of light one of its
// surfaces lets through (1 - opacity; 0 for an opaque caster) into the
// light's mask, which was cleared to "lit" (1), blended multiplicatively. A
// shadow ray through a closed caster crosses two of its surfaces, and its
// flattened image covers each pixel twice, so the mask holds what the ray
// brings; where opaque casters overlap the shadow stays exactly 0.

flat in float transmittance;

out vec4 fragOutput0;

void main()
{
  fragOutput0 = vec4(transmittance);
}
