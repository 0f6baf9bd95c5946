#version 150
// Shadow-map pass, fragment stage. The depth written is linear: the distance
// to the light over `far` (cube and spot maps), or with DEPTH_ALONG_Z the
// depth along a directional light from the map's near plane over the depth
// range. The map then has the same precision at every range and the lookup
// needs no projection of depth.

in vec3 lightToPoint;
uniform float invFar;

void main()
{
#ifdef DEPTH_ALONG_Z
  gl_FragDepth = clamp(lightToPoint.z * invFar, 0.0, 1.0);
#else
  gl_FragDepth = clamp(length(lightToPoint) * invFar, 0.0, 1.0);
#endif
}
