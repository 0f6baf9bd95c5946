#version 150
// Shadow volumes, depth pre-pass: every visible actor's triangles with the
// camera's projection, so the stencil pass can tell which parts of each
// volume lie in front of or behind the surface seen in each pixel.
// Each model-to-clip matrix is composed in double precision on the CPU,
// relative to the actor's centre, so large offsets cancel before the float32
// upload. The pass draws through pvshadows.gl.caster_draws, as the map passes
// do, so its matrices carry their uniform names: here the "light" is the camera.

in vec3 position;
#ifdef BATCHED
// Many actors in one draw (pvshadows.gl.caster_batch): each vertex carries its
// caster's row, and the pass sets the matrices of BATCHED rows from rowBase.
in int casterRow;
uniform mat4 modelToLights[BATCHED];
uniform int rowBase;
#define modelToClip modelToLights[casterRow - rowBase]
#else
uniform mat4 modelToLight;
#define modelToClip modelToLight
#endif

void main()
{
  gl_Position = modelToClip * vec4(position, 1.0);
}
