#version 150
// Depth-cube pass, vertex stage. Positions arrive in the caster's model
// coordinates (shifted to its centre); `modelToLight` takes them to world
// axes with the light at the origin, computed in double precision on the CPU.

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

#ifdef SIX_PASSES
uniform mat4 faceProjection;   // 90-degree projection times this face's rotation
out vec3 lightToPoint;
#else
out vec3 lightToPointVS;
#endif

void main()
{
  vec4 p = modelToLight * vec4(position, 1.0);
  vec3 fromLight = p.xyz / p.w;
#ifdef SIX_PASSES
  lightToPoint = fromLight;
  gl_Position = faceProjection * vec4(fromLight, 1.0);
#else
  lightToPointVS = fromLight;
  gl_Position = vec4(fromLight, 1.0);
#endif
}
