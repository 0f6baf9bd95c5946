#version 150
// 2D shadow-map pass, vertex stage. Positions arrive in the caster's model
// coordinates (shifted to its centre); `modelToLight` takes them to the
// light's space and `lightToClip` projects them onto the map (perspective for
// a spot light, orthographic for a directional one). Both are composed in
// double precision on the CPU.

in vec3 position;
#ifdef BATCHED
// Many casters in one draw (pvshadows.gl.caster_batch): each vertex carries its
// caster's row, and the pass sets the matrices of BATCHED rows from rowBase.
in int casterRow;
uniform mat4 modelToLights[BATCHED];
uniform int rowBase;
#define modelToLight modelToLights[casterRow - rowBase]
#else
uniform mat4 modelToLight;
#endif
uniform mat4 lightToClip;
out vec3 lightToPoint;

void main()
{
  vec4 p = modelToLight * vec4(position, 1.0);
  lightToPoint = p.xyz / p.w;
  gl_Position = lightToClip * vec4(lightToPoint, 1.0);
}
