/* Stand-in for Modelica's ModelicaUtilities.h so that EMBSlib's SID reader
   (EMBSlib/Resources/Include/ReadSID_C.h, github.com/vwaurich/EMBS_ModelicaLib, MIT) compiles
   outside a Modelica tool: messages go to stderr. The index helpers are declared here because
   the reader uses them before it defines them. Used only by tests/export_sid.rs. */
#include <stdarg.h>
#include <stdio.h>
static void ModelicaFormatMessage(const char *format, ...) {
  va_list args;
  va_start(args, format);
  vfprintf(stderr, format, args);
  va_end(args);
}
int matrix2Index(int r, int c, int numR, int numC);
int matrix3Index(int r, int q, int c, int numR, int numQ, int numC);
