#version 150
// Planar shadows: a caster's triangles flattened onto the receiving plane
// along the lines to the light, drawn with the camera's projection into the
// light's screen-space mask.
//
// `modelToClip` is camera projection * view * flattening * model, composed
// in double precision on the CPU around the caster's centre. The flattened
// point is kept homogeneous (no division by its w), so its clip position is
// a linear function of the caster's point and clipping by the two distances
// below cuts the flattened triangle exactly where the caster's triangle
// would be cut:
//   0: the caster's signed distance to the plane, positive on the light's
//      side: only what lies above the plane casts;
//   1: the flattened point's w, negative beyond a positional light (whose
//      line to the point meets the plane on the far side of the light):
//      no anti-shadows in the mask (the camera's clipping already keeps
//      them off the plane's own pixels).

//
// The pass draws through pvshadows.gl.caster_draws, as the map passes do, so
// its matrix carries the name every caster draw sets (the "light" is the
// camera here); `lightThrough.x` is the share of light one of the caster's
// surfaces lets through, handed to the fragment stage.

in vec3 position;
#ifdef BATCHED
// Many casters in one draw (pvshadows.gl.caster_batch): each vertex carries its
// caster's row, and the pass sets the uniforms of BATCHED rows from rowBase.
in int casterRow;
uniform mat4 modelToLights[BATCHED];
uniform vec4 planeModels[BATCHED];
uniform vec4 flatWs[BATCHED];
uniform vec4 lightThroughs[BATCHED];
uniform int rowBase;
#define modelToClip modelToLights[casterRow - rowBase]
#define planeModel planeModels[casterRow - rowBase]
#define flatW flatWs[casterRow - rowBase]
#define lightThrough lightThroughs[casterRow - rowBase]
#else
uniform mat4 modelToLight;
uniform vec4 planeModel;
uniform vec4 flatW;
uniform vec4 lightThrough;
#define modelToClip modelToLight
#endif
flat out float transmittance;

void main()
{
  vec4 p = vec4(position, 1.0);
  transmittance = lightThrough.x;
  gl_Position = modelToClip * p;
  gl_ClipDistance[0] = dot(planeModel, p);
  gl_ClipDistance[1] = dot(flatW, p);
}
