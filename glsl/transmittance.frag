#version 150
// Transmittance pass of a shadow map, fragment stage: only the translucent
// casters are drawn, both sides, into a colour target cleared to 1, with
// blending multiplying the colour (each surface over a texel lets
// `transmittance` = 1 - opacity of the light through) and keeping the
// smallest alpha (the nearest translucent surface's depth, linear as in
// distance_depth.frag: the distance to the light over `far`, or with
// DEPTH_ALONG_Z the depth along a directional light over the depth range).

in vec3 lightToPoint;
uniform float invFar;
uniform float transmittance;

out vec4 fragOutput0;

void main()
{
#ifdef DEPTH_ALONG_Z
  float depth = clamp(lightToPoint.z * invFar, 0.0, 1.0);
#else
  float depth = clamp(length(lightToPoint) * invFar, 0.0, 1.0);
#endif
  fragOutput0 = vec4(vec3(transmittance), depth);
}
