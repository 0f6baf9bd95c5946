#version 150
// Shadow volumes: one colour for every fragment. The depth and stencil passes
// write no colour at all; the mask pass writes 0 (in shadow) where the stencil
// count is not zero; the debug overlay draws the volumes translucent.

uniform vec4 colour;
out vec4 fragOutput0;

void main()
{
  fragOutput0 = colour;
}
