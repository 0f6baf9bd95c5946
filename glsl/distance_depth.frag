//VTK::System::Dec
// Depth-cube pass, fragment stage: the depth written is the distance to the
// light divided by `far`, linear in distance, so the map has the same
// precision at every range and the lookup needs no projection.

in vec3 lightToPoint;
uniform float invFar;

void main()
{
  gl_FragDepth = clamp(length(lightToPoint) * invFar, 0.0, 1.0);
}
