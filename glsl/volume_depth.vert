#version 150
// Shadow volumes, depth pre-pass: every visible actor's triangles with the
// camera's projection, so the stencil pass can tell which parts of each
// volume lie in front of or behind the surface seen in each pixel.
// `modelToClip` is composed in double precision on the CPU, relative to the
// actor's centre, so large offsets cancel before the float32 upload.

in vec3 position;
uniform mat4 modelToClip;

void main()
{
  gl_Position = modelToClip * vec4(position, 1.0);
}
