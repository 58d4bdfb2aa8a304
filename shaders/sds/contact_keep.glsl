// The contact lists' append (contact_list.glsl, contact_self.glsl): cell c's
// entries after its first n_in; a count past lcap is only counted (the host
// grows the lists and builds again).
#ifndef SDS_CONTACT_KEEP_GLSL
#define SDS_CONTACT_KEEP_GLSL
uint n_in = 0u; // candidates found (may exceed the list's capacity: the host grows it and builds again)
void keep(uint c, uint entry) {
  if (n_in < pc.lcap) list[pc.lbase + c * pc.lcap + n_in] = entry;
  n_in++;
}

#endif
