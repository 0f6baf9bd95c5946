#version 150
// 2D shadow-map pass, vertex stage. Positions arrive in the caster's model
// coordinates (shifted to its centre); `modelToLight` takes them to the
// light's space and `lightToClip` projects them onto the map (perspective for
// a spot light, orthographic for a directional one). Both are composed in
// double precision on the CPU.

in vec3 position;
uniform mat4 modelToLight;
uniform mat4 lightToClip;
out vec3 lightToPoint;

void main()
{
  vec4 p = modelToLight * vec4(position, 1.0);
  lightToPoint = p.xyz / p.w;
  gl_Position = lightToClip * vec4(lightToPoint, 1.0);
}
