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

in vec3 position;
uniform mat4 modelToClip;
uniform vec4 planeModel;
uniform vec4 flatW;

void main()
{
  vec4 p = vec4(position, 1.0);
  gl_Position = modelToClip * p;
  gl_ClipDistance[0] = dot(planeModel, p);
  gl_ClipDistance[1] = dot(flatW, p);
}
