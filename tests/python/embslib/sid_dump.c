/* Loads a .SID_FEM file with EMBSlib's own reader (ReadSID_C.h, not part of this repository:
   tests/export_sid.rs compiles this file against the folder named by FLEXBODY_EMBSLIB_INCLUDE)
   and prints what the reader holds as one JSON document: the mass, every body Taylor term
   (m0 row-major nrow x ncol, m1 as [row][mode][col]) and every node's origin, phi, psi, AP. */
#include "ReadSID_C.h"

static void dump_taylor(const char *name, taylor t, int first) {
  printf("%s\"%s\": {\"nrow\": %d, \"ncol\": %d, \"nq\": %d, \"structure\": %d, \"m0\": [",
         first ? "" : ", ", name, t.nrow, t.ncol, t.nq, t.structure);
  for (int i = 0; i < t.nrow * t.ncol; i++) printf("%s%.17g", i ? ", " : "", t.M0[i]);
  printf("], \"m1\": [");
  int k = 0;
  for (int r = 1; r <= t.nrow; r++)
    for (int q = 1; q <= t.nq; q++)
      for (int c = 1; c <= t.ncol; c++)
        printf("%s%.17g", k++ ? ", " : "", t.M1[matrix3Index(r, q, c, t.nrow, t.nq, t.ncol)]);
  printf("]}");
}

int main(int argc, char **argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: sid_dump FILE.SID_FEM\n");
    return 2;
  }
  SID_Data *s = (SID_Data *)SIDFileConstructor_C(argv[1]);
  static const char *terms[] = {"mdCM", "J",  "Ct",     "Cr", "Me", "Gr",
                                "Ge",   "Oe", "ksigma", "Ke", "De"};
  printf("{\"nodes_count\": %d, \"modes\": %d, \"mass\": %.17g, \"terms\": {", s->numNodes,
         s->numModes, s->mass);
  for (int i = 0; i < 11; i++) dump_taylor(terms[i], getTaylorByName(s, terms[i]), i == 0);
  printf("}, \"frames\": [");
  for (int n = 0; n < s->numNodes; n++) {
    printf("%s{\"id\": %d, \"terms\": {", n ? ", " : "", s->nodes[n].id);
    dump_taylor("origin", s->nodes[n].orig, 1);
    dump_taylor("phi", s->nodes[n].phi, 0);
    dump_taylor("psi", s->nodes[n].psi, 0);
    dump_taylor("AP", s->nodes[n].AP, 0);
    printf("}}");
  }
  printf("]}\n");
  return 0;
}
