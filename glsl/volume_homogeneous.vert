#version 150
// Shadow volumes built on the CPU (extrude="cpu"): positions are homogeneous,
// w = 1 on the caster and w = 0 at infinity, in the caster's model frame.
// The light cap is drawn with a tiny clip-space depth offset (`capDepthOffset`,
// times w) so that it loses the depth test against the lit surface it lies on;
// x and y are untouched, so the volume stays watertight on screen.

in vec4 position;
uniform mat4 modelToClip;
uniform float capDepthOffset;

void main()
{
  vec4 clip = modelToClip * position;
  clip.z += capDepthOffset * clip.w;
  gl_Position = clip;
}
