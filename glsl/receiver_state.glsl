// Added to a receiver's fragment shader before main(), which every variant
// VTK builds has: the values the other edits share live here (with each
// shadowed light's pvsVisibility<i>, 1 until its diffuse or radiance hook
// sets it), so that each edit compiles on its own, whichever of the others
// found its place in the variant VTK generated (lines and points lack some of
// a surface's code).

// The visibility the probe shows (pvsProbeLight picks the light).
float pvsProbe = 0.0;

// The facet normal from screen-space derivatives, set at the top of main()
// where the variant computes its view position; zero (the shading normal
// stands in, see pvsGeometricNormal) where it does not.
vec3 pvsFacetVC = vec3(0.0);

// Each shadowed light's visibility and the share of its light a receiver
// keeps (1 - strength * (1 - visibility)): 1 until its diffuse or radiance
// hook sets them. The receiver defines PVS_LIGHTS(EACH) as
// EACH(pvsVisibility<i>, pvsKept<i>) for every light it shows.
#define PVS_LIGHT_STATE(visibility, kept) float visibility = 1.0; float kept = 1.0;
PVS_LIGHTS(PVS_LIGHT_STATE)
#undef PVS_LIGHT_STATE
#undef PVS_LIGHTS

// The facet normal in view coordinates from screen-space derivatives of the
// view position; the top of main() stores it in pvsFacetVC.
vec3 pvsFacetNormal(vec3 positionVC)
{
  return cross(dFdx(positionVC), dFdy(positionVC));
}

// The share of a shadowed light's diffuse and specular terms a receiver keeps:
// 1 - strength * (1 - visibility). In a probe frame of this light
// (pvsProbeLight == light) the visibility is what the frame shows.
float pvsKeptShare(float visibility, int light, float strength)
{
  if (pvsProbeLight == light) { pvsProbe = visibility; }
  return 1.0 - strength * (1.0 - visibility);
}
