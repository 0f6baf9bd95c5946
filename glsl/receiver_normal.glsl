// Added to a receiver's fragment shader before any shadow lookup: the normal
// the lookups offset along. The facet normal from screen-space derivatives is
// the true geometric normal of the triangle; where it degenerates (a pixel
// seeing the triangle edge-on, or derivatives whose square underflows or
// overflows) the interpolated shading normal stands in.

vec3 pvsGeometricNormal(vec3 facet, vec3 shadingNormal)
{
  float size = dot(facet, facet);
  return size > 0.0 && !isinf(size) ? normalize(facet) : shadingNormal;
}
