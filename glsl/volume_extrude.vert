#version 150
// Shadow volumes extruded on the GPU (extrude="gpu"), vertex stage: hands the
// model-space position and the vertex's index to the geometry shader, which
// needs the index to test each face from the same corner in every invocation.

in vec3 position;
out vec3 modelPosition;
flat out int vertexIndex;
#ifdef BATCHED
// Many casters' volumes in one draw (pvshadows.gl.volume_batch): each vertex
// carries its caster's row, passed on for the geometry stage to read its uniforms.
in int casterRow;
flat out int vertexRow;
#endif

void main()
{
  modelPosition = position;
  vertexIndex = gl_VertexID;
#ifdef BATCHED
  vertexRow = casterRow;
#endif
  gl_Position = vec4(position, 1.0);
}
