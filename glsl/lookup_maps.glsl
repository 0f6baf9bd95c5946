// pvsLookupMaps: every group of map lookups (shadow_group.glsl) in turn, each
// setting its lights' visibilities. Before this file the receiver defines
//
//   PVS_LOOKUP_GROUPS(EACH)   EACH(pvsCubePcfLookup) EACH(pvsSunHardLookup) ...:
//                             the lookup function of every group

#define PVS_LOOKUP_ONE(lookup) lookup(posVC, normalVC);

void pvsLookupMaps(vec3 posVC, vec3 normalVC)
{
  PVS_LOOKUP_GROUPS(PVS_LOOKUP_ONE)
}

#undef PVS_LOOKUP_ONE
