/* Compiled as a file of host/sds (tests/CMakeLists.txt, layers_private_header):
 * sds's own private header is found, mesh's is not, so this must fail on the
 * second line and only there. */
#include "sds/sds_internal.h"
#include "mesh/mesh_internal.h"
